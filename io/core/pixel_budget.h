// A stated budget on the pixels an app will work on, so that an absurd input (an 8000x6000
// noise image took 432 s and 9.6 GB in comic_detect, issue 19) is refused in a second with one
// line saying how to raise it, instead of exhausting the shared machine.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

namespace comic::io {

// 12 Mpx: a 4000x3000 photo passes, KITTI frames are 0.47 Mpx; the worst case, CoMIC on noise,
// grows faster than the pixels, and the default keeps it within the memory and time the docs
// state (docs/robustness.md, "Bounded options": detector x size -> time and peak memory).
constexpr int64_t kDefaultMaxPixels = 12'000'000;
// The largest budget accepted (--max-pixels): 1 Gpx.
constexpr int64_t kMaxMaxPixels = 1'000'000'000;

// Throws comic::Error(kInvalidArgument) unless 1 <= max_pixels <= kMaxMaxPixels.
void CheckMaxPixels(int64_t max_pixels);

// Throws comic::Error(kInvalidData) naming `what` when size.area() > max_pixels, saying how to
// raise the budget (--max-pixels) or lower the work (--resize-height).
void CheckPixelBudget(const std::string& what, cv::Size size, int64_t max_pixels);
// The same for a size declared by a file's header, which may exceed int's range.
void CheckPixelBudget(const std::string& what, int64_t width, int64_t height, int64_t max_pixels);

}  // namespace comic::io
