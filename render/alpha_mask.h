// The outline of a planar piece that is not a plain rectangle (a tree's crown, a fence's slats):
// a coverage image stretched over the piece, bilinearly interpolated and cut at one half, so the
// outline is a smooth curve at any distance (anti-aliased by the rasteriser's supersampling).
#pragma once

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
  bool Covers(double s, double t) const;
};

// A tree seen from the side: a trunk (the bottom `trunk_fraction` of the height, a tenth of the
// width) under a crown made of overlapping discs with a ragged rim, drawn from `random`. Rows run
// from the top of the tree (t = 0) to the ground (t = 1). `size` is the mask's side in texels.
AlphaMask MakeTreeMask(Random& random, int size = 256, double trunk_fraction = 0.35);

// A picket fence: `slats` vertical slats filling `fill` of their period, held by two horizontal
// rails at 20 % and 75 % of the height; `texels_per_slat` sets the resolution.
AlphaMask MakeFenceMask(int slats, double fill, int texels_per_slat = 16);

}  // namespace comic::render
