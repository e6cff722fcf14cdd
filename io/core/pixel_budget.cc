#include "io/core/pixel_budget.h"

#include "io/core/error.h"

namespace comic::io {

void CheckMaxPixels(int64_t max_pixels) {
  COMIC_CHECK(max_pixels >= 1 && max_pixels <= kMaxMaxPixels, kInvalidArgument,
              "--max-pixels must be in [1, " << kMaxMaxPixels << "], got " << max_pixels);
}

void CheckPixelBudget(const std::string& what, cv::Size size, int64_t max_pixels) {
  const int64_t pixels = static_cast<int64_t>(size.width) * size.height;
  COMIC_CHECK(pixels <= max_pixels, kInvalidData,
              what << ": " << size.width << "x" << size.height << " = " << pixels
                   << " pixels exceeds the budget of " << max_pixels
                   << " (about 200 bytes each); raise it with --max-pixels " << pixels
                   << " or work smaller with --resize-height");
}

}  // namespace comic::io
