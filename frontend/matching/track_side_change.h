// How much each side of a track's point changes its appearance along the track: the evidence,
// without any truth, for which tracks sit on an object boundary (paper §4: a point on an occluding
// contour has one side on the object, which moves with the point, and one on whatever is behind,
// which does not).
//
// The sides are cut once, at the track's first observation, by the level line through the point
// (frontend/matching/level_line_sides.h: CoMIC's own iso-curve for a CoMIC point, the same rule
// for every other detector). Each later observation's patch, sampled at its sub-pixel position, is
// compared side by side with the first: after removing each side's mean (an exposure change is
// not a change of surface), the mean squared difference over the sum of the two variances plus
// the noise floor. 0 is the same appearance, 1 an unrelated one, 2 the inverse; a flat side that
// stays flat stays near 0.
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"
#include "frontend/matching/track.h"

namespace comic::frontend {

struct TrackSideChangeOptions {
  // Tracks with fewer observations are not measured.
  int min_track_length = 3;
  // Grey levels of image noise: the variance floor of the normalised change (a flat side's
  // noise is not a change).
  double noise_grey_levels = 2.0;

  void Check() const;
};

struct SideChange {
  bool measured = false;                     // long enough, with two sides at the first observation
  PatchSide object_side = PatchSide::kNone;  // the side the point's corner points into
  // Per side (kPlus, kMinus): the mean normalised change over the later observations, and the
  // change at the last one.
  float plus_mean = 0.0f;
  float minus_mean = 0.0f;
  float plus_last = 0.0f;
  float minus_last = 0.0f;
  int num_compared = 0;  // later observations whose patch fitted the frame
};

// Frame k's grey image (CV_8UC1, the size the features live in); called once per frame, in order.
using GrayFrameFn = std::function<cv::Mat(int frame)>;

// One SideChange per track of `tracks`. Throws comic::Error(kInvalidArgument) for bad options or
// a frame of the wrong size or type.
std::vector<SideChange> MeasureTrackSideChanges(const FeatureTracks& tracks,
                                                const GrayFrameFn& gray,
                                                const TrackSideChangeOptions& options);

}  // namespace comic::frontend
