// Why the frames missing from a run's largest model are missing (issue 30, "honest status"): each
// frame's reason is the first check on its way into the model that it failed, and consecutive
// frames with the same reason form one range.
//   tracking / features          fewer features detected than PnP needs (a stretch without
//                                texture, a blank or smeared frame)
//   tracking / tracked_features  fewer of them in tracks than PnP needs (the tracker lost them)
//   linking / other_model        registered in another model that could not be merged
//   registration / visible_points  fewer of its tracks have a 3-D point of the model than PnP
//                                  needs
//   registration / pose_inliers  PnP found too few inliers among them
//
//   result.unregistered_ranges = ExplainUnregisteredFrames(tracks, largest, others, inliers, pnp);
#pragma once

#include <vector>

#include "frontend/matching/track.h"
#include "sfm/absolute_pose.h"
#include "sfm/incremental_pipeline_types.h"

namespace comic::sfm {

// `largest` and `others` are the run's models (image i + 1 is frame i), `best_failed_pose_inliers`
// per frame the most PnP inliers a failed registration found in the largest model's growth (-1:
// never tried; IncrementalMapper::best_failed_pose_inliers), `pnp` the registration's options.
// `no_initial_pair_left`: the run stopped starting models because no initial pair qualified
// among the frames no model holds (the messages of frames in no model say so).
std::vector<UnregisteredRange> ExplainUnregisteredFrames(
    const frontend::FeatureTracks& tracks, const Reconstruction& largest,
    const std::vector<IncrementalModel>& others, const std::vector<int>& best_failed_pose_inliers,
    const AbsolutePoseOptions& pnp, bool no_initial_pair_left);

}  // namespace comic::sfm
