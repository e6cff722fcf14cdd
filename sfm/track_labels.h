// Which tracks sit on an object boundary and which slide, told without truth (paper §4): a point
// on an occluding contour has one side on the object, which keeps its look as the point moves,
// and one on whatever lies behind, which changes; a track that stays on a T-junction of a
// silhouette with the background changes on both sides, or strays from every single 3-D point
// under the cameras.
//
// Evidence: each side's change along the track (frontend/matching/track_side_change.h) and the
// track's drift from one point under a model's cameras (sfm/track_drift.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "frontend/matching/track_side_change.h"

namespace comic::sfm {

enum class TrackLabel {
  kUnknown,   // too short, no sides and not in the model
  kInterior,  // both sides keep their look (or no sides, and no drift)
  kBoundary,  // one side keeps its look (the object side), the other has changed
  kSliding,   // both sides have changed, or the track strays from every single point
};

std::string TrackLabelName(TrackLabel label);

struct TrackLabelOptions {
  // A side whose mean normalised change (0 same, 1 unrelated) stays at most this keeps its look;
  // one at least side_changed_min has changed (between: neither).
  double side_kept_max = 0.35;
  double side_changed_min = 0.7;
  // A track whose RMS reprojection error from its best single point exceeds this slides (pixels):
  // a detector's jitter stays below it.
  double drift_max_px = 1.2;

  void Check() const;
};

struct LabelledTrack {
  TrackLabel label = TrackLabel::kUnknown;
  frontend::PatchSide object_side = frontend::PatchSide::kNone;  // for kBoundary: the kept side
};

// One label per track; `sides` and `drift` are per track, of the same length. Throws
// comic::Error(kInvalidArgument) for bad options or lengths that differ.
std::vector<LabelledTrack> LabelTracks(const std::vector<frontend::SideChange>& sides,
                                       const std::vector<std::optional<double>>& drift,
                                       const TrackLabelOptions& options);

}  // namespace comic::sfm
