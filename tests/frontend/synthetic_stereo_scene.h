// A synthetic rectified stereo pair with exactly known ground truth, for the stereo evaluation's
// tests: a textured foreground rectangle at disparity 12 shifted over a differently textured
// background at disparity 4, so every left pixel's class (boundary, non-boundary, occluded,
// unknown) and true right position are known by construction.
//
// Left image:  L(x, y) = F(x, y) inside the foreground rectangle, B(x, y) elsewhere.
// Right image: R(x, y) = F(x + 12, y) where x + 12 falls in the rectangle, else B(x + 4, y).
// Hence left (x, y) shows at right (x − 12, y) on the foreground, (x − 4, y) on the background.
// Occluded: background pixels whose right position is covered by the foreground (x in [72, 80)
// on the rectangle's rows) and x < 4 (right position outside the image). Unknown disparity:
// x >= 176. Boundary (disc = 255): valid pixels whose 7x7 window holds foreground and
// background pixels (within 3 px of the rectangle's edge); non-boundary (128): the other valid
// pixels.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "io/datasets/middlebury.h"

namespace comic::test {

struct SyntheticStereoScene {
  static constexpr int kWidth = 200;
  static constexpr int kHeight = 120;
  static constexpr int kFgX0 = 80;  // foreground columns [kFgX0, kFgX1), rows [kFgY0, kFgY1)
  static constexpr int kFgX1 = 140;
  static constexpr int kFgY0 = 25;
  static constexpr int kFgY1 = 95;
  static constexpr int kFgDisparity = 12;
  static constexpr int kBgDisparity = 4;
  static constexpr int kUnknownX0 = 176;  // GT unknown for x >= kUnknownX0
  static constexpr int kDiscRadius = 3;

  static bool InForeground(int x, int y) {
    return x >= kFgX0 && x < kFgX1 && y >= kFgY0 && y < kFgY1;
  }

  // Random grey blocks of `block` x `block` pixels (seeded: the same texture every time).
  static cv::Mat BlockTexture(cv::Size size, int block, uint64_t seed) {
    cv::RNG rng(seed);
    cv::Mat texture(size, CV_8UC1);
    const int bw = (size.width + block - 1) / block;
    const int bh = (size.height + block - 1) / block;
    cv::Mat blocks(bh, bw, CV_8UC1);
    for (int y = 0; y < bh; ++y) {
      for (int x = 0; x < bw; ++x)
        blocks.at<uint8_t>(y, x) = static_cast<uint8_t>(rng.uniform(0, 256));
    }
    for (int y = 0; y < size.height; ++y) {
      for (int x = 0; x < size.width; ++x) {
        texture.at<uint8_t>(y, x) = blocks.at<uint8_t>(y / block, x / block);
      }
    }
    return texture;
  }

  // The pair at its own size (resize factor 1, disparity scale 1): grey and colour images,
  // disparity in pixels, nonocc and disc masks.
  static io::MiddleburyPair Make() {
    const cv::Mat background = BlockTexture({kWidth + kBgDisparity, kHeight}, 3, 7);
    const cv::Mat foreground = BlockTexture({kWidth, kHeight}, 3, 11);
    io::MiddleburyPair pair;
    pair.name = "synthetic";
    pair.left_gray.create(kHeight, kWidth, CV_8UC1);
    pair.right_gray.create(kHeight, kWidth, CV_8UC1);
    pair.disparity.create(kHeight, kWidth, CV_32FC1);
    pair.nonocc.create(kHeight, kWidth, CV_8UC1);
    pair.disc.create(kHeight, kWidth, CV_8UC1);
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const bool fg = InForeground(x, y);
        pair.left_gray.at<uint8_t>(y, x) =
            fg ? foreground.at<uint8_t>(y, x) : background.at<uint8_t>(y, x);
        pair.right_gray.at<uint8_t>(y, x) = InForeground(x + kFgDisparity, y)
                                                ? foreground.at<uint8_t>(y, x + kFgDisparity)
                                                : background.at<uint8_t>(y, x + kBgDisparity);
        const bool unknown = x >= kUnknownX0;
        pair.disparity.at<float>(y, x) =
            unknown ? 0.0f : static_cast<float>(fg ? kFgDisparity : kBgDisparity);
        const bool occluded =
            !fg && (x < kBgDisparity || InForeground(x - kBgDisparity + kFgDisparity, y));
        const bool valid = !unknown && !occluded;
        pair.nonocc.at<uint8_t>(y, x) = valid ? 255 : 0;
        bool near_edge = false;
        for (int dy = -kDiscRadius; dy <= kDiscRadius; ++dy) {
          for (int dx = -kDiscRadius; dx <= kDiscRadius; ++dx) {
            near_edge = near_edge || InForeground(x + dx, y + dy) != fg;
          }
        }
        pair.disc.at<uint8_t>(y, x) = !valid ? 0 : near_edge ? 255 : 128;
      }
    }
    cv::cvtColor(pair.left_gray, pair.left_color, cv::COLOR_GRAY2BGR);
    cv::cvtColor(pair.right_gray, pair.right_color, cv::COLOR_GRAY2BGR);
    pair.disparity_scale = 1.0;
    pair.resize_factor = 1.0;
    pair.original_size = pair.left_gray.size();
    return pair;
  }
};

}  // namespace comic::test
