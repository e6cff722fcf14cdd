// The outline of a planar piece that is not a plain rectangle (a tree's crown, a fence's slats):
// a coverage image stretched over the piece, bilinearly interpolated and cut at one half, so the
// outline is a smooth curve at any distance (anti-aliased by the rasteriser's supersampling).
#pragma once

#include <algorithm>
#include <opencv2/core.hpp>

#include "render/random.h"

namespace comic::render {

struct AlphaMask {
  cv::Mat coverage;  // CV_8UC1, 255 = solid; spans the piece's (s, t) in [0, 1]^2
  // Per 8x8 block of texels (and its one-texel rim): 0 all empty, 255 all solid, 128 mixed, so
  // that most lookups need no interpolation. Made by Finish().
  cv::Mat blocks;

  // Call once `coverage` is drawn.
  void Finish();
  // True where the interpolated coverage at (s, t) is at least one half.
  bool Covers(double s, double t) const {
    const float x =
        std::clamp(static_cast<float>(s) * coverage.cols - 0.5f, 0.0f, coverage.cols - 1.0f);
    const float y =
        std::clamp(static_cast<float>(t) * coverage.rows - 0.5f, 0.0f, coverage.rows - 1.0f);
    const int x0 = static_cast<int>(x);
    const int y0 = static_cast<int>(y);
    const uint8_t block = blocks.ptr<uint8_t>(y0 >> kBlockShift)[x0 >> kBlockShift];
    if (block != kMixed) return block != 0;
    return Interpolate(x, y, x0, y0);
  }

  static constexpr int kBlockShift = 3;  // blocks of 8 x 8 texels
  static constexpr uint8_t kMixed = 128;

 private:
  bool Interpolate(float x, float y, int x0, int y0) const;
};

// A tree seen from the side: a trunk (the bottom `trunk_fraction` of the height, a tenth of the
// width) under a crown made of overlapping discs with a ragged rim, drawn from `random`. Rows run
// from the top of the tree (t = 0) to the ground (t = 1). `size` is the mask's side in texels.
AlphaMask MakeTreeMask(Random& random, int size = 256, double trunk_fraction = 0.35);

// A picket fence: `slats` vertical slats filling `fill` of their period, held by two horizontal
// rails at 20 % and 75 % of the height; `texels_per_slat` sets the resolution.
AlphaMask MakeFenceMask(int slats, double fill, int texels_per_slat = 16);

}  // namespace comic::render
