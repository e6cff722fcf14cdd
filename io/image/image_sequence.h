// A sequence of frames from a folder of images or a video file, as 8-bit grey plus colour.
//
//   comic::io::ImageSequenceOptions options;
//   options.resize_height = 700;
//   auto sequence = comic::io::ImageSequence::Open("examples/data/kitti06/image_l", options);
//   for (size_t i = 0; i < sequence.NumFrames(); ++i) {
//     comic::io::Frame frame = sequence.ReadFrame(i);  // frame.gray, frame.color
//   }
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/core/pixel_budget.h"

namespace comic::io {

struct ImageSequenceOptions {
  // Resize every frame to this height in pixels, keeping the aspect ratio (0 = original size).
  int resize_height = 0;
  // First source frame to use (0-based index in the naturally sorted folder or in the video).
  int first_frame = 0;
  // Last source frame to use, inclusive (-1 = up to the end).
  int last_frame = -1;
  // Use every `stride`-th frame from first_frame on.
  int stride = 1;
  // A video whose frames stop decoding before the end its header announces is an error naming
  // the last good frame; true uses the frames before the break and sets ImageSequence::warning().
  bool allow_truncated = false;
  // Frames with more pixels than this after resizing are refused before any is resized
  // (io/core/pixel_budget.h).
  int64_t max_pixels = kDefaultMaxPixels;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct Frame {
  int source_index = -1;  // index in the folder's sorted file list or the video's frame number
  std::string name;       // file name relative to the folder, or "frame_000123.png" for a video
  cv::Mat gray;           // CV_8UC1
  cv::Mat color;          // CV_8UC3 BGR (grey sources replicated)
};

class ImageSequence {
 public:
  // Opens a folder of images (png/jpg/jpeg/ppm/pgm/pnm/pbm/tif/tiff/bmp, naturally sorted so
  // frame_2 < frame_10; other files are ignored; entries named as images that are not regular
  // files, such as FIFOs and dangling symlinks, are skipped and counted in warning()), a single
  // image, or a video file (anything else, read with cv::VideoCapture). Reads the first frame to
  // validate the source, and every other frame's header (size and pixel budget); a video's
  // declared frame size is held to the budget before any frame is decoded.
  // Throws comic::Error naming the path and the problem: missing path (kNotFound), folder
  // without images or a range selecting no frame (kInvalidArgument), corrupt first image or
  // video that cannot be opened, frames lower or narrower than kMinResizeHeight (kInvalidData).
  static ImageSequence Open(const std::string& path, const ImageSequenceOptions& options = {});

  ImageSequence(ImageSequence&&) noexcept;
  ImageSequence& operator=(ImageSequence&&) noexcept;
  ~ImageSequence();

  const std::string& path() const { return path_; }
  // Non-empty when the source was accepted with a problem the user should hear about (a truncated
  // video opened with allow_truncated: how many frames are used; entries of a folder skipped).
  // Apps print it as one line.
  const std::string& warning() const { return warning_; }
  bool IsVideo() const { return is_video_; }
  // A video's frame rate as its container declares it (frames per second); 0 when unknown or for
  // a folder of images.
  double Fps() const { return fps_; }
  size_t NumFrames() const { return source_indices_.size(); }
  // Size of every frame after resizing (that of the first frame; others must match).
  cv::Size FrameSize() const { return frame_size_; }
  // Size of the frames as stored, before resizing.
  cv::Size SourceFrameSize() const { return source_size_; }
  // Names of the selected frames, in order (file names, or "frame_%06d.png" for videos:
  // the files io/image/frame_export.h writes).
  const std::vector<std::string>& FrameNames() const { return names_; }
  // Absolute or as-given path of frame i's file (folders only; empty for videos).
  std::string FramePath(size_t i) const;

  // Reads the i-th selected frame. Throws comic::Error(kInvalidData) naming the file if it is
  // corrupt or its size differs from the first frame's, kInvalidArgument if i is out of range.
  Frame ReadFrame(size_t i) const;

  // Reads all selected frames in order.
  std::vector<Frame> ReadAll() const;

 private:
  ImageSequence() = default;
  // The i-th selected frame as stored; `what` names it in error messages.
  cv::Mat ReadRaw(size_t i, std::string* what) const;
  cv::Mat ReadImageRaw(size_t i, std::string* what) const;
  cv::Mat ReadVideoRaw(size_t i, std::string* what) const;
  Frame MakeFrame(const cv::Mat& raw, size_t i, const std::string& what) const;
  // Every selected frame's header (folders): a frame declaring more pixels than the budget, or
  // another size than the first frame's, is refused at Open(), before any work (issue 29).
  void CheckFrameHeaders() const;

  std::string path_;
  std::string warning_;
  ImageSequenceOptions options_;
  bool is_video_ = false;
  double fps_ = 0.0;
  std::string folder_;               // folder holding the image files
  std::vector<std::string> names_;   // selected frame names
  std::vector<int> source_indices_;  // selected source indices
  cv::Size frame_size_;
  cv::Size source_size_;
  struct VideoState;  // an open cv::VideoCapture and its position
  mutable std::unique_ptr<VideoState> video_;
};

}  // namespace comic::io
