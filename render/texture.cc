#include "render/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <opencv2/core/hal/intrin.hpp>
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
  std::vector<cv::Mat> pyramid = {bgr};
  while (pyramid.back().cols > 1 || pyramid.back().rows > 1) {
    const cv::Mat& last = pyramid.back();
    cv::Mat next;
    if (last.cols >= 2 && last.rows >= 2) {
      cv::pyrDown(last, next);
    } else {
      cv::resize(last, next, cv::Size((last.cols + 1) / 2, (last.rows + 1) / 2), 0, 0,
                 cv::INTER_AREA);
    }
    pyramid.push_back(next);
  }
  for (const cv::Mat& level : pyramid) {
    cv::Mat padded;
    cv::copyMakeBorder(level, padded, 0, 0, 0, 1, cv::BORDER_REPLICATE);
    cv::Mat bgrx;
    cv::cvtColor(padded, bgrx, cv::COLOR_BGR2BGRA);
    bgrx.forEach<cv::Vec4b>([](cv::Vec4b& p, const int*) { p[3] = 0; });
    texture.levels_.push_back(bgrx);
    texture.sizes_.push_back(level.size());
    const float scale = 1.0f / static_cast<float>(1 << texture.level_scales_.size());
    texture.level_scales_.emplace_back(scale, scale);
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
  const cv::Size& size = sizes_[level];
  // cv::pyrDown centres level k's texel i on level k-1's texel 2i, so on level 0's texel 2^k i,
  // whose centre is at 2^k i + 1/2: every level is centred where level 0 is, and a texture does
  // not shift on its surface as the level changes with distance.
  const float scale = level_scales_[level][0];  // 2^-k
  const float fx = std::clamp((static_cast<float>(x) - 0.5f) * scale, 0.0f, size.width - 1.0f);
  const float fy = std::clamp((static_cast<float>(y) - 0.5f) * scale, 0.0f, size.height - 1.0f);
  const int x0 = static_cast<int>(fx);
  const int y0 = static_cast<int>(fy);
  const int y1 = std::min(y0 + 1, size.height - 1);
  // Weights in 1/256 of a texel, in integers: exact, and the same in the vector and the scalar
  // code. Texel x0 + 1 exists (the repeated column) even at the right edge, where its weight is 0.
  const uint32_t wx = static_cast<uint32_t>((fx - x0) * 256.0f);
  const uint32_t wy = static_cast<uint32_t>((fy - y0) * 256.0f);
  const uint8_t* top = image.ptr<uint8_t>(y0) + 4 * x0;
  const uint8_t* bottom = image.ptr<uint8_t>(y1) + 4 * x0;
  float channels[4];
#if CV_SIMD128
  const uint16_t w[8] = {static_cast<uint16_t>(256 - wx), static_cast<uint16_t>(256 - wx),
                         static_cast<uint16_t>(256 - wx), static_cast<uint16_t>(256 - wx),
                         static_cast<uint16_t>(wx),       static_cast<uint16_t>(wx),
                         static_cast<uint16_t>(wx),       static_cast<uint16_t>(wx)};
  const cv::v_uint16x8 weights = cv::v_load(w);
  cv::v_uint32x4 left, right;
  cv::v_expand(cv::v_mul_wrap(cv::v_load_expand(top), weights), left, right);
  const cv::v_uint32x4 upper = left + right;
  cv::v_expand(cv::v_mul_wrap(cv::v_load_expand(bottom), weights), left, right);
  const cv::v_uint32x4 lower = left + right;
  const cv::v_uint32x4 blended = upper * cv::v_setall_u32(256 - wy) + lower * cv::v_setall_u32(wy);
  cv::v_store(channels,
              cv::v_cvt_f32(cv::v_reinterpret_as_s32(blended)) * cv::v_setall_f32(1.0f / 65536.0f));
#else
  for (int c = 0; c < 4; ++c) {
    const uint32_t upper = top[c] * (256 - wx) + top[4 + c] * wx;
    const uint32_t lower = bottom[c] * (256 - wx) + bottom[4 + c] * wx;
    channels[c] = static_cast<float>(upper * (256 - wy) + lower * wy) * (1.0f / 65536.0f);
  }
#endif
  return cv::Vec3f(channels[0], channels[1], channels[2]);
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
