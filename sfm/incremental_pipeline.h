// The incremental reconstruction of one sequence from its feature tracks: drives the
// IncrementalMapper (initial pair, then register / triangulate / local bundle adjustment per
// frame, global bundle adjustment as the model grows and at the end). Frames that cannot be
// registered are reported, not fatal; failures to start return a status.
//
//   IncrementalPipelineOptions options;
//   const IncrementalReconstruction result =
//       ReconstructIncrementally(tracks, camera, options, [](const MapperProgress& p) { ... });
//   if (result.status != ReconstructionStatus::kSuccess) { ... }
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/bundle_adjuster.h"
#include "sfm/camera.h"
#include "sfm/focal_observability.h"
#include "sfm/incremental_mapper.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

enum class ReconstructionStatus {
  kSuccess,        // a model with at least the initial pair (see unregistered_frames)
  kTooFewFrames,   // fewer than two frames
  kNoInitialPair,  // no frame pair with enough matches and parallax (e.g. pure rotation)
  kTooFewPoints,   // the initial pair triangulated too few points
};

// "success", "too_few_frames", "no_initial_pair", "too_few_points".
const char* ReconstructionStatusName(ReconstructionStatus status);
// A sentence for users, e.g. for a status other than kSuccess in an app's error line.
std::string ReconstructionStatusMessage(ReconstructionStatus status);

struct IncrementalPipelineOptions {
  IncrementalMapper::Options mapper;
  // Bundle adjustment after each new frame, over a window of images.
  BundleAdjustmentOptions local_ba;
  // Bundle adjustment of everything, as the model grows and at the end. Its refine_* flags say
  // which intrinsics may be refined; they are refined in global adjustments only (local windows
  // keep them, COLMAP's policy of refining a camera once many images constrain it), once
  // refine_intrinsics_min_num_images images are registered, and the focal length (and the
  // distortion, which would absorb its error) only while the motion makes it observable
  // (focal_observability); otherwise the priors stay.
  BundleAdjustmentOptions global_ba;
  int refine_intrinsics_min_num_images = 5;
  FocalObservabilityOptions focal_observability;
  // The final global adjustments (the model's output) stop at this relative cost gain instead of
  // global_ba.function_tolerance: on the dino ring (weak perspective) 1e-4 throughout gave ATE
  // 0.0050 instead of 0.0038 (COLMAP 0.0045), while KITTI's intermediate adjustments need no more.
  double final_global_ba_function_tolerance = 1e-5;
  // Images in the local bundle adjustment window (the new one and those sharing most points).
  // COLMAP's default (ba_local_num_images); 8 costs a quarter more for 0.5 mm less ATE on KITTI.
  int local_ba_num_images = 6;
  // A global bundle adjustment runs whenever the number of registered images has grown by this
  // factor since the last one.
  double global_ba_growth_ratio = 1.5;
  // Attempts to register a frame before it is given up.
  int max_registration_trials = 3;
  // The initial pair must triangulate at least this many points.
  int min_num_initial_points = 30;
  // Models grown at most: when a model leaves frames unregistered, another is started from an
  // initial pair among the frames no earlier model reached, and the model with the most
  // registered frames is returned.
  int max_num_models = 4;
  // When no frame pair qualifies as the initial pair, search once more with the minimum shared
  // tracks and inliers (mapper.init_min_num_matches, init_min_num_inliers) halved, as COLMAP
  // relaxes its initialisation constraints. A sparsely tracked sequence (MSER on the dino ring:
  // 774 tracks) then starts a model instead of none; sequences whose strict search succeeds are
  // unaffected.
  bool relax_initial_pair = true;
  // When a model stops short, the earlier models sharing a registered frame with it are merged
  // into it (IncrementalMapper::MergeModel), and it grows on from the merged frames.
  bool merge_models = true;

  IncrementalPipelineOptions();
  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// Reported after the initial pair and after each newly registered frame.
struct MapperProgress {
  int frame = -1;  // frame index just registered
  std::string frame_name;
  int attempt = 0;            // which model (0 = the first; see max_num_models)
  bool initial_pair = false;  // registered as part of the initial pair
  bool merged = false;        // registered by merging an earlier model (merge_models)
  size_t num_registered = 0;  // registered frames so far
  size_t num_frames = 0;
  size_t num_points3D = 0;
  int num_pose_inliers = 0;  // PnP inliers (0 for the initial pair)
};
using MapperProgressCallback = std::function<void(const MapperProgress&)>;

struct IncrementalReconstruction {
  ReconstructionStatus status = ReconstructionStatus::kTooFewFrames;
  Reconstruction reconstruction;
  std::vector<int> registered_frames;    // ascending
  std::vector<int> unregistered_frames;  // ascending
  int initial_frame1 = -1;
  int initial_frame2 = -1;
  // What the first initial pair search saw: why kNoInitialPair, and how close it came
  // (sfm/reconstruction_diagnosis.h words it).
  IncrementalMapper::InitialPairSearch initial_pair_search;
  // The 3-D points the initial pair kept (after its bundle adjustment): why kTooFewPoints.
  size_t initial_pair_num_points = 0;
  int num_models = 0;  // models grown (the best is returned)
  // Over all models grown:
  int num_local_ba = 0;
  int num_global_ba = 0;
  // Levenberg-Marquardt iterations summed over those adjustments (their cost, load-free).
  int num_local_ba_iterations = 0;
  int num_global_ba_iterations = 0;
  double local_ba_time_s = 0.0;
  double global_ba_time_s = 0.0;
  // The same as CPU time of the process (all threads): stable when other jobs share the machine.
  double local_ba_cpu_time_s = 0.0;
  double global_ba_cpu_time_s = 0.0;
  BundleAdjustmentSummary final_ba;  // the last global bundle adjustment
  // When global_ba.refine_focal_length asked for the focal: whether the motion let it be
  // refined, as assessed before the last global adjustment (focal_assessed false otherwise).
  bool focal_assessed = false;
  FocalObservability focal_observability;
  // Some intrinsic parameter was refined in at least one global adjustment.
  bool intrinsics_refined = false;
  double wall_time_s = 0.0;  // the whole reconstruction
  double cpu_time_s = 0.0;   // and its CPU time
};

// Reconstructs the frames of `tracks` seen by `camera`: one model, the largest of up to
// options.max_num_models. Throws comic::Error only for invalid input (tracks, camera, options);
// expected failures come back as the status (that of the first attempt when none succeeds).
IncrementalReconstruction ReconstructIncrementally(const frontend::FeatureTracks& tracks,
                                                   const Camera& camera,
                                                   const IncrementalPipelineOptions& options,
                                                   const MapperProgressCallback& progress = {});

}  // namespace comic::sfm
