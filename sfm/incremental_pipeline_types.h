// The types of the incremental reconstruction (sfm/incremental_pipeline.h) that its stages share:
// the options, the status, the progress callback, the models and the result. The stages
// (sfm/model_growth.h, sfm/unregistered_ranges.h) include this header, not the pipeline's, so that
// the pipeline can include them.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sfm/bundle_adjuster.h"
#include "sfm/camera.h"
#include "sfm/focal_observability.h"
#include "sfm/incremental_mapper.h"
#include "sfm/intrinsics_plausibility.h"
#include "sfm/keyframe_selection.h"
#include "sfm/loop_closure.h"
#include "sfm/model_self_check.h"
#include "sfm/planar_pose_ambiguity.h"
#include "sfm/reconstruction.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

enum class ReconstructionStatus {
  // At least success_min_registered_fraction of the frames are in the largest model.
  kSuccess,
  // Models, but the largest holds fewer frames: unregistered_ranges say which and why.
  kPartial,
  kTooFewFrames,   // fewer than two frames
  kNoInitialPair,  // no frame pair with enough matches and parallax (e.g. pure rotation)
  kTooFewPoints,   // the initial pair triangulated too few points
  // A model, but its own frame pairs contradict it (sfm/model_self_check.h): not called success
  // whatever it registered. The models are written all the same.
  kSuspect,
};

// "success", "partial", "too_few_frames", "no_initial_pair", "too_few_points".
const char* ReconstructionStatusName(ReconstructionStatus status);
// A sentence for users, e.g. for a status without a model in an app's error line.
std::string ReconstructionStatusMessage(ReconstructionStatus status);
// kSuccess, kPartial or kSuspect: there is at least one model.
bool HasModel(ReconstructionStatus status);

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
  // Those adjustments hold at most this many of the most recently registered (key)frames
  // variable, with every point they see; older frames seeing those points are held constant
  // (0: every frame). The final adjustment of a model larger than the window is one sweep of
  // overlapping windows of this many keyframes (IncrementalMapper::AdjustGlobalBundleInWindows),
  // with the intrinsics held. Long video: an adjustment of the whole model costs in proportion to
  // it, so whole-model adjustments make the cost per frame grow with the video
  // (docs/long_video.md).
  int global_ba_max_images = 0;
  // Attempts to register a frame before it is given up.
  int max_registration_trials = 3;
  // The initial pair must triangulate at least this many points.
  int min_num_initial_points = 30;
  // Models started at most (COLMAP's max_num_models). When registration stops, a new model is
  // started from an initial pair among the frames no model has registered, as COLMAP's mapper
  // does, until every frame is in a model or no pair qualifies; every model is kept.
  int max_num_models = 50;
  // When no frame pair qualifies as the initial pair, search once more with the minimum shared
  // tracks and inliers (mapper.init_min_num_matches, init_min_num_inliers) halved, as COLMAP
  // relaxes its initialisation constraints. A sparsely tracked sequence (MSER on the dino ring:
  // 774 tracks) then starts a model instead of none; sequences whose strict search succeeds are
  // unaffected. If that finds nothing either, a third search also accepts a pair a homography
  // explains when it has parallax (IncrementalMapper::Options::init_accept_planar).
  bool relax_initial_pair = true;
  // An initial pair with a planar alternative (IncrementalMapper::Options::
  // init_find_planar_alternative) is started from the pose the clip's other frames side with
  // (CompareByThirdViews, sfm/planar_pose_ambiguity.h): on a nearly flat scene the essential
  // matrix's pose may be the homography's wrong solution, and a model grown from it registers
  // every frame with its cameras turned degrees away. Off: always the essential matrix's pose.
  bool choose_planar_pose = true;
  ThirdViewOptions planar_third_views;
  // A growth stops once this many frames are registered (0: no limit).
  int max_registered_frames = 0;
  // Models are merged into the model being grown (IncrementalMapper::MergeModel) when it stops
  // short, and once it has registered merge_overlap_frames frames of an earlier model (and again
  // at each doubling of that overlap), so that a model does not grow again all an earlier one
  // holds (COLMAP stops a model at 20 shared images, max_model_overlap); the merged model grows
  // on from the merged frames. Merging early takes the earlier model's poses of frames this one
  // would have registered itself: at 3 shared frames the temple ring's hessian run merged two
  // frames 19 and 43 deg off (ATE 1.6 % of the path instead of 0.03 %).
  bool merge_models = true;
  int merge_overlap_frames = 20;
  // When a model stops short and a FrameMatcher is given, its frames facing an earlier model it
  // could not merge across a gap of at most seam_max_frame_gap frames (seam_num_frames on each
  // side; no other model in between) are matched, and the matches link the two models
  // (IncrementalMapper::FeatureLink): a stretch without texture, or where tracking failed, breaks
  // the clip into two models that are joined again where the scene is seen again.
  int seam_num_frames = 2;
  int seam_max_frame_gap = 30;
  // Frames without a pose after the models are grown (sfm/pose_gap_filling.h): a frame the
  // camera reached by turning (or barely moving) from a registered neighbour gets its rotation
  // against the map (registered, flagged); a frame between two registered frames of a model at
  // most max_interpolated_gap frames apart gets an interpolated pose, kept beside the model and
  // never registered. For video only: the frames must be in the order they were taken
  // (sfm/run/run_options.h turns it off for image sets).
  bool fill_pose_gaps = true;
  int max_interpolated_gap = 10;
  // kSuccess needs at least this fraction of the frames registered in the largest model.
  double success_min_registered_fraction = 0.95;
  // The largest model is checked against its own frame pairs (sfm/model_self_check.h) and
  // called kSuspect when they contradict it.
  bool self_check = true;
  ModelSelfCheckOptions self_check_options;
  // When the largest model is suspect, a model holding at least this fraction of its frames
  // that its own pairs do not contradict is returned first instead (ChooseKeptModel).
  double self_check_yield_fraction = 0.8;
  // The plausible range of a self-calibrated camera (sfm/intrinsics_plausibility.h): outside it
  // the camera is reset to its prior, held fixed and the model adjusted again.
  IntrinsicsPlausibilityOptions plausible_intrinsics;
  // The mapper works on images whose larger side is at most this (pixels; 0: any size): larger
  // tracks and cameras are scaled down for the work and the model is returned in the input's
  // pixels (sfm/working_resolution.h), because its pixel thresholds (PnP, triangulation,
  // filtering) are tuned at ~700 px. 1280 keeps KITTI (1226 x 370) as it is and takes 1080p
  // video to 720p; Herz-Jesu at 3072 x 2048 self-calibrates to within 0.2 % at 1280 and 1600
  // (docs/sfm.md "Working resolution"). comic_sfm tracks at the same size.
  int max_working_image_size = 1280;
  // Keyframes (sfm/keyframe_selection.h; ORB-SLAM's rule on the tracks): only keyframes add
  // points to the map and enter bundle adjustments; the other frames are registered by PnP
  // against the map as they come (every frame keeps a pose) and posed again against the final
  // map at the end of their model's growth (IncrementalMapper::LocalizeNonKeyframes). A frame
  // registering while neither keyframe beside it has is made one. For long, dense video: the
  // adjustments then grow with the keyframes, not the frames (docs/long_video.md).
  bool keyframes_only = false;
  KeyframeOptions keyframes;
  // Loop closure (sfm/loop_closure.h) at the end of each model's growth, before its final
  // adjustment: revisited places found by appearance among the keyframes, verified, closed by a
  // Sim(3) pose graph and fused points. Needs tracks with descriptors.
  bool close_loops = false;
  LoopClosureOptions loop_closure;

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

// Matches between the features of two frames the tracks do not link (e.g. on both sides of a
// stretch where tracking failed): pairs (feature index in frame1, feature index in frame2),
// geometrically verified. Given by whoever has the images (sfm/sequence_reconstruction.h).
using FrameMatcher = std::function<std::vector<std::pair<int, int>>(int frame1, int frame2)>;

// How a frame of a model got its pose.
enum class PoseSource {
  kRegistered,    // initial pair, PnP, or a merged model's
  kRotationOnly,  // its rotation against the map; the centre of a registered neighbour
  kInterpolated,  // interpolated between registered frames of the model: a guess, not registered
};
// "registered", "rotation_only", "interpolated".
const char* PoseSourceName(PoseSource source);

// One model of the run.
struct IncrementalModel {
  Reconstruction reconstruction;
  // Every frame registered in the model (a pose from observations), ascending.
  std::vector<int> registered_frames;
  // Of those, the frames posed by their rotation against the map (sfm/pose_gap_filling.h).
  std::vector<int> rotation_only_frames;
  // Frames not registered whose pose was interpolated between registered frames of this model
  // (ascending; a guess, kept out of the reconstruction), and those poses.
  std::vector<int> interpolated_frames;
  std::vector<Rigid3d> interpolated_poses;
  int initial_frame1 = -1;
  int initial_frame2 = -1;
  int num_merged_models = 0;  // earlier models merged into it
  // Frames registered from observations: registered_frames (interpolated frames are not in it).
  size_t NumObservedFrames() const;
};

// A run of consecutive frames missing from the largest model for one reason: the stage and the
// check that failed, as DiagnoseReconstruction words a failed run.
struct UnregisteredRange {
  int first_frame = 0;
  int last_frame = 0;
  // "tracking" (check "features": too few features detected, a stretch without texture;
  // "tracked_features": too few of them in tracks), "registration" ("visible_points": too few
  // tracks with a 3-D point of the model; "pose_inliers": PnP found too few inliers),
  // "linking" ("other_model": the frames are in another model that could not be merged).
  std::string stage;
  std::string check;
  double value = 0.0;    // the best measured over the range
  double needed = 0.0;   // the threshold it missed
  int other_model = -1;  // check "other_model": its index in other_models
  std::string message;   // one sentence
};

// What became of a self-calibrated camera that left the plausible range.
struct IntrinsicsRejection {
  bool rejected = false;
  Camera rejected_camera;  // what self-calibration gave
  std::string reason;      // e.g. "focal length 2880 px is 3.75x the prior 768 px (at most 3x)"
};

struct IncrementalReconstruction {
  ReconstructionStatus status = ReconstructionStatus::kTooFewFrames;
  // The largest model (most frames registered from observations; ties by the earlier start).
  Reconstruction reconstruction;
  // Ascending: the frames registered in the largest model (poses from observations), and the
  // others (the interpolated ones among them).
  std::vector<int> registered_frames;
  std::vector<int> unregistered_frames;
  std::vector<int> rotation_only_frames;  // of registered_frames, see IncrementalModel
  // Of unregistered_frames, those with a pose interpolated in the largest model, and the poses
  // (see IncrementalModel).
  std::vector<int> interpolated_frames;
  std::vector<Rigid3d> interpolated_poses;
  int initial_frame1 = -1;
  int initial_frame2 = -1;
  // Every other model, largest first.
  std::vector<IncrementalModel> other_models;
  // The frames missing from the largest model, in ranges with the reason.
  std::vector<UnregisteredRange> unregistered_ranges;
  // The largest model against its own frame pairs (with options.self_check); suspect: kSuspect.
  ModelSelfCheck self_check;
  // What the first initial pair search saw: why kNoInitialPair, and how close it came
  // (sfm/reconstruction_diagnosis.h words it).
  IncrementalMapper::InitialPairSearch initial_pair_search;
  // The 3-D points the initial pair kept (after its bundle adjustment): why kTooFewPoints.
  size_t initial_pair_num_points = 0;
  int num_models = 0;      // models started (attempts; merged ones included)
  int num_merges = 0;      // models merged into others
  int num_seam_links = 0;  // of those, merged through matches at their seams or by appearance
  // With close_loops: the models linked by appearance (LinkModelsByAppearance), seam matching
  // having found nothing.
  int num_appearance_links = 0;
  // The initial pair searches and the seam matches (FrameMatcher calls), with their CPU time.
  int num_initial_pair_searches = 0;
  double initial_pair_search_cpu_time_s = 0.0;
  // Each initial pair whose two planar poses were compared (choose_planar_pose), in the order
  // the models were started.
  std::vector<PlanarPoseChoice> planar_pose_choices;
  int num_seam_matches = 0;
  double seam_matching_cpu_time_s = 0.0;
  // Over all models grown:
  int num_local_ba = 0;
  int num_global_ba = 0;
  int num_final_ba_windows = 0;  // of those, windows of bounded final adjustments
  // Levenberg-Marquardt iterations summed over those adjustments (their cost, load-free).
  int num_local_ba_iterations = 0;
  int num_global_ba_iterations = 0;
  double local_ba_time_s = 0.0;
  double global_ba_time_s = 0.0;
  // The same as CPU time of the process (all threads): stable when other jobs share the machine.
  double local_ba_cpu_time_s = 0.0;
  double global_ba_cpu_time_s = 0.0;
  // With keyframes_only: the selection's decision per frame, with the mapper's changes (initial
  // pairs, promotions) in `keyframe_decisions[f].reason`; the frames of the largest model that
  // are not keyframes; those a model registered but could not pose again against its final
  // map (deregistered; pose gap filling may interpolate them). Empty otherwise.
  std::vector<KeyframeDecision> keyframe_decisions;
  std::vector<int> non_keyframes_lost;
  // With close_loops: what loop closure found and did in the largest model.
  std::optional<LoopClosureSummary> loop_closure;
  BundleAdjustmentSummary final_ba;  // the last global bundle adjustment of the largest model
  // When global_ba.refine_focal_length asked for the focal: whether the motion let it be
  // refined, as assessed before the last global adjustment (focal_assessed false otherwise).
  bool focal_assessed = false;
  FocalObservability focal_observability;
  // Some intrinsic parameter was refined in at least one global adjustment of the largest model
  // (and kept: see intrinsics_rejection).
  bool intrinsics_refined = false;
  IntrinsicsRejection intrinsics_rejection;
  // The mapper worked at working_scale x the input's pixels (1: at the input's size); every
  // model is returned in the input's pixels.
  double working_scale = 1.0;
  double wall_time_s = 0.0;  // the whole reconstruction
  double cpu_time_s = 0.0;   // and its CPU time

  size_t NumModels() const { return HasModel(status) ? 1 + other_models.size() : 0; }
};

}  // namespace comic::sfm
