// How far a track's observations stray from one 3-D point under a model's cameras: the geometric
// half of telling, without truth, a track that follows a surface point from one that slides (a
// T-junction of a silhouette with what lies behind it moves along the silhouette, against the
// epipolar geometry, as the camera moves; paper §4's reason for matching the object side only).
//
// The point is the linear (DLT) triangulation of the track's observations in the model's
// registered frames; the drift is the RMS of their reprojection errors in pixels. A track that
// follows a point has the detector's jitter as drift; a sliding one more, growing with its length.
#pragma once

#include <optional>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

// Per track of `tracks` (frame k is the model's image k + 1, as the incremental mapper numbers
// them): the RMS reprojection error in pixels of the point triangulated from its observations in
// registered frames, or none with fewer than `min_views` of them or a point behind a camera.
std::vector<std::optional<double>> MeasureTrackDrift(const frontend::FeatureTracks& tracks,
                                                     const Reconstruction& model,
                                                     int min_views = 3);

}  // namespace comic::sfm
