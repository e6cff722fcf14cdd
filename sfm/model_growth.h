// Growing one model (one attempt of sfm/incremental_pipeline.h): from an initial pair, register
// frames one at a time (PnP, triangulation, local bundle adjustment; global adjustments as the
// model grows), retry the frames left out after a global adjustment, merge earlier models the
// model reaches, and finish with a global adjustment. Self-calibrated intrinsics that leave the
// plausible range are reset to the prior and held fixed (sfm/intrinsics_plausibility.h).
//
//   GrownModel grown = GrowModel(tracks, camera, options, pair, attempt, earlier, linker,
//   progress); if (grown.status == ReconstructionStatus::kSuccess) { ... grown.model ...
//   grown.merged ... }
#pragma once

#include <functional>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/incremental_mapper.h"
#include "sfm/incremental_pipeline_types.h"
#include "sfm/keyframe_selection.h"
#include "sfm/loop_closure.h"

namespace comic::sfm {

// Links between the model being grown (`current`) and an earlier model it shares no tracks or
// frames with, found by matching the frames at their seams; empty when none were found.
using SeamLinker = std::function<std::vector<IncrementalMapper::FeatureLink>(
    const Reconstruction& current, const Reconstruction& earlier)>;

// The bundle adjustments of a run: how many, their Levenberg-Marquardt iterations and time.
struct BundleAdjustmentTally {
  int num_local_ba = 0;
  int num_global_ba = 0;
  // Of the global adjustments, the windows of bounded final adjustments (global_ba_max_images).
  int num_final_ba_windows = 0;
  int num_local_ba_iterations = 0;
  int num_global_ba_iterations = 0;
  double local_ba_time_s = 0.0;
  double global_ba_time_s = 0.0;
  double local_ba_cpu_time_s = 0.0;
  double global_ba_cpu_time_s = 0.0;

  void AddLocal(const BundleAdjustmentSummary& summary);
  void AddGlobal(const BundleAdjustmentSummary& summary);
  void Add(const BundleAdjustmentTally& other);
};

struct GrownModel {
  // kSuccess: a model; kTooFewPoints: the initial pair kept too few points (no model).
  ReconstructionStatus status = ReconstructionStatus::kTooFewPoints;
  IncrementalModel model;
  size_t initial_pair_num_points = 0;
  // Indices into `earlier` of the models merged into this one, and how many of those merges
  // needed seam links.
  std::vector<size_t> merged;
  int num_seam_links = 0;
  // Per frame: the most PnP inliers a failed registration found (-1: never tried).
  std::vector<int> best_failed_pose_inliers;
  BundleAdjustmentTally ba;
  BundleAdjustmentSummary final_ba;
  // Frames registered but not posed again against the final map (LocalizeNonKeyframes).
  std::vector<int> non_keyframes_lost;
  // With IncrementalPipelineOptions::close_loops.
  LoopClosureSummary loop_closure;
  bool focal_assessed = false;
  FocalObservability focal_observability;
  bool intrinsics_refined = false;
  IntrinsicsRejection intrinsics_rejection;
};

// Grows a model of `tracks` from `pair` with `camera` as the prior intrinsics. `earlier` are the
// run's earlier models still standing (merged when this model shares registered frames, tracked
// points or, through `seam_linker` if given, seam matches with them). `attempt` numbers the
// progress reports. `keyframes` (one decision per frame; nullptr: every frame is a keyframe)
// says which frames add to the map (IncrementalMapper::SetKeyframes); the frames this model makes
// keyframes (its initial pair, promotions) are written back with their reason.
GrownModel GrowModel(const frontend::FeatureTracks& tracks, const Camera& camera,
                     const IncrementalPipelineOptions& options,
                     const IncrementalMapper::InitialPair& pair, int attempt,
                     const std::vector<const IncrementalModel*>& earlier,
                     const SeamLinker& seam_linker, const MapperProgressCallback& progress,
                     std::vector<KeyframeDecision>* keyframes = nullptr);

}  // namespace comic::sfm
