#include "render/lens.h"

#include <Eigen/Dense>
#include <cmath>

#include "io/core/error.h"

namespace comic::render {

Eigen::Vector2d Lens::Distort(const Eigen::Vector2d& uv) const {
  const double u = uv.x();
  const double v = uv.y();
  const double r2 = u * u + v * v;
  const double radial = 1.0 + k1 * r2 + k2 * r2 * r2;
  return {u * radial + 2.0 * p1 * u * v + p2 * (r2 + 2.0 * u * u),
          v * radial + p1 * (r2 + 2.0 * v * v) + 2.0 * p2 * u * v};
}

Eigen::Vector2d Lens::PixelFromNormalized(const Eigen::Vector2d& uv) const {
  const Eigen::Vector2d d = Distort(uv);
  return {fx * d.x() + cx, fy * d.y() + cy};
}

Eigen::Vector2d Lens::NormalizedFromPixel(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d target((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  return HasDistortion() ? Undistort(target, target) : target;
}

Eigen::Vector2d Lens::Undistort(const Eigen::Vector2d& distorted,
                                const Eigen::Vector2d& guess) const {
  Eigen::Vector2d uv = guess;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double u = uv.x();
    const double v = uv.y();
    const double r2 = u * u + v * v;
    const double radial = 1.0 + k1 * r2 + k2 * r2 * r2;
    const double d_radial = 2.0 * (k1 + 2.0 * k2 * r2);  // d radial / du = u * d_radial
    Eigen::Matrix2d jacobian;
    jacobian << radial + u * u * d_radial + 2.0 * p1 * v + 6.0 * p2 * u,
        u * v * d_radial + 2.0 * p1 * u + 2.0 * p2 * v,
        u * v * d_radial + 2.0 * p1 * u + 2.0 * p2 * v,
        radial + v * v * d_radial + 6.0 * p1 * v + 2.0 * p2 * u;
    const Eigen::Vector2d step = jacobian.inverse() * (Distort(uv) - distorted);
    uv -= step;
    if (step.norm() <= 1e-12 * std::max(1.0, uv.norm())) break;
  }
  return uv;
}

std::string Lens::ColmapModelName() const { return HasDistortion() ? "OPENCV" : "PINHOLE"; }

std::vector<double> Lens::ColmapParams() const {
  std::vector<double> params = {fx, fy, cx + 0.5, cy + 0.5};
  if (HasDistortion()) params.insert(params.end(), {k1, k2, p1, p2});
  return params;
}

void Lens::Check() const {
  COMIC_CHECK(width >= 1 && width <= 16384 && height >= 1 && height <= 16384, kInvalidArgument,
              "camera: width and height must be in 1..16384, got " << width << "x" << height);
  for (double value : {fx, fy, cx, cy, k1, k2, p1, p2}) {
    COMIC_CHECK(std::isfinite(value), kInvalidArgument, "camera: parameters must be finite");
  }
  COMIC_CHECK(fx > 0 && fy > 0, kInvalidArgument,
              "camera: fx and fy must be > 0, got " << fx << ", " << fy);
  if (!HasDistortion()) return;
  // One-to-one: along each half-diagonal from the principal point to a corner (and 10 % beyond),
  // the distorted radius must keep growing, or pixels would see two rays.
  const double corners[4][2] = {
      {-0.5, -0.5}, {width - 0.5, -0.5}, {-0.5, height - 0.5}, {width - 0.5, height - 0.5}};
  for (const auto& corner : corners) {
    const Eigen::Vector2d end((corner[0] - cx) / fx * 1.1, (corner[1] - cy) / fy * 1.1);
    double previous = 0.0;
    for (int i = 1; i <= 200; ++i) {
      const double radius = Distort(end * (i / 200.0)).norm();
      COMIC_CHECK(radius > previous, kInvalidArgument,
                  "camera: the distortion (k1 " << k1 << ", k2 " << k2 << ", p1 " << p1 << ", p2 "
                                                << p2
                                                << ") folds over within the image; use smaller "
                                                   "coefficients");
      previous = radius;
    }
  }
}

}  // namespace comic::render
