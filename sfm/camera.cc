#include "sfm/camera.h"

#include <algorithm>
#include <cmath>

#include "io/error.h"

namespace comic::sfm {

Camera Camera::FromImageSize(int width, int height) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = 1.2 * std::max(width, height);
  camera.cx = (width - 1) / 2.0;
  camera.cy = (height - 1) / 2.0;
  camera.Check();
  return camera;
}

Camera Camera::Scaled(double factor) const {
  COMIC_CHECK(factor > 0, kInvalidArgument, "camera scale factor must be > 0, got " << factor);
  Camera scaled = *this;
  scaled.width = static_cast<int>(std::lround(width * factor));
  scaled.height = static_cast<int>(std::lround(height * factor));
  scaled.fx = fx * factor;
  scaled.fy = fy * factor;
  // Pixel centre c maps to (c + 0.5) · factor − 0.5.
  scaled.cx = (cx + 0.5) * factor - 0.5;
  scaled.cy = (cy + 0.5) * factor - 0.5;
  return scaled;
}

Eigen::Matrix3d Camera::K() const {
  Eigen::Matrix3d k;
  k << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return k;
}

void Camera::Check() const {
  COMIC_CHECK(width > 0 && height > 0, kInvalidArgument,
              "camera size must be positive, got " << width << "x" << height);
  COMIC_CHECK(fx > 0 && fy > 0 && std::isfinite(fx) && std::isfinite(fy), kInvalidArgument,
              "camera focal lengths must be positive, got fx=" << fx << " fy=" << fy);
  COMIC_CHECK(std::isfinite(cx) && std::isfinite(cy), kInvalidArgument,
              "camera principal point must be finite");
}

}  // namespace comic::sfm
