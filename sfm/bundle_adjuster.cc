#include "sfm/bundle_adjuster.h"

#include <ceres/ceres.h>
#include <ceres/product_manifold.h>
#include <glog/logging.h>

#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <memory>
#include <vector>

#include "io/core/error.h"

namespace comic::sfm {

const char* BundleAdjustmentLossName(BundleAdjustmentLoss loss) {
  switch (loss) {
    case BundleAdjustmentLoss::kTrivial:
      return "trivial";
    case BundleAdjustmentLoss::kHuber:
      return "huber";
    case BundleAdjustmentLoss::kSoftL1:
      return "soft_l1";
  }
  return "unknown";
}

void BundleAdjustmentOptions::Check() const {
  COMIC_CHECK(loss == BundleAdjustmentLoss::kTrivial || loss == BundleAdjustmentLoss::kHuber ||
                  loss == BundleAdjustmentLoss::kSoftL1,
              kInvalidArgument, "bundle adjustment loss is not a BundleAdjustmentLoss");
  COMIC_CHECK(loss_scale_px > 0, kInvalidArgument,
              "bundle adjustment loss_scale_px must be > 0, got " << loss_scale_px);
  COMIC_CHECK(max_num_iterations >= 1, kInvalidArgument,
              "bundle adjustment max_num_iterations must be >= 1");
  COMIC_CHECK(function_tolerance >= 0 && gradient_tolerance >= 0 && parameter_tolerance >= 0,
              kInvalidArgument, "bundle adjustment tolerances must be >= 0");
  COMIC_CHECK(num_threads >= 1, kInvalidArgument, "bundle adjustment num_threads must be >= 1");
  COMIC_CHECK(progress_after_s >= 0, kInvalidArgument,
              "bundle adjustment progress_after_s must be >= 0");
}

bool EvaluateReprojection(const double* pose, const double* point, const double* intrinsics,
                          const Eigen::Vector2d& observed, double* residuals, double* jacobian_pose,
                          double* jacobian_point) {
  // Eigen's rotation of v by q = (u, w): v + 2w (u × v) + 2 u × (u × v), the formula the
  // automatically differentiated cost goes through; differentiated as written (not assuming
  // |q| = 1), so the Jacobian is that of the residual Ceres evaluates.
  const Eigen::Map<const Eigen::Vector3d> u(pose);
  const double w = pose[3];
  const Eigen::Map<const Eigen::Vector3d> translation(pose + 4);
  const Eigen::Map<const Eigen::Vector3d> v(point);
  const Eigen::Vector3d uv = 2.0 * u.cross(v);
  const Eigen::Vector3d point_in_cam = v + w * uv + u.cross(uv) + translation;
  const double inverse_z = 1.0 / point_in_cam.z();
  const double x = point_in_cam.x() * inverse_z;
  const double y = point_in_cam.y() * inverse_z;
  residuals[0] = intrinsics[0] * x + intrinsics[2] - observed.x();
  residuals[1] = intrinsics[1] * y + intrinsics[3] - observed.y();
  if (jacobian_pose == nullptr && jacobian_point == nullptr) return true;
  // d residual / d point_in_cam.
  Eigen::Matrix<double, 2, 3> d_projection;
  d_projection << intrinsics[0] * inverse_z, 0.0, -intrinsics[0] * x * inverse_z, 0.0,
      intrinsics[1] * inverse_z, -intrinsics[1] * y * inverse_z;
  const auto skew = [](const Eigen::Vector3d& a) {
    Eigen::Matrix3d m;
    m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
    return m;
  };
  if (jacobian_point != nullptr) {
    // d/dv: I + 2w [u]x + 2 [u]x [u]x.
    const Eigen::Matrix3d skew_u = skew(u);
    const Eigen::Matrix3d d_rotated =
        Eigen::Matrix3d::Identity() + 2.0 * w * skew_u + 2.0 * skew_u * skew_u;
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> jacobian(jacobian_point);
    jacobian = d_projection * d_rotated;
  }
  if (jacobian_pose != nullptr) {
    // d/du: −2w [v]x + 2 ((u·v) I + u vᵀ − 2 v uᵀ); d/dw: 2 (u × v); d/dt: I.
    Eigen::Matrix<double, 3, 7> d_pose;
    d_pose.block<3, 3>(0, 0) =
        -2.0 * w * skew(v) + 2.0 * (u.dot(v) * Eigen::Matrix3d::Identity() + u * v.transpose() -
                                    2.0 * v * u.transpose());
    d_pose.col(3) = uv;
    d_pose.block<3, 3>(0, 4).setIdentity();
    Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> jacobian(jacobian_pose);
    jacobian = d_projection * d_pose;
  }
  return true;
}

namespace {

// Reprojection residual of one observation, in pixels, through the camera model (the
// distortion of sfm/camera_model.h). Parameter blocks: the image's cam_from_world pose (7: the
// rotation as an Eigen quaternion x, y, z, w, then the translation), the point in world
// coordinates (3) and the camera's parameters in COLMAP's order (kNumParams). One pose block
// with 6 degrees of freedom lets Ceres use its Schur eliminator specialised for 2x3 point and 2x6
// camera Jacobian blocks.
template <CameraModelId kModel>
class ReprojectionCost {
 public:
  explicit ReprojectionCost(const Eigen::Vector2d& observed) : observed_(observed) {}

  template <typename T>
  bool operator()(const T* pose, const T* point_data, const T* intrinsics, T* residuals) const {
    return Residuals(pose, point_data, intrinsics, observed_, residuals);
  }

  template <typename T, typename I>
  static bool Residuals(const T* pose, const T* point_data, const I* intrinsics,
                        const Eigen::Vector2d& observed, T* residuals) {
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(pose);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> translation(pose + 4);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> point(point_data);
    const Eigen::Matrix<T, 3, 1> point_in_cam = rotation * point + translation;
    T x, y;
    ImageFromNormalized(kModel, intrinsics, T(point_in_cam.x() / point_in_cam.z()),
                        T(point_in_cam.y() / point_in_cam.z()), &x, &y);
    residuals[0] = x - T(observed.x());
    residuals[1] = y - T(observed.y());
    return true;
  }

  static constexpr int kNumParams = kModel == CameraModelId::kSimplePinhole  ? 3
                                    : kModel == CameraModelId::kPinhole      ? 4
                                    : kModel == CameraModelId::kSimpleRadial ? 4
                                    : kModel == CameraModelId::kRadial       ? 5
                                                                             : 8;

  static ceres::CostFunction* Create(const Eigen::Vector2d& observed) {
    return new ceres::AutoDiffCostFunction<ReprojectionCost, 2, 7, 3, kNumParams>(
        new ReprojectionCost(observed));
  }

 private:
  Eigen::Vector2d observed_;
};

ceres::CostFunction* CreateReprojectionCost(CameraModelId model, const Eigen::Vector2d& observed) {
  switch (model) {
    case CameraModelId::kSimplePinhole:
      return ReprojectionCost<CameraModelId::kSimplePinhole>::Create(observed);
    case CameraModelId::kPinhole:
      return ReprojectionCost<CameraModelId::kPinhole>::Create(observed);
    case CameraModelId::kSimpleRadial:
      return ReprojectionCost<CameraModelId::kSimpleRadial>::Create(observed);
    case CameraModelId::kRadial:
      return ReprojectionCost<CameraModelId::kRadial>::Create(observed);
    case CameraModelId::kOpenCV:
      return ReprojectionCost<CameraModelId::kOpenCV>::Create(observed);
  }
  return nullptr;
}

// The residual of a distorted camera with its intrinsics held fixed (automatic differentiation
// with respect to pose and point only).
class FixedDistortedReprojectionCost {
 public:
  FixedDistortedReprojectionCost(const Eigen::Vector2d& observed, CameraModelId model,
                                 const double* params)
      : observed_(observed), model_(model), params_(params, params + CameraModelNumParams(model)) {}

  template <typename T>
  bool operator()(const T* pose, const T* point_data, T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(pose);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> translation(pose + 4);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> point(point_data);
    const Eigen::Matrix<T, 3, 1> point_in_cam = rotation * point + translation;
    T x, y;
    ImageFromNormalized(model_, params_.data(), T(point_in_cam.x() / point_in_cam.z()),
                        T(point_in_cam.y() / point_in_cam.z()), &x, &y);
    residuals[0] = x - T(observed_.x());
    residuals[1] = y - T(observed_.y());
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector2d& observed, CameraModelId model,
                                     const double* params) {
    return new ceres::AutoDiffCostFunction<FixedDistortedReprojectionCost, 2, 7, 3>(
        new FixedDistortedReprojectionCost(observed, model, params));
  }

 private:
  Eigen::Vector2d observed_;
  CameraModelId model_;
  std::vector<double> params_;
};

// The same residual with the intrinsics held fixed, with analytic Jacobians: the common case and
// the bulk of the solver's time. Automatic differentiation of it (10-component jets through the
// quaternion rotation and the projection) took about as long as the Schur elimination itself.
class FixedIntrinsicsReprojectionCost : public ceres::SizedCostFunction<2, 7, 3> {
 public:
  FixedIntrinsicsReprojectionCost(const Eigen::Vector2d& observed, const double* intrinsics)
      : observed_(observed),
        intrinsics_{intrinsics[0], intrinsics[1], intrinsics[2], intrinsics[3]} {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    return EvaluateReprojection(parameters[0], parameters[1], intrinsics_.data(), observed_,
                                residuals, jacobians == nullptr ? nullptr : jacobians[0],
                                jacobians == nullptr ? nullptr : jacobians[1]);
  }

  static ceres::CostFunction* Create(const Eigen::Vector2d& observed, const double* intrinsics) {
    return new FixedIntrinsicsReprojectionCost(observed, intrinsics);
  }

 private:
  Eigen::Vector2d observed_;
  std::array<double, 4> intrinsics_;
};

// The translation of the scale-fixing image: R^3 with one coordinate held, but with a 3-D tangent
// space (the held direction's Jacobian column is zero) rather than SubsetManifold's 2-D one. Every
// pose then has 6 tangent dimensions, so Ceres picks its Schur eliminator specialised for 2x3 point
// and 2x6 pose blocks instead of the dynamic-size one (the global adjustments always contain this
// image). The held coordinate gets no gradient, so Levenberg-Marquardt's step leaves it exactly
// where it is, as with SubsetManifold.
class HeldCoordinateManifold : public ceres::Manifold {
 public:
  explicit HeldCoordinateManifold(int held) : held_(held) {}
  int AmbientSize() const override { return 3; }
  int TangentSize() const override { return 3; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    for (int i = 0; i < 3; ++i) x_plus_delta[i] = i == held_ ? x[i] : x[i] + delta[i];
    return true;
  }
  bool PlusJacobian(const double* /*x*/, double* jacobian) const override {
    for (int i = 0; i < 9; ++i) jacobian[i] = 0.0;
    for (int i = 0; i < 3; ++i) jacobian[4 * i] = i == held_ ? 0.0 : 1.0;
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    for (int i = 0; i < 3; ++i) y_minus_x[i] = i == held_ ? 0.0 : y[i] - x[i];
    return true;
  }
  bool MinusJacobian(const double* x, double* jacobian) const override {
    return PlusJacobian(x, jacobian);
  }

 private:
  int held_;
};

// RMS reprojection error (no loss) over the problem's residuals, one per observation, at the
// parameters' current values: ½ Σ ‖r‖² is what Ceres evaluates (the loss left out). Evaluating
// the problem reads its flat parameter blocks; walking the model's maps for every observation
// cost as much as a fifth of a local adjustment on long videos (docs/long_video.md).
double RmsReprojectionError(ceres::Problem* problem, int num_observations) {
  ceres::Problem::EvaluateOptions options;
  options.apply_loss_function = false;
  double half_sum_squared = 0.0;
  if (num_observations == 0 ||
      !problem->Evaluate(options, &half_sum_squared, nullptr, nullptr, nullptr)) {
    return 0.0;
  }
  return std::sqrt(2.0 * half_sum_squared / static_cast<double>(num_observations));
}

}  // namespace

BundleAdjuster::BundleAdjuster(const BundleAdjustmentOptions& options,
                               const BundleAdjustmentConfig& config)
    : options_(options), config_(config) {
  options_.Check();
}

double ProcessCpuSeconds() {
  timespec time{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &time);
  return static_cast<double>(time.tv_sec) + 1e-9 * static_cast<double>(time.tv_nsec);
}

std::set<point3D_t> PointsSeenBy(const Reconstruction& reconstruction,
                                 const std::set<image_t>& image_ids) {
  std::set<point3D_t> point_ids;
  for (image_t image_id : image_ids) {
    for (const Point2D& point2D : reconstruction.image(image_id).points2D) {
      if (point2D.HasPoint3D()) point_ids.insert(point2D.point3D_id);
    }
  }
  return point_ids;
}

std::set<image_t> ConstantNeighbourImages(const Reconstruction& reconstruction,
                                          const std::set<image_t>& image_ids,
                                          const std::set<point3D_t>& point_ids) {
  std::set<image_t> neighbours;
  for (point3D_t point3D_id : point_ids) {
    for (const TrackElement& element : reconstruction.point3D(point3D_id).track) {
      if (!image_ids.count(element.image_id) && reconstruction.image(element.image_id).registered) {
        neighbours.insert(element.image_id);
      }
    }
  }
  return neighbours;
}

namespace {

// What enters the problem, in id order: every observation of the config's images, and the
// observations of their points in other registered images, whose poses stay constant.
struct ProblemContents {
  std::set<point3D_t> point_ids;
  std::set<image_t> neighbour_ids;  // registered images outside the config, poses constant
  std::vector<image_t> image_ids;   // images with at least one observation in the problem
  std::set<camera_t> camera_ids;
  int num_observations = 0;
};

ProblemContents GatherProblemContents(const Reconstruction& reconstruction,
                                      const BundleAdjustmentConfig& config) {
  ProblemContents contents;
  contents.point_ids = PointsSeenBy(reconstruction, config.image_ids);
  std::set<image_t> observing_ids(config.image_ids.begin(), config.image_ids.end());
  contents.neighbour_ids =
      ConstantNeighbourImages(reconstruction, config.image_ids, contents.point_ids);
  observing_ids.insert(contents.neighbour_ids.begin(), contents.neighbour_ids.end());
  for (image_t image_id : observing_ids) {
    const Image& image = reconstruction.image(image_id);
    int num_observations = 0;
    for (const Point2D& point2D : image.points2D) {
      num_observations += point2D.HasPoint3D() && contents.point_ids.count(point2D.point3D_id);
    }
    if (num_observations == 0) continue;
    contents.num_observations += num_observations;
    contents.image_ids.push_back(image_id);
    contents.camera_ids.insert(image.camera_id);
  }
  return contents;
}

// All parameters live in one buffer during the solve (points, then poses as x y z w quaternion
// and translation, then each camera's parameters in COLMAP's order) and are written back
// afterwards. Ceres orders the blocks of an ordering group by address, so one buffer filled in id
// order makes the elimination order, and hence the result, independent of where the heap put
// things. The maps point into `values`, so the struct is filled in place and never copied.
struct ParameterBlocks {
  ParameterBlocks() = default;
  ParameterBlocks(const ParameterBlocks&) = delete;
  ParameterBlocks& operator=(const ParameterBlocks&) = delete;

  std::vector<point3D_t> point_ids;
  std::vector<camera_t> camera_ids;
  std::vector<double> values;
  std::map<point3D_t, double*> points;
  std::map<image_t, double*> poses;
  std::map<camera_t, double*> cameras;
  // Per camera, the indices of its parameters that stay constant; the cameras with some
  // parameter refined.
  std::map<camera_t, std::vector<int>> constant_camera_params;
  std::set<camera_t> variable_cameras;
};

// Indices of the parameters of `camera` (COLMAP's order: focal lengths, principal point,
// distortion) that the options hold constant.
std::vector<int> ConstantCameraParams(const Camera& camera,
                                      const BundleAdjustmentOptions& options) {
  const int num_params = static_cast<int>(CameraModelNumParams(camera.model));
  const int num_focal = CameraModelNumFocalParams(camera.model);
  std::vector<int> constant;
  for (int i = 0; i < num_params; ++i) {
    const bool focal = i < num_focal;
    const bool principal_point = i >= num_focal && i < num_focal + 2;
    const bool refined = (focal && options.refine_focal_length) ||
                         (principal_point && options.refine_principal_point) ||
                         (!focal && !principal_point && options.refine_extra_params);
    if (!refined) constant.push_back(i);
  }
  return constant;
}

void FillParameterBlocks(const Reconstruction& reconstruction, const ProblemContents& contents,
                         const BundleAdjustmentOptions& options, ParameterBlocks* blocks) {
  blocks->point_ids.assign(contents.point_ids.begin(), contents.point_ids.end());
  blocks->camera_ids.assign(contents.camera_ids.begin(), contents.camera_ids.end());
  const size_t pose_offset = 3 * blocks->point_ids.size();
  const size_t camera_offset = pose_offset + 7 * contents.image_ids.size();
  size_t num_camera_params = 0;
  for (camera_t camera_id : blocks->camera_ids) {
    num_camera_params += CameraModelNumParams(reconstruction.camera(camera_id).model);
  }
  blocks->values.assign(camera_offset + num_camera_params, 0.0);
  for (size_t i = 0; i < blocks->point_ids.size(); ++i) {
    double* block = blocks->values.data() + 3 * i;
    Eigen::Map<Eigen::Vector3d> xyz(block);
    xyz = reconstruction.point3D(blocks->point_ids[i]).xyz;
    blocks->points[blocks->point_ids[i]] = block;
  }
  for (size_t i = 0; i < contents.image_ids.size(); ++i) {
    double* block = blocks->values.data() + pose_offset + 7 * i;
    const Rigid3d& pose = reconstruction.image(contents.image_ids[i]).cam_from_world;
    Eigen::Map<Eigen::Vector4d> rotation_coeffs(block);
    Eigen::Map<Eigen::Vector3d> translation(block + 4);
    rotation_coeffs = pose.rotation.normalized().coeffs();
    translation = pose.translation;
    blocks->poses[contents.image_ids[i]] = block;
  }
  size_t camera_block_offset = camera_offset;
  for (camera_t camera_id : blocks->camera_ids) {
    double* block = blocks->values.data() + camera_block_offset;
    const Camera& camera = reconstruction.camera(camera_id);
    const std::vector<double> camera_values = camera.Params();
    std::copy(camera_values.begin(), camera_values.end(), block);
    camera_block_offset += camera_values.size();
    blocks->cameras[camera_id] = block;
    std::vector<int>& constant = blocks->constant_camera_params[camera_id];
    constant = ConstantCameraParams(camera, options);
    if (constant.size() < camera_values.size()) blocks->variable_cameras.insert(camera_id);
  }
}

// The robust loss of the options, owned by the problem it is given to (one object shared by every
// residual); nullptr for plain least squares.
ceres::LossFunction* CreateLoss(const BundleAdjustmentOptions& options) {
  if (options.loss == BundleAdjustmentLoss::kHuber) {
    return new ceres::HuberLoss(options.loss_scale_px);
  }
  if (options.loss == BundleAdjustmentLoss::kSoftL1) {
    return new ceres::SoftLOneLoss(options.loss_scale_px);
  }
  return nullptr;
}

// One residual per observation of a problem point in `image_id`, with the cost its camera needs:
// intrinsics refined, fixed with distortion, or fixed without (the analytic Jacobian).
void AddImageResiduals(const Reconstruction& reconstruction, image_t image_id,
                       const ParameterBlocks& blocks, ceres::LossFunction* loss,
                       ceres::Problem* problem) {
  const Image& image = reconstruction.image(image_id);
  double* pose = blocks.poses.at(image_id);
  for (const Point2D& point2D : image.points2D) {
    if (!point2D.HasPoint3D() || !blocks.points.count(point2D.point3D_id)) continue;
    const Camera& camera = reconstruction.camera(image.camera_id);
    double* point = blocks.points.at(point2D.point3D_id);
    if (blocks.variable_cameras.count(image.camera_id)) {
      problem->AddResidualBlock(CreateReprojectionCost(camera.model, point2D.xy), loss, pose, point,
                                blocks.cameras.at(image.camera_id));
    } else if (camera.HasDistortion()) {
      problem->AddResidualBlock(FixedDistortedReprojectionCost::Create(
                                    point2D.xy, camera.model, blocks.cameras.at(image.camera_id)),
                                loss, pose, point);
    } else {
      // Undistorted and fixed: the analytic cost takes fx, fy, cx, cy.
      const std::array<double, 4> pinhole = {camera.fx, camera.fy, camera.cx, camera.cy};
      problem->AddResidualBlock(FixedIntrinsicsReprojectionCost::Create(point2D.xy, pinhole.data()),
                                loss, pose, point);
    }
  }
}

// The pose of `image_id` constant (config or neighbour), with its scale coordinate held, or free
// on the quaternion manifold. Returns whether the pose is variable.
bool ParameteriseImagePose(const Image& image, image_t image_id,
                           const BundleAdjustmentConfig& config, const ProblemContents& contents,
                           double* pose, ceres::Problem* problem) {
  if (config.constant_pose_ids.count(image_id) || contents.neighbour_ids.count(image_id)) {
    problem->SetParameterBlockConstant(pose);
    return false;
  }
  if (config.fixed_scale_image_ids.count(image_id)) {
    int largest = 0;
    image.cam_from_world.translation.cwiseAbs().maxCoeff(&largest);
    problem->SetManifold(
        pose, new ceres::ProductManifold<ceres::EigenQuaternionManifold, HeldCoordinateManifold>(
                  ceres::EigenQuaternionManifold(), HeldCoordinateManifold(largest)));
  } else {
    problem->SetManifold(
        pose,
        new ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>>());
  }
  return true;
}

// The constant points of the config, and the constant parameters of the refined cameras.
void HoldConstantPointsAndIntrinsics(const Reconstruction& reconstruction,
                                     const BundleAdjustmentConfig& config,
                                     const ParameterBlocks& blocks, ceres::Problem* problem) {
  for (point3D_t point3D_id : config.constant_point_ids) {
    if (blocks.points.count(point3D_id)) {
      problem->SetParameterBlockConstant(blocks.points.at(point3D_id));
    }
  }
  for (camera_t camera_id : blocks.variable_cameras) {
    const std::vector<int>& constant = blocks.constant_camera_params.at(camera_id);
    if (constant.empty()) continue;
    problem->SetManifold(
        blocks.cameras.at(camera_id),
        new ceres::SubsetManifold(CameraModelNumParams(reconstruction.camera(camera_id).model),
                                  constant));
  }
}

// Schur complement: eliminate the points (group 0) first, then solve for the cameras.
std::shared_ptr<ceres::ParameterBlockOrdering> SchurOrdering(const ProblemContents& contents,
                                                             const ParameterBlocks& blocks) {
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (point3D_t point3D_id : blocks.point_ids) {
    ordering->AddElementToGroup(blocks.points.at(point3D_id), 0);
  }
  for (image_t image_id : contents.image_ids) {
    ordering->AddElementToGroup(blocks.poses.at(image_id), 1);
  }
  for (camera_t camera_id : blocks.variable_cameras) {
    ordering->AddElementToGroup(blocks.cameras.at(camera_id), 1);
  }
  return ordering;
}

ceres::Solver::Options SolverOptions(const BundleAdjustmentOptions& options,
                                     int num_variable_images,
                                     std::shared_ptr<ceres::ParameterBlockOrdering> ordering) {
  ceres::Solver::Options solver_options;
  // Dense Schur is fastest for the few dozen cameras of a video window; larger problems need the
  // sparse one.
  constexpr int kMaxDenseImages = 60;
  solver_options.linear_solver_type =
      num_variable_images <= kMaxDenseImages ? ceres::DENSE_SCHUR : ceres::SPARSE_SCHUR;
  if (solver_options.linear_solver_type == ceres::SPARSE_SCHUR &&
      !ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE) &&
      !ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)) {
    solver_options.linear_solver_type = ceres::ITERATIVE_SCHUR;
  }
  solver_options.linear_solver_ordering = std::move(ordering);
  solver_options.max_num_iterations = options.max_num_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  // One thread, whatever num_threads says: Ceres' threaded residual evaluation sums the cost and
  // gradient per thread in the order the threads took the blocks, and its Schur eliminator adds
  // chunk contributions under locks in arrival order, so two threads changed the last bits of the
  // model from run to run (up to 3e-10 relative on the bundled example). Output must be identical
  // bit for bit for any thread count (README).
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  return solver_options;
}

// Copies the solved points, poses (quaternion renormalised) and refined cameras back.
void WriteBack(const ProblemContents& contents, const ParameterBlocks& blocks,
               Reconstruction* reconstruction) {
  for (point3D_t point3D_id : blocks.point_ids) {
    reconstruction->point3D(point3D_id).xyz =
        Eigen::Map<const Eigen::Vector3d>(blocks.points.at(point3D_id));
  }
  for (image_t image_id : contents.image_ids) {
    const double* block = blocks.poses.at(image_id);
    Rigid3d& pose = reconstruction->image(image_id).cam_from_world;
    pose.rotation = Eigen::Quaterniond(block[3], block[0], block[1], block[2]).normalized();
    pose.translation = Eigen::Map<const Eigen::Vector3d>(block + 4);
  }
  for (camera_t camera_id : blocks.variable_cameras) {
    reconstruction->camera(camera_id).SetParams(blocks.cameras.at(camera_id));
  }
}

// Passes Ceres' per-iteration state to BundleAdjustmentOptions::progress once the solve has run
// long enough to deserve a line.
class ProgressReporter : public ceres::IterationCallback {
 public:
  ProgressReporter(const BundleAdjustmentOptions& options, BundleAdjustmentProgress base,
                   std::chrono::steady_clock::time_point start)
      : options_(options), base_(base), start_(start) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& iteration) override {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed >= options_.progress_after_s) {
      BundleAdjustmentProgress progress = base_;
      progress.iteration = iteration.iteration;
      progress.cost = iteration.cost;
      progress.elapsed_s = elapsed;
      progress.first = !reported_;
      reported_ = true;
      options_.progress(progress);
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const BundleAdjustmentOptions& options_;
  const BundleAdjustmentProgress base_;
  bool reported_ = false;
  const std::chrono::steady_clock::time_point start_;
};

}  // namespace

BundleAdjustmentSummary BundleAdjuster::Solve(Reconstruction* reconstruction) const {
  COMIC_CHECK(reconstruction != nullptr, kInvalidArgument, "bundle adjustment: no reconstruction");
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ProcessCpuSeconds();
  BundleAdjustmentSummary summary;
  for (image_t image_id : config_.image_ids) {
    COMIC_CHECK(reconstruction->ExistsImage(image_id) && reconstruction->image(image_id).registered,
                kInvalidArgument,
                "bundle adjustment: image " << image_id << " is unknown or not registered");
  }

  const ProblemContents contents = GatherProblemContents(*reconstruction, config_);
  summary.num_residuals = contents.num_observations;
  if (summary.num_residuals == 0) {
    summary.termination = "no observations";
    return summary;
  }
  summary.num_images = static_cast<int>(contents.image_ids.size());
  summary.num_points = static_cast<int>(contents.point_ids.size());

  ParameterBlocks blocks;
  FillParameterBlocks(*reconstruction, contents, options_, &blocks);
  summary.refined_intrinsics = !blocks.variable_cameras.empty();

  ceres::Problem problem;
  ceres::LossFunction* loss = CreateLoss(options_);
  for (image_t image_id : contents.image_ids) {
    AddImageResiduals(*reconstruction, image_id, blocks, loss, &problem);
    summary.num_variable_images +=
        ParameteriseImagePose(reconstruction->image(image_id), image_id, config_, contents,
                              blocks.poses.at(image_id), &problem);
  }
  HoldConstantPointsAndIntrinsics(*reconstruction, config_, blocks, &problem);
  ceres::Solver::Options solver_options =
      SolverOptions(options_, summary.num_variable_images, SchurOrdering(contents, blocks));
  BundleAdjustmentProgress progress_base;
  progress_base.max_num_iterations = options_.max_num_iterations;
  progress_base.num_variable_images = summary.num_variable_images;
  progress_base.num_points = summary.num_points;
  ProgressReporter reporter(options_, progress_base, start);
  if (options_.progress) solver_options.callbacks.push_back(&reporter);

  summary.initial_rmse_px = RmsReprojectionError(&problem, contents.num_observations);
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, &problem, &ceres_summary);

  summary.usable = ceres_summary.IsSolutionUsable();
  summary.num_iterations = static_cast<int>(ceres_summary.iterations.size());
  summary.initial_cost = ceres_summary.initial_cost;
  summary.final_cost = ceres_summary.final_cost;
  summary.termination =
      std::string(ceres::TerminationTypeToString(ceres_summary.termination_type)) + ": " +
      ceres_summary.message;
  // Ceres leaves the parameter blocks at the solution it returns; an unusable one is not written
  // back, so the model keeps its initial error.
  summary.final_rmse_px = summary.usable ? RmsReprojectionError(&problem, contents.num_observations)
                                         : summary.initial_rmse_px;
  if (summary.usable) WriteBack(contents, blocks, reconstruction);
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.cpu_time_s = ProcessCpuSeconds() - cpu_start;
  return summary;
}

void ShowOnlySolverErrors() { FLAGS_minloglevel = google::GLOG_ERROR; }

}  // namespace comic::sfm
