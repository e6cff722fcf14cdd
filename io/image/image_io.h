// Reading single images into the forms every module works on: 8-bit grey for detection and
// matching, 8-bit BGR colour for drawing and point colours.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "io/core/pixel_budget.h"

namespace comic::io {

// True for the extensions ImageSequence reads as images: png, jpg, jpeg, ppm, pgm, pnm, pbm,
// tif, tiff, bmp (case-insensitive).
bool IsImageExtension(const std::string& extension);

// Converts any 1-, 3- or 4-channel 8- or 16-bit image to 8-bit grey (colour: ITU-R 601 luma as
// cv::cvtColor; 16-bit: divided by 257 so 65535 -> 255). Other depths throw comic::Error.
cv::Mat ToGray8(const cv::Mat& image);

// Same conversions to 8-bit 3-channel BGR (grey replicated).
cv::Mat ToBgr8(const cv::Mat& image);

// Resizes to the given height keeping the aspect ratio (width rounded); INTER_AREA when
// shrinking, INTER_LINEAR when enlarging. height <= 0 or equal to the current height: a copy.
cv::Mat ResizeToHeight(const cv::Mat& image, int height);

// The size ResizeToHeight gives an image of `size` (height <= 0: `size`).
cv::Size ResizedSize(cv::Size size, int height);

// The largest --resize-height accepted: 16384 px (beyond it a frame alone takes gigabytes).
constexpr int kMaxResizeHeight = 16384;

struct LoadedImage {
  cv::Mat gray;   // CV_8UC1
  cv::Mat color;  // CV_8UC3, BGR
};

// Throws comic::Error(kInvalidArgument) unless `resize_height` is 0 (keep) or in
// [kMinResizeHeight, kMaxResizeHeight]; `what` names it ("--resize-height", "resize_height").
void CheckResizeHeight(int resize_height, const std::string& what = "--resize-height");

// The smallest --resize-height accepted other than 0: 8 px.
constexpr int kMinResizeHeight = 8;

// Refuses the image at `path` when the size its header declares (io/image/image_header.h),
// resized to `resize_height`, exceeds `max_pixels` (CheckPixelBudget), or its stored size exceeds
// kMaxMaxPixels, before anything is decoded, and returns the stored size. A file whose header is
// not read (RequireImageHeader) or declares no pixels is refused too ("cannot decode image").
cv::Size CheckImageHeaderBudget(const std::string& path, int resize_height, int64_t max_pixels);

// Reads `path` (any format whose header io/image/image_header.h reads) and returns grey and colour
// at `resize_height` (0 = original size). Throws comic::Error: kNotFound for a missing file,
// kInvalidData for a file that is not a decodable image or has an unsupported depth, or whose size
// after resizing exceeds `max_pixels` (io/core/pixel_budget.h; checked on the header before
// decoding, and again before resizing), naming the file; kIo when memory runs out for the
// pixels.
LoadedImage LoadImage(const std::string& path, int resize_height = 0,
                      int64_t max_pixels = kDefaultMaxPixels);

// Reads `path` unchanged (depth and channels as stored). Same errors as LoadImage; the size the
// header declares is checked against `max_pixels` before decoding.
cv::Mat ReadImageUnchanged(const std::string& path, int64_t max_pixels = kMaxMaxPixels);

}  // namespace comic::io
