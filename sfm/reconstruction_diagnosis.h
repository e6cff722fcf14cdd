// Why a reconstruction failed, in words a user can act on (issue 17): which stage failed, the
// measured value against the threshold it missed, and the option that would change it, e.g.
//   "best initial pair 000012.jpg-000019.jpg: 143 shared tracks, 120 inliers, median
//    triangulation angle 0.9 deg, parallax score 12.3, needs 30"
// with the suggestion "--init-angle 1.6 (accept less parallax) or --init-max-gap 40".
// A homography explaining the best pair (panning: the camera turns without moving sideways) is
// reported as such: no option can create parallax the frames do not have.
//
//   const ReconstructionDiagnosis diagnosis =
//       DiagnoseReconstruction(run.mapping, options.mapper, sequence.FrameNames());
//   if (diagnosis.failed) std::cerr << diagnosis.message << "; try " << diagnosis.suggestion;
#pragma once

#include <string>
#include <vector>

#include "sfm/incremental_pipeline.h"

namespace comic::sfm {

struct ReconstructionDiagnosis {
  bool failed = false;  // false: a model (kSuccess or kPartial), nothing else is set
  // "frames", "initial_pair" or "initial_points".
  std::string stage;
  // The check that failed: "frames", "shared_tracks", "two_view_geometry", "inliers",
  // "parallax", "initial_points".
  std::string check;
  double value = 0.0;   // what was measured (frames, tracks, inliers, score, points)
  double needed = 0.0;  // the threshold it missed
  // The frames of the pair that came closest (empty if none shared a track).
  std::string frame1;
  std::string frame2;
  // A homography explains the best pair: the camera only turned (or the scene is a plane).
  bool rotation_only = false;
  std::string message;     // one sentence, no line break
  std::string suggestion;  // the options that would change the outcome, as the apps spell them
};

// Diagnoses `reconstruction` made with `options` from frames named `frame_names` (image i + 1 is
// frame i). With a model (HasModel) returns {failed = false}; a partial run says why in its
// IncrementalReconstruction::unregistered_ranges.
ReconstructionDiagnosis DiagnoseReconstruction(const IncrementalReconstruction& reconstruction,
                                               const IncrementalPipelineOptions& options,
                                               const std::vector<std::string>& frame_names);

}  // namespace comic::sfm
