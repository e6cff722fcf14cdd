// Side masks for any detector's point (issue 15): the level line through the point at its local
// middle level cuts its 23x23 patch into a bright side (ic+) and a dark side (ic-), just as
// CoMIC's maximally stable iso-curve cuts the patch of a CoMIC point (paper §4, Fig. 7). The cut
// itself is frontend/comic/side_mask's, so every detector's sides are drawn by the same rule.
//
// The "object" side is the one the point's corner points into (the side holding the smaller
// angle, paper §2: the iso-curve turns by less than 180° around the corner's interior). CoMIC
// states it (Feature::polarity); for the other detectors it is the side holding clearly fewer of
// the pixels near the point, and unknown (kNone) on straight edges.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

struct LevelLineSides {
  std::vector<PatchSide> mask;  // kPatchSize² labels as Feature::side_mask; empty = no sides
  PatchSide object_side = PatchSide::kNone;  // kPlus, kMinus or unknown
};

// True if `mask` labels at least one pixel on each side.
bool HasBothSides(const std::vector<PatchSide>& mask);

// The side of a CoMIC feature's corner interior from its polarity (kBright -> kPlus), kNone
// without polarity.
PatchSide ObjectSideFromPolarity(Polarity polarity);

// The feature's own sides when it has a side mask (object side from its polarity, or from the
// geometry if it has none); otherwise the level line of `gray` (CV_8UC1) through the rounded
// position at the middle of the grey range of its 5x5 neighbourhood. No sides (empty mask) when
// the patch does not fit, the neighbourhood spans fewer than kMinSideContrast grey levels, or no
// level line passes within 2 px.
LevelLineSides ComputeLevelLineSides(const cv::Mat& gray, const Feature& feature);

// Smallest grey-level range of the 5x5 neighbourhood for which a level line is drawn: below it
// the line follows noise.
inline constexpr int kMinSideContrast = 8;

}  // namespace comic::frontend
