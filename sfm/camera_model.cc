#include "sfm/camera_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace comic::sfm {

namespace {

struct ModelInfo {
  CameraModelId id;
  const char* name;
  int num_params;
  int num_focal_params;
  const char* params_info;
};

constexpr std::array<ModelInfo, 5> kModels = {{
    {CameraModelId::kSimplePinhole, "SIMPLE_PINHOLE", 3, 1, "f, cx, cy"},
    {CameraModelId::kPinhole, "PINHOLE", 4, 2, "fx, fy, cx, cy"},
    {CameraModelId::kSimpleRadial, "SIMPLE_RADIAL", 4, 1, "f, cx, cy, k"},
    {CameraModelId::kRadial, "RADIAL", 5, 1, "f, cx, cy, k1, k2"},
    {CameraModelId::kOpenCV, "OPENCV", 8, 2, "fx, fy, cx, cy, k1, k2, p1, p2"},
}};

const ModelInfo& Info(CameraModelId model) { return kModels.at(static_cast<size_t>(model)); }

}  // namespace

std::string CameraModelName(CameraModelId model) { return Info(model).name; }

std::optional<CameraModelId> CameraModelFromName(const std::string& name) {
  for (const ModelInfo& info : kModels) {
    if (name == info.name) return info.id;
  }
  return std::nullopt;
}

std::optional<CameraModelId> CameraModelFromId(int id) {
  if (id < 0 || id >= static_cast<int>(kModels.size())) return std::nullopt;
  return kModels[static_cast<size_t>(id)].id;
}

std::string CameraModelNames() {
  std::string names;
  for (const ModelInfo& info : kModels)
    names += (names.empty() ? "" : ", ") + std::string(info.name);
  return names;
}

int CameraModelNumParams(CameraModelId model) { return Info(model).num_params; }

int CameraModelNumFocalParams(CameraModelId model) { return Info(model).num_focal_params; }

std::string CameraModelParamsInfo(CameraModelId model) { return Info(model).params_info; }

Eigen::Vector2d NormalizedFromImage(CameraModelId model, const double* params,
                                    const Eigen::Vector2d& pixel) {
  const int pp = CameraModelPrincipalPointIndex(model);
  const double fx = params[0];
  const double fy = params[pp == 1 ? 0 : 1];
  // The distorted normalised point; the undistorted one u solves u + d(u) = distorted.
  const Eigen::Vector2d distorted((pixel.x() - params[pp]) / fx, (pixel.y() - params[pp + 1]) / fy);
  if (CameraModelNumExtraParams(model) == 0) return distorted;
  const double* extra = params + pp + 2;
  // Newton's method on f(u) = u + d(u) − distorted with a central-difference Jacobian, as
  // COLMAP's IterativeUndistortion: stops when the step is tiny relative to the point.
  constexpr int kMaxIterations = 100;
  constexpr double kMaxStepSquared = 1e-20;
  constexpr double kRelativeStep = 1e-6;
  Eigen::Vector2d u = distorted;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const double step_x =
        std::max(std::numeric_limits<double>::epsilon(), std::abs(u.x() * kRelativeStep));
    const double step_y =
        std::max(std::numeric_limits<double>::epsilon(), std::abs(u.y() * kRelativeStep));
    double du, dv;
    DistortionOffset(model, extra, u.x(), u.y(), &du, &dv);
    double du_x0, dv_x0, du_x1, dv_x1, du_y0, dv_y0, du_y1, dv_y1;
    DistortionOffset(model, extra, u.x() - step_x, u.y(), &du_x0, &dv_x0);
    DistortionOffset(model, extra, u.x() + step_x, u.y(), &du_x1, &dv_x1);
    DistortionOffset(model, extra, u.x(), u.y() - step_y, &du_y0, &dv_y0);
    DistortionOffset(model, extra, u.x(), u.y() + step_y, &du_y1, &dv_y1);
    Eigen::Matrix2d jacobian;
    jacobian(0, 0) = 1.0 + (du_x1 - du_x0) / (2.0 * step_x);
    jacobian(0, 1) = (du_y1 - du_y0) / (2.0 * step_y);
    jacobian(1, 0) = (dv_x1 - dv_x0) / (2.0 * step_x);
    jacobian(1, 1) = 1.0 + (dv_y1 - dv_y0) / (2.0 * step_y);
    const Eigen::Vector2d residual = u + Eigen::Vector2d(du, dv) - distorted;
    const Eigen::Vector2d step = jacobian.inverse() * residual;
    u -= step;
    if (!u.allFinite()) return u;
    if (step.squaredNorm() < kMaxStepSquared * std::max(1.0, u.squaredNorm())) break;
  }
  return u;
}

}  // namespace comic::sfm
