// The camera models of COLMAP's camera_models.h that a perspective lens needs, with COLMAP's
// names, ids and parameter order (pixel values here in OpenCV's convention, see sfm/camera.h):
//
//   SIMPLE_PINHOLE (0)  f, cx, cy
//   PINHOLE        (1)  fx, fy, cx, cy
//   SIMPLE_RADIAL  (2)  f, cx, cy, k
//   RADIAL         (3)  f, cx, cy, k1, k2
//   OPENCV         (4)  fx, fy, cx, cy, k1, k2, p1, p2
//
// A point (u, v) on the normalised image plane (z = 1) is distorted as OpenCV and COLMAP do,
// with r² = u² + v²:
//   u' = u (1 + k1 r² + k2 r⁴) + 2 p1 u v + p2 (r² + 2 u²)
//   v' = v (1 + k1 r² + k2 r⁴) + p1 (r² + 2 v²) + 2 p2 u v
// and mapped to pixels as (fx u' + cx, fy v' + cy). Undistortion inverts the distortion by
// Newton's method (COLMAP's IterativeUndistortion).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace comic::sfm {

enum class CameraModelId : int {
  kSimplePinhole = 0,
  kPinhole = 1,
  kSimpleRadial = 2,
  kRadial = 3,
  kOpenCV = 4,
};

// "SIMPLE_PINHOLE", ... as COLMAP spells them.
std::string CameraModelName(CameraModelId model);
// The model of a name (as CameraModelName spells it); std::nullopt for any other name.
std::optional<CameraModelId> CameraModelFromName(const std::string& name);
// The model of a COLMAP id 0..4; std::nullopt for any other id.
std::optional<CameraModelId> CameraModelFromId(int id);
// The names of every model, comma separated (for messages).
std::string CameraModelNames();
// Number of parameters in COLMAP's order (3, 4, 4, 5, 8).
int CameraModelNumParams(CameraModelId model);
// One shared focal length (SIMPLE_*, RADIAL) or fx and fy.
int CameraModelNumFocalParams(CameraModelId model);
// Index of cx in the parameter vector (1 or 2); cy follows it; distortion follows cy.
inline int CameraModelPrincipalPointIndex(CameraModelId model) {
  return CameraModelNumFocalParams(model);
}
// Number of distortion parameters (0, 0, 1, 2, 4).
inline int CameraModelNumExtraParams(CameraModelId model) {
  return CameraModelNumParams(model) - CameraModelNumFocalParams(model) - 2;
}
// The parameter names in order, e.g. "f, cx, cy, k".
std::string CameraModelParamsInfo(CameraModelId model);

// The distortion offset (du, dv) = (u', v') − (u, v) of a normalised point for `extra` (the
// model's distortion parameters in order). Templated for automatic differentiation.
template <typename T, typename P>
void DistortionOffset(CameraModelId model, const P* extra, const T& u, const T& v, T* du, T* dv) {
  switch (model) {
    case CameraModelId::kSimplePinhole:
    case CameraModelId::kPinhole:
      *du = T(0.0);
      *dv = T(0.0);
      return;
    case CameraModelId::kSimpleRadial: {
      const T radial = extra[0] * (u * u + v * v);
      *du = u * radial;
      *dv = v * radial;
      return;
    }
    case CameraModelId::kRadial: {
      const T r2 = u * u + v * v;
      const T radial = extra[0] * r2 + extra[1] * r2 * r2;
      *du = u * radial;
      *dv = v * radial;
      return;
    }
    case CameraModelId::kOpenCV: {
      const T uu = u * u;
      const T uv = u * v;
      const T vv = v * v;
      const T r2 = uu + vv;
      const T radial = extra[0] * r2 + extra[1] * r2 * r2;
      *du = u * radial + T(2.0) * extra[2] * uv + extra[3] * (r2 + T(2.0) * uu);
      *dv = v * radial + T(2.0) * extra[3] * uv + extra[2] * (r2 + T(2.0) * vv);
      return;
    }
  }
}

// Pixel of a normalised point: distortion, then focal length and principal point. `params` in
// the model's order.
template <typename T, typename P>
void ImageFromNormalized(CameraModelId model, const P* params, const T& u, const T& v, T* x, T* y) {
  const int pp = CameraModelPrincipalPointIndex(model);
  T du = T(0.0);
  T dv = T(0.0);
  DistortionOffset(model, params + pp + 2, u, v, &du, &dv);
  const P& fx = params[0];
  const P& fy = params[pp == 1 ? 0 : 1];
  *x = fx * (u + du) + params[pp];
  *y = fy * (v + dv) + params[pp + 1];
}

// The normalised point of a pixel: inverse of ImageFromNormalized, the distortion inverted by
// Newton iterations (at most 100, until the step is below 1e-10 of the point's norm, as COLMAP's
// IterativeUndistortion).
Eigen::Vector2d NormalizedFromImage(CameraModelId model, const double* params,
                                    const Eigen::Vector2d& pixel);

}  // namespace comic::sfm
