// Bundle adjustment of a Reconstruction on Ceres (with sfm/pose_graph.cc the only places the
// project uses Ceres; its types stay in the .cc files). One reprojection cost per observation with
// a Huber loss, Schur elimination with points eliminated first, intrinsics held fixed or with any
// of focal length, principal point and distortion refined, and the gauge fixed by constant poses
// chosen in the config.
//
//   BundleAdjustmentConfig config;
//   for (image_t id : reconstruction.RegisteredImageIds()) config.image_ids.insert(id);
//   config.constant_pose_ids.insert(first_id);        // fixes position and orientation
//   config.fixed_scale_image_ids.insert(second_id);   // fixes the scale
//   BundleAdjuster adjuster(options, config);
//   const BundleAdjustmentSummary summary = adjuster.Solve(&reconstruction);
#pragma once

#include <functional>
#include <set>
#include <string>

#include "sfm/reconstruction.h"

namespace comic::sfm {

// The loss applied to each observation's squared reprojection error (COLMAP's
// loss_function_type): kTrivial is plain least squares; kHuber and kSoftL1 count residuals longer
// than loss_scale_px about linearly, so that a wrong observation pulls less.
enum class BundleAdjustmentLoss { kTrivial, kHuber, kSoftL1 };

// "trivial", "huber", "soft_l1".
const char* BundleAdjustmentLossName(BundleAdjustmentLoss loss);

// Where a long adjustment stands, for progress lines: the last global adjustment of a long clip
// runs for many seconds (docs/long_video.md).
struct BundleAdjustmentProgress {
  bool first = false;  // the solve's first report (a front door may start a new line of output)
  int iteration = 0;   // Levenberg-Marquardt iterations done
  int max_num_iterations = 0;
  int num_variable_images = 0;
  int num_points = 0;
  double cost = 0.0;       // Ceres cost ½ Σ ρ(‖r‖²) after this iteration, pixels²
  double elapsed_s = 0.0;  // wall time since the solve started
};
using BundleAdjustmentProgressCallback = std::function<void(const BundleAdjustmentProgress&)>;

struct BundleAdjustmentOptions {
  // Robust loss and its scale (pixels; ignored by kTrivial). A robust loss costs iterations: with
  // many residuals in its linear part Ceres' model of the cost is a reweighted one, and
  // Levenberg-Marquardt then converges linearly (on KITTI the final global adjustment of Harris
  // tracks took 23 iterations with Huber, 2 without; docs/sfm.md "Loss").
  BundleAdjustmentLoss loss = BundleAdjustmentLoss::kHuber;
  double loss_scale_px = 1.0;
  // Levenberg–Marquardt iterations at most.
  int max_num_iterations = 100;
  // Ceres stopping tolerances (relative cost change, gradient, relative step).
  double function_tolerance = 1e-6;
  double gradient_tolerance = 1e-10;
  double parameter_tolerance = 1e-8;
  // Intrinsics to refine, each on or off (COLMAP's ba_refine_focal_length, _principal_point,
  // _extra_params): the focal length (one for SIMPLE_* and RADIAL, fx and fy otherwise), the
  // principal point and the distortion coefficients of the camera's model (sfm/camera_model.h).
  // All off: intrinsics are constant (analytic Jacobians for undistorted cameras).
  bool refine_focal_length = false;
  bool refine_principal_point = false;
  bool refine_extra_params = false;
  // Threads the caller offers. Ceres itself always runs on one thread (bundle_adjuster.cc: its
  // threaded sums depend on the thread schedule), so the result is identical bit for bit for any
  // value; kept so that one --threads reaches every stage.
  int num_threads = 1;
  // Called after each iteration once the solve has run progress_after_s seconds (wall time); it
  // only reports: the solution is the same with or without it.
  BundleAdjustmentProgressCallback progress;
  double progress_after_s = 1.0;

  void Check() const;
};

struct BundleAdjustmentConfig {
  // Images whose observations enter the problem (must be registered). The points they see are
  // refined; those points' observations in other registered images enter too, with those images'
  // poses held constant, so a local window stays anchored to the rest of the model.
  std::set<image_t> image_ids;
  // Images among image_ids whose pose stays fixed.
  std::set<image_t> constant_pose_ids;
  // Images among image_ids whose translation keeps its largest coordinate fixed: with one
  // constant pose this removes the remaining scale freedom.
  std::set<image_t> fixed_scale_image_ids;
  // 3-D points held fixed (others seen by image_ids are refined).
  std::set<point3D_t> constant_point_ids;
};

struct BundleAdjustmentSummary {
  bool usable = false;  // Ceres returned a usable solution (the reconstruction was updated)
  int num_images = 0;   // images in the problem (variable and constant, neighbours included)
  int num_variable_images = 0;
  int num_points = 0;
  int num_residuals = 0;  // observations
  int num_iterations = 0;
  double initial_cost = 0.0;     // Ceres cost ½ Σ ρ(‖r‖²) before, pixels²
  double final_cost = 0.0;       // and after
  double initial_rmse_px = 0.0;  // RMS reprojection error (no loss) before
  double final_rmse_px = 0.0;    // and after
  double wall_time_s = 0.0;
  // CPU time of the whole process during the solve (all threads): unlike the wall time it does
  // not grow when other jobs share the machine.
  double cpu_time_s = 0.0;
  std::string termination;          // Ceres's termination type and message
  bool refined_intrinsics = false;  // some intrinsic parameter was variable
};

// The reprojection residual of one observation with fixed intrinsics (fx, fy, cx, cy), in
// pixels, and optionally its Jacobians (row-major 2x7 with respect to the pose x y z w tx ty tz,
// 2x3 with respect to the point; either may be null): the cost the adjuster minimises when the
// intrinsics are constant. Returns true. Exposed so that the analytic Jacobian can be tested.
bool EvaluateReprojection(const double* pose, const double* point, const double* intrinsics,
                          const Eigen::Vector2d& observed, double* residuals, double* jacobian_pose,
                          double* jacobian_point);

// CPU time consumed by this process so far (all threads), seconds.
double ProcessCpuSeconds();

// The 3-D points the images observe: what an adjustment of those images refines.
std::set<point3D_t> PointsSeenBy(const Reconstruction& reconstruction,
                                 const std::set<image_t>& image_ids);

// Registered images outside `image_ids` that observe one of `point_ids`: an adjustment of
// `image_ids` (and of the points they see) holds these images' poses constant.
std::set<image_t> ConstantNeighbourImages(const Reconstruction& reconstruction,
                                          const std::set<image_t>& image_ids,
                                          const std::set<point3D_t>& point_ids);

class BundleAdjuster {
 public:
  // Throws comic::Error(kInvalidArgument) for invalid options.
  BundleAdjuster(const BundleAdjustmentOptions& options, const BundleAdjustmentConfig& config);

  // Refines the poses, points (and focal lengths if asked) in place. Throws comic::Error for a
  // config naming unknown or unregistered images. A problem without observations returns a
  // summary with usable == false and leaves the reconstruction untouched.
  BundleAdjustmentSummary Solve(Reconstruction* reconstruction) const;

 private:
  BundleAdjustmentOptions options_;
  BundleAdjustmentConfig config_;
};

// Ceres reports solver trouble it recovers from (e.g. "Linear solver failure", after which
// Levenberg–Marquardt simply raises its damping) as glog warnings on stderr. That logger is
// process-wide, so the library leaves it alone; an app that owns the process and wants stderr for
// its own messages calls this once at start-up to show only glog errors.
void ShowOnlySolverErrors();

}  // namespace comic::sfm
