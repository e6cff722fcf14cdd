#include "io/image/image_sequence.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/input_file.h"
#include "io/core/library_messages.h"
#include "io/image/image_header.h"
#include "io/image/image_io.h"

namespace comic::io {

struct ImageSequence::VideoState {
  cv::VideoCapture capture;
  int next_index = 0;  // source index of the frame the next read() returns
};

void ImageSequenceOptions::Check() const {
  CheckResizeHeight(resize_height, "resize_height");
  CheckMaxPixels(max_pixels);
  COMIC_CHECK(first_frame >= 0, kInvalidArgument, "first_frame must be >= 0, got " << first_frame);
  COMIC_CHECK(last_frame == -1 || last_frame >= first_frame, kInvalidArgument,
              "last_frame must be -1 (to the end) or >= first_frame (" << first_frame << "), got "
                                                                       << last_frame);
  COMIC_CHECK(stride >= 1, kInvalidArgument, "stride must be >= 1, got " << stride);
}

ImageSequence::ImageSequence(ImageSequence&&) noexcept = default;
ImageSequence& ImageSequence::operator=(ImageSequence&&) noexcept = default;
ImageSequence::~ImageSequence() = default;

namespace {

// The name of the PNG file `comic_sfm --write-frames` writes for the frame (issue 17): a model's
// images.txt and a COLMAP database name their images so, and COLMAP's image tools find them.
std::string VideoFrameName(int index) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "frame_%06d.png", index);
  return buffer;
}

// Source indices first, first+stride, ... up to min(last, count - 1).
std::vector<int> SelectIndices(int count, const ImageSequenceOptions& options) {
  std::vector<int> indices;
  const int last = options.last_frame < 0 ? count - 1 : std::min(options.last_frame, count - 1);
  for (int i = options.first_frame; i <= last; i += options.stride) indices.push_back(i);
  return indices;
}

// A frame stored lower or narrower than the smallest --resize-height holds no detector's window
// (resized to a height, one a pixel wide would be no pixels wide): refused naming it.
void CheckFrameNotTooSmall(const std::string& what, int64_t width, int64_t height) {
  COMIC_CHECK(width >= kMinResizeHeight && height >= kMinResizeHeight, kInvalidData,
              what << ": frames of " << width << "x" << height
                   << " pixels (as stored) are too small to reconstruct (at least "
                   << kMinResizeHeight << "x" << kMinResizeHeight << ")");
}

// A folder's images, in name order, selected by the frame range. Image-named entries that are not
// files are left out with a warning.
void ListFolderFrames(const std::string& path, const ImageSequenceOptions& options,
                      std::vector<int>& source_indices, std::vector<std::string>& names,
                      std::string& warning) {
  std::vector<std::string> images;
  std::vector<SkippedEntry> skipped;
  for (const std::string& name : ListFiles(path, &skipped)) {
    if (IsImageExtension(FileExtension(name))) images.push_back(name);
  }
  // Entries named as images that are not files (a FIFO would block the reader, a dangling
  // symlink is a frame gone missing) are left out, and said so (issue 29).
  std::vector<SkippedEntry> skipped_images;
  for (const SkippedEntry& entry : skipped) {
    if (IsImageExtension(FileExtension(entry.name))) skipped_images.push_back(entry);
  }
  if (!skipped_images.empty()) {
    warning = path + ": " + DescribeSkippedEntries(skipped_images);
  }
  COMIC_CHECK(
      !images.empty(), kInvalidArgument,
      path << ": folder holds no images (png/jpg/jpeg/ppm/pgm/pnm/pbm/tif/tiff/bmp)"
           << (skipped_images.empty() ? "" : "; " + DescribeSkippedEntries(skipped_images)));
  source_indices = SelectIndices(static_cast<int>(images.size()), options);
  COMIC_CHECK(!source_indices.empty(), kInvalidArgument,
              path << ": frame range [" << options.first_frame << ", " << options.last_frame
                   << "] selects none of its " << images.size() << " images");
  for (int index : source_indices) names.push_back(images[index]);
}

// Opens a video file for decoding: refuses streams, what FFmpeg cannot open, and a declared size
// over the pixel budget.
void OpenVideo(const std::string& path, const ImageSequenceOptions& options,
               cv::VideoCapture& capture) {
  CheckInputFile(path);
  // Counted by decoding, then decoded again: a stream cannot be read twice.
  COMIC_CHECK(IsRegularFile(path), kInvalidData,
              path << ": a video must be a regular file (it is read twice: its frames counted, "
                      "then decoded), not a stream");
  SilenceLibraryLogging();
  // FFmpeg prints what it finds wrong ("moov atom not found", "overread 8"): captured per call,
  // it becomes our one line, and tells where a damaged stream stops decoding.
  std::string message = CaptureLibraryMessages([&] {
    try {
      capture.open(path, cv::CAP_FFMPEG);
    } catch (const cv::Exception&) {
    }
  });
  COMIC_CHECK(capture.isOpened(), kInvalidData,
              path << ": cannot open as a video (unknown format, unsupported codec or corrupt"
                   << (message.empty() ? "" : "; FFmpeg: " + message) << ")");
  // The budget on the size the stream declares, before any frame is decoded.
  const double declared_width = capture.get(cv::CAP_PROP_FRAME_WIDTH);
  const double declared_height = capture.get(cv::CAP_PROP_FRAME_HEIGHT);
  if (declared_width >= 1 && declared_height >= 1 && declared_width < 1e9 &&
      declared_height < 1e9) {
    const cv::Size declared =
        ResizedSize(cv::Size(static_cast<int>(declared_width), static_cast<int>(declared_height)),
                    options.resize_height);
    CheckPixelBudget(path, declared, options.max_pixels);
  }
}

// Counts a video's frames by decoding them and selects the frame range; a stream that stops
// decoding before its header's count is refused unless allow_truncated.
void ListVideoFrames(const std::string& path, const ImageSequenceOptions& options,
                     cv::VideoCapture& capture, std::vector<int>& source_indices,
                     std::vector<std::string>& names, std::string& warning, double& fps) {
  std::string message;
  const double declared_fps = capture.get(cv::CAP_PROP_FPS);
  if (std::isfinite(declared_fps) && declared_fps > 0.0 && declared_fps < 1e6) fps = declared_fps;
  // Count frames by grabbing: CAP_PROP_FRAME_COUNT is an estimate for many containers.
  int count = 0;
  bool corrupt = false;
  while (true) {
    bool grabbed = false;
    message = CaptureLibraryMessages([&] { grabbed = capture.grab(); });
    if (MessageReportsCorruptData(message)) corrupt = true;
    if (!grabbed || corrupt) break;
    ++count;
  }
  const double announced = capture.get(cv::CAP_PROP_FRAME_COUNT);
  const int header_count = announced > 0 && announced < 1e9 ? static_cast<int>(announced) : 0;
  COMIC_CHECK(count > 0, kInvalidData,
              path << ": video has no decodable frames"
                   << (message.empty() ? "" : " (FFmpeg: " + message + ")"));
  if (corrupt || count < header_count) {
    std::ostringstream what;
    what << path << ": video stops decoding after frame " << count - 1;
    if (header_count > 0) what << " of the " << header_count << " its header announces";
    if (!message.empty()) what << " (FFmpeg: " << message << ")";
    COMIC_CHECK(
        options.allow_truncated, kInvalidData,
        what.str() << "; --allow-truncated uses the " << count << " frames before the break");
    warning = what.str() + "; using its first " + std::to_string(count) + " frames";
  }
  source_indices = SelectIndices(count, options);
  COMIC_CHECK(!source_indices.empty(), kInvalidArgument,
              path << ": frame range [" << options.first_frame << ", " << options.last_frame
                   << "] selects none of its " << count << " frames");
  for (int index : source_indices) names.push_back(VideoFrameName(index));
}

}  // namespace

ImageSequence ImageSequence::Open(const std::string& path, const ImageSequenceOptions& options) {
  options.Check();
  COMIC_CHECK(!path.empty(), kInvalidArgument, "no input path given");
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such file or folder");

  ImageSequence sequence;
  sequence.path_ = path;
  sequence.options_ = options;

  if (IsDirectory(path)) {
    sequence.folder_ = path;
    ListFolderFrames(path, options, sequence.source_indices_, sequence.names_, sequence.warning_);
  } else if (IsImageExtension(FileExtension(path))) {
    // A single image is a one-frame sequence.
    sequence.folder_ = ParentPath(path);
    sequence.source_indices_ = SelectIndices(1, options);
    COMIC_CHECK(!sequence.source_indices_.empty(), kInvalidArgument,
                path << ": frame range selects no frame of a single image");
    sequence.names_.push_back(FileName(path));
  } else {
    sequence.is_video_ = true;
    cv::VideoCapture capture;
    OpenVideo(path, options, capture);
    ListVideoFrames(path, options, capture, sequence.source_indices_, sequence.names_,
                    sequence.warning_, sequence.fps_);
  }

  // Read the first frame: it fixes the frame size and validates the source early. An image's
  // size is checked on its header first, before the budget of its size resized to a height.
  if (!sequence.is_video_) {
    const std::string first = JoinPaths(sequence.folder_, sequence.names_[0]);
    const ImageHeader header = RequireImageHeader(first);
    CheckFrameNotTooSmall(first, header.width, header.height);
  }
  std::string what;
  const cv::Mat raw = sequence.ReadRaw(0, &what);
  sequence.source_size_ = raw.size();
  CheckFrameNotTooSmall(what, raw.cols, raw.rows);
  CheckPixelBudget(what, ResizedSize(raw.size(), options.resize_height), options.max_pixels);
  sequence.frame_size_ = sequence.MakeFrame(raw, 0, what).gray.size();
  if (!sequence.is_video_) sequence.CheckFrameHeaders();
  return sequence;
}

void ImageSequence::CheckFrameHeaders() const {
  for (size_t i = 1; i < names_.size(); ++i) {
    const std::string path = JoinPaths(folder_, names_[i]);
    const cv::Size size = CheckImageHeaderBudget(path, options_.resize_height, options_.max_pixels);
    COMIC_CHECK(size == source_size_, kInvalidData,
                path << ": size " << size.width << "x" << size.height
                     << " differs from the first frame's " << source_size_.width << "x"
                     << source_size_.height);
  }
}

std::string ImageSequence::FramePath(size_t i) const {
  if (is_video_ || i >= names_.size()) return "";
  return JoinPaths(folder_, names_[i]);
}

Frame ImageSequence::ReadFrame(size_t i) const {
  COMIC_CHECK(
      i < source_indices_.size(), kInvalidArgument,
      path_ << ": frame " << i << " out of range (" << source_indices_.size() << " frames)");
  std::string what;
  const cv::Mat raw = ReadRaw(i, &what);
  return MakeFrame(raw, i, what);
}

cv::Mat ImageSequence::ReadRaw(size_t i, std::string* what) const {
  return is_video_ ? ReadVideoRaw(i, what) : ReadImageRaw(i, what);
}

std::vector<Frame> ImageSequence::ReadAll() const {
  std::vector<Frame> frames;
  frames.reserve(NumFrames());
  for (size_t i = 0; i < NumFrames(); ++i) frames.push_back(ReadFrame(i));
  return frames;
}

Frame ImageSequence::MakeFrame(const cv::Mat& raw, size_t i, const std::string& what) const {
  // The size check is on the stored size, so a mismatch is reported before any resizing.
  COMIC_CHECK(raw.size() == source_size_, kInvalidData,
              what << ": size " << raw.cols << "x" << raw.rows << " differs from the first frame's "
                   << source_size_.width << "x" << source_size_.height);
  Frame frame;
  frame.source_index = source_indices_[i];
  frame.name = names_[i];
  try {
    frame.gray = ResizeToHeight(ToGray8(raw), options_.resize_height);
    frame.color = ResizeToHeight(ToBgr8(raw), options_.resize_height);
  } catch (const Error& e) {
    throw Error(e.kind(), what + ": " + e.what());
  }
  return frame;
}

cv::Mat ImageSequence::ReadImageRaw(size_t i, std::string* what) const {
  *what = JoinPaths(folder_, names_[i]);
  // Every frame's declared size against the budget before it is decoded, not only the first's.
  CheckImageHeaderBudget(*what, options_.resize_height, options_.max_pixels);
  return ReadImageUnchanged(*what);
}

cv::Mat ImageSequence::ReadVideoRaw(size_t i, std::string* what) const {
  const int target = source_indices_[i];
  cv::Mat raw;
  bool decoded = false;
  bool ended = false;
  // Open() decoded every selected frame once; FFmpeg's messages stay off the terminal here too.
  CaptureLibraryMessages([&] {
    if (!video_ || video_->next_index > target) {
      // (Re)open and read forward: seeking is unreliable across codecs, reading is exact.
      video_ = std::make_unique<VideoState>();
      video_->capture.open(path_, cv::CAP_FFMPEG);
    }
    if (!video_->capture.isOpened()) return;
    while (video_->next_index < target) {
      if (!video_->capture.grab()) {
        ended = true;
        return;
      }
      ++video_->next_index;
    }
    decoded = video_->capture.read(raw) && !raw.empty();
  });
  COMIC_CHECK(video_ && video_->capture.isOpened(), kInvalidData, path_ << ": cannot reopen video");
  COMIC_CHECK(!ended, kInvalidData, path_ << ": video ended before frame " << target);
  COMIC_CHECK(decoded, kInvalidData, path_ << ": cannot decode frame " << target);
  ++video_->next_index;
  *what = path_ + " frame " + std::to_string(target);
  return raw;
}

}  // namespace comic::io
