#include "io/core/pixel_budget.h"

#include "io/core/error.h"

namespace comic::io {

void CheckMaxPixels(int64_t max_pixels) {
  COMIC_CHECK(max_pixels >= 1 && max_pixels <= kMaxMaxPixels, kInvalidArgument,
              "--max-pixels must be in [1, " << kMaxMaxPixels << "], got " << max_pixels);
}

void CheckPixelBudget(const std::string& what, cv::Size size, int64_t max_pixels) {
  CheckPixelBudget(what, size.width, size.height, max_pixels);
}

void CheckPixelBudget(const std::string& what, int64_t width, int64_t height, int64_t max_pixels) {
  // Header sizes are at most 2^32 per side: the product fits in int64.
  const int64_t pixels = width * height;
  COMIC_CHECK(pixels <= max_pixels, kInvalidData,
              what << ": " << width << "x" << height << " = " << pixels
                   << " pixels exceeds the budget of " << max_pixels
                   << " (docs/robustness.md); raise it with --max-pixels " << pixels
                   << " or work smaller with --resize-height");
}

}  // namespace comic::io
