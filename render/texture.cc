#include "render/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::render {

Texture Texture::FromImage(const cv::Mat& image, const std::string& name) {
  COMIC_CHECK(!image.empty() && image.depth() == CV_8U &&
                  (image.channels() == 1 || image.channels() == 3 || image.channels() == 4),
              kInvalidArgument, name << ": a texture must be an 8-bit grey, BGR or BGRA image");
  Texture texture;
  texture.name_ = name;
  cv::Mat bgr;
  if (image.channels() == 1) {
    cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  } else if (image.channels() == 4) {
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  } else {
    bgr = image.clone();
  }
  texture.levels_.push_back(bgr);
  while (texture.levels_.back().cols > 1 || texture.levels_.back().rows > 1) {
    const cv::Mat& last = texture.levels_.back();
    cv::Mat next;
    if (last.cols >= 2 && last.rows >= 2) {
      cv::pyrDown(last, next);
    } else {
      cv::resize(last, next, cv::Size((last.cols + 1) / 2, (last.rows + 1) / 2), 0, 0,
                 cv::INTER_AREA);
    }
    texture.levels_.push_back(next);
  }
  for (const cv::Mat& level : texture.levels_) {
    texture.level_scales_.emplace_back(static_cast<float>(level.cols) / bgr.cols,
                                       static_cast<float>(level.rows) / bgr.rows);
  }
  return texture;
}

Texture Texture::Solid(const cv::Vec3f& bgr, const std::string& name) {
  cv::Mat pixel(1, 1, CV_8UC3);
  pixel.at<cv::Vec3b>(0, 0) =
      cv::Vec3b(cv::saturate_cast<uint8_t>(bgr[0]), cv::saturate_cast<uint8_t>(bgr[1]),
                cv::saturate_cast<uint8_t>(bgr[2]));
  return FromImage(pixel, name);
}

cv::Vec3f Texture::SampleLevel(int level, double x, double y) const {
  const cv::Mat& image = levels_[level];
  // Level k's texel (i, j) covers level 0's [i, i + 1) / level_scales_[k].
  const float fx =
      std::clamp(static_cast<float>(x) * level_scales_[level][0] - 0.5f, 0.0f, image.cols - 1.0f);
  const float fy =
      std::clamp(static_cast<float>(y) * level_scales_[level][1] - 0.5f, 0.0f, image.rows - 1.0f);
  const int x0 = static_cast<int>(fx);
  const int y0 = static_cast<int>(fy);
  const int x1 = std::min(x0 + 1, image.cols - 1);
  const int y1 = std::min(y0 + 1, image.rows - 1);
  // Weights in 1/256 of a texel, in integers: exact and the same everywhere.
  const int wx = static_cast<int>((fx - x0) * 256.0f);
  const int wy = static_cast<int>((fy - y0) * 256.0f);
  const uint8_t* row0 = image.ptr<uint8_t>(y0);
  const uint8_t* row1 = image.ptr<uint8_t>(y1);
  const int a = 3 * x0;
  const int b = 3 * x1;
  cv::Vec3f out;
  for (int c = 0; c < 3; ++c) {
    const int top = row0[a + c] * (256 - wx) + row0[b + c] * wx;
    const int bottom = row1[a + c] * (256 - wx) + row1[b + c] * wx;
    out[c] = static_cast<float>(top * (256 - wy) + bottom * wy) * (1.0f / 65536.0f);
  }
  return out;
}

namespace {

// log2 to about 0.003 (the mantissa's log by a quadratic), enough to pick and blend mip levels,
// and far cheaper than std::log2 per pixel. `value` > 0 and finite.
float FastLog2(float value) {
  uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  const int exponent = static_cast<int>((bits >> 23) & 0xff) - 127;
  const uint32_t mantissa_bits = (bits & 0x7fffffu) | 0x3f800000u;  // the mantissa in [1, 2)
  float m = 0.0f;
  std::memcpy(&m, &mantissa_bits, sizeof(m));
  m -= 1.0f;
  return exponent + m * (1.3465553f - 0.34655532f * m);
}

}  // namespace

cv::Vec3f Texture::Sample(double x, double y, double footprint) const {
  if (!(footprint > 1.0) || levels_.size() == 1) return SampleLevel(0, x, y);
  const double level = std::min<double>(FastLog2(static_cast<float>(footprint)), NumLevels() - 1.0);
  const int lower = std::min(static_cast<int>(level), NumLevels() - 1);
  const int upper = std::min(lower + 1, NumLevels() - 1);
  const float w = static_cast<float>(level - lower);
  // Within 1/16 of a level, one level is as good as two.
  if (w >= 15.0f / 16.0f) return SampleLevel(upper, x, y);
  const cv::Vec3f a = SampleLevel(lower, x, y);
  if (w <= 1.0f / 16.0f || upper == lower) return a;
  return a + w * (SampleLevel(upper, x, y) - a);
}

}  // namespace comic::render
