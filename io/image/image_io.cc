#include "io/image/image_io.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/library_messages.h"
#include "io/image/image_header.h"

namespace comic::io {
namespace {

cv::Mat To8Bit(const cv::Mat& image) {
  switch (image.depth()) {
    case CV_8U:
      return image;
    case CV_16U: {
      cv::Mat out;
      image.convertTo(out, CV_8U, 1.0 / 257.0);  // 65535 -> 255, exact for 257 * k
      return out;
    }
    default:
      throw Error(ErrorKind::kInvalidData,
                  "unsupported image depth (only 8- and 16-bit integer images are supported)");
  }
}

}  // namespace

bool IsImageExtension(const std::string& extension) {
  static constexpr const char* kExtensions[] = {"png", "jpg", "jpeg", "ppm",  "pgm",
                                                "pnm", "pbm", "tif",  "tiff", "bmp"};
  for (const char* e : kExtensions) {
    if (extension == e) return true;
  }
  return false;
}

cv::Mat ToGray8(const cv::Mat& image) {
  COMIC_CHECK(!image.empty(), kInvalidData, "empty image");
  const cv::Mat image8 = To8Bit(image);
  cv::Mat gray;
  switch (image8.channels()) {
    case 1:
      gray = image8.clone();
      break;
    case 3:
      cv::cvtColor(image8, gray, cv::COLOR_BGR2GRAY);
      break;
    case 4:
      cv::cvtColor(image8, gray, cv::COLOR_BGRA2GRAY);
      break;
    default:
      throw Error(ErrorKind::kInvalidData,
                  "unsupported number of channels: " + std::to_string(image8.channels()));
  }
  return gray;
}

cv::Mat ToBgr8(const cv::Mat& image) {
  COMIC_CHECK(!image.empty(), kInvalidData, "empty image");
  const cv::Mat image8 = To8Bit(image);
  cv::Mat color;
  switch (image8.channels()) {
    case 1:
      cv::cvtColor(image8, color, cv::COLOR_GRAY2BGR);
      break;
    case 3:
      color = image8.clone();
      break;
    case 4:
      cv::cvtColor(image8, color, cv::COLOR_BGRA2BGR);
      break;
    default:
      throw Error(ErrorKind::kInvalidData,
                  "unsupported number of channels: " + std::to_string(image8.channels()));
  }
  return color;
}

cv::Size ResizedSize(cv::Size size, int height) {
  if (height <= 0 || height == size.height || size.height <= 0) return size;
  const double width = std::lround(size.width * static_cast<double>(height) / size.height);
  return cv::Size(static_cast<int>(std::clamp(width, 1.0, 1e9)), height);
}

cv::Mat ResizeToHeight(const cv::Mat& image, int height) {
  if (height <= 0 || height == image.rows) return image.clone();
  cv::Mat out;
  cv::resize(image, out, ResizedSize(image.size(), height), 0, 0,
             height < image.rows ? cv::INTER_AREA : cv::INTER_LINEAR);
  return out;
}

cv::Mat ReadImageUnchanged(const std::string& path, int64_t max_pixels) {
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such file");
  COMIC_CHECK(!IsDirectory(path), kInvalidData, path << ": is a folder, not an image file");
  COMIC_CHECK(IsRegularFile(path), kInvalidData, path << ": not a regular file");
  // The decoder allocates what the header declares: a file whose header is not read is not
  // decoded, and a declared size beyond the budget is refused before any allocation.
  const ImageHeader header = RequireImageHeader(path);
  CheckPixelBudget(path, header.width, header.height, max_pixels);
  cv::Mat image;
  std::string opencv_error;
  bool out_of_memory = false;
  // libpng and libjpeg print to stderr instead of reporting (a truncated JPEG even decodes, grey
  // below the cut): their words are captured and become part of our one line.
  const std::string library_message = CaptureLibraryMessages([&] {
    try {
      image = cv::imread(path, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception& e) {
      out_of_memory = e.code == cv::Error::StsNoMem;
      opencv_error = e.err;
    } catch (const std::bad_alloc&) {
      out_of_memory = true;
    }
  });
  // Memory running out for the pixels is no fault of the file: said so, with what to do.
  COMIC_CHECK(!out_of_memory, kIo,
              path << ": out of memory for its " << header.width << "x" << header.height
                   << " pixels; free memory or work smaller (--max-pixels, --resize-height)");
  const std::string detail = !library_message.empty() ? library_message : opencv_error;
  COMIC_CHECK(!image.empty(), kInvalidData,
              path << ": cannot decode image (corrupt, truncated or not an image"
                   << (detail.empty() ? "" : ": " + detail) << ")");
  COMIC_CHECK(!MessageReportsCorruptData(library_message), kInvalidData,
              path << ": corrupt or truncated image (" << library_message << ")");
  return image;
}

void CheckResizeHeight(int resize_height, const std::string& what) {
  COMIC_CHECK(resize_height == 0 ||
                  (resize_height >= kMinResizeHeight && resize_height <= kMaxResizeHeight),
              kInvalidArgument,
              what << " must be 0 (original size) or in [" << kMinResizeHeight << ", "
                   << kMaxResizeHeight << "] pixels, got " << resize_height);
}

cv::Size CheckImageHeaderBudget(const std::string& path, int resize_height, int64_t max_pixels) {
  const ImageHeader header = RequireImageHeader(path);
  COMIC_CHECK(header.width > 0 && header.height > 0, kInvalidData,
              path << ": cannot decode image (its " << header.format << " header declares "
                   << header.width << "x" << header.height << ")");
  int64_t width = header.width;
  int64_t height = header.height;
  if (resize_height > 0 && resize_height != height) {
    width = std::max<int64_t>(1, std::llround(static_cast<double>(width) * resize_height / height));
    height = resize_height;
  }
  CheckPixelBudget(path, width, height, max_pixels);
  // The stored size is decoded too: it must stay within what any budget allows.
  CheckPixelBudget(path, header.width, header.height, kMaxMaxPixels);
  // Within kMaxMaxPixels, so within int (kMaxMaxPixels < 2^31).
  return cv::Size(static_cast<int>(header.width), static_cast<int>(header.height));
}

LoadedImage LoadImage(const std::string& path, int resize_height, int64_t max_pixels) {
  CheckImageHeaderBudget(path, resize_height, max_pixels);
  const cv::Mat raw = ReadImageUnchanged(path);
  CheckPixelBudget(path, ResizedSize(raw.size(), resize_height), max_pixels);
  LoadedImage loaded;
  try {
    loaded.gray = ResizeToHeight(ToGray8(raw), resize_height);
    loaded.color = ResizeToHeight(ToBgr8(raw), resize_height);
  } catch (const Error& e) {
    throw Error(e.kind(), path + ": " + e.what());
  }
  return loaded;
}

}  // namespace comic::io
