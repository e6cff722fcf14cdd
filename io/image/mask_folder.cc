#include "io/image/mask_folder.h"

#include <opencv2/imgproc.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"

namespace comic::io {

MaskFolder MaskFolder::Open(const std::string& folder) {
  MaskFolder masks;
  masks.folder_ = folder;
  for (const std::string& name : ListFiles(folder)) {
    if (IsImageExtension(FileExtension(name))) masks.names_.push_back(name);
  }
  COMIC_CHECK(!masks.names_.empty(), kInvalidArgument, folder << ": mask folder holds no images");
  return masks;
}

void MaskFolder::CheckCount(size_t num_source_frames) const {
  COMIC_CHECK(names_.size() == num_source_frames, kInvalidData,
              folder_ << ": " << names_.size() << " masks for " << num_source_frames
                      << " frames (need one mask per frame)");
}

cv::Mat MaskFolder::Read(size_t index, const cv::Size& expected_size) const {
  COMIC_CHECK(index < names_.size(), kInvalidArgument,
              folder_ << ": mask " << index << " requested, folder holds " << names_.size());
  const std::string path = JoinPaths(folder_, names_[index]);
  const cv::Mat raw = ReadImageUnchanged(path);
  COMIC_CHECK(expected_size.empty() || raw.size() == expected_size, kInvalidData,
              path << ": mask is " << raw.cols << "x" << raw.rows << " but the frames are "
                   << expected_size.width << "x" << expected_size.height);
  cv::Mat any_channel;
  if (raw.channels() == 1) {
    any_channel = raw;
  } else {
    std::vector<cv::Mat> channels;
    cv::split(raw, channels);
    any_channel = channels[0] != 0;
    for (size_t c = 1; c < channels.size() && c < 3; ++c) any_channel |= channels[c] != 0;
  }
  cv::Mat mask = any_channel != 0;  // CV_8UC1, 255 where non-zero
  return mask;
}

}  // namespace comic::io
