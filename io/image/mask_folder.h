// A folder of per-frame object masks (DAVIS `Annotations/480p/<sequence>/00000.png` ..): one image
// per source frame, naturally sorted, so mask k belongs to source frame k.
//
//   auto masks = comic::io::MaskFolder::Open("davis/Annotations/480p/car-shadow");
//   masks.CheckCount(sequence_frame_count);
//   cv::Mat mask = masks.Read(0, sequence.SourceFrameSize());  // CV_8UC1, 255 = object
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace comic::io {

class MaskFolder {
 public:
  // Lists the images in `folder` (same extensions as ImageSequence). Throws comic::Error:
  // kNotFound for a missing folder, kInvalidArgument for a path that is not a folder or a folder
  // without images.
  static MaskFolder Open(const std::string& folder);

  const std::string& folder() const { return folder_; }
  size_t NumMasks() const { return names_.size(); }
  const std::vector<std::string>& Names() const { return names_; }

  // Throws comic::Error(kInvalidData) naming the folder unless it holds exactly
  // `num_source_frames` masks (one per frame of the sequence as stored).
  void CheckCount(size_t num_source_frames) const;

  // Reads mask `index` as CV_8UC1 with 255 = object (any non-zero value of any channel) and
  // 0 = background. Throws comic::Error: kInvalidArgument for an index out of range, kInvalidData
  // naming the file if it is corrupt or its size differs from `expected_size` (the size of the
  // frames as stored; pass an empty size to skip the check).
  cv::Mat Read(size_t index, const cv::Size& expected_size) const;

 private:
  std::string folder_;
  std::vector<std::string> names_;
};

}  // namespace comic::io
