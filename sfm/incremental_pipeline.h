// The incremental reconstruction of one sequence from its feature tracks, as COLMAP's
// IncrementalMapperController: models grown one after another by the IncrementalMapper (initial
// pair, then register / triangulate / local bundle adjustment per frame, global bundle adjustment
// as a model grows and at the end; sfm/model_growth.h), each started among the frames no model
// holds, merged where they share frames, points or seam matches; then poses for the frames left
// in the gaps (sfm/pose_gap_filling.h), and the frames still missing from the largest model in
// ranges with the reason (sfm/unregistered_ranges.h). Frames that cannot be registered are
// reported, not fatal; failures to start return a status.
//
//   IncrementalPipelineOptions options;
//   const IncrementalReconstruction result =
//       ReconstructIncrementally(tracks, camera, options, [](const MapperProgress& p) { ... });
//   if (!HasModel(result.status)) { ... no model: DiagnoseReconstruction says why ... }
//   // result.reconstruction: the largest model; result.other_models: the rest;
//   // result.unregistered_ranges: the frames missing from the largest, with the reason.
#pragma once

#include "frontend/matching/track.h"
#include "sfm/camera.h"
#include "sfm/incremental_pipeline_types.h"

namespace comic::sfm {

// Reconstructs the frames of `tracks` seen by `camera`: every model (see max_num_models), the
// largest in `reconstruction`. With `frame_matcher`, models whose tracks do not meet are linked
// through matches at their seams. Throws comic::Error only for invalid input (tracks, camera,
// options); expected failures come back as the status (that of the first attempt when none
// succeeds).
IncrementalReconstruction ReconstructIncrementally(const frontend::FeatureTracks& tracks,
                                                   const Camera& camera,
                                                   const IncrementalPipelineOptions& options,
                                                   const MapperProgressCallback& progress = {},
                                                   const FrameMatcher& frame_matcher = {});

}  // namespace comic::sfm
