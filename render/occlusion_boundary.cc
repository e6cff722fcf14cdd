#include "render/occlusion_boundary.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::render {

void BoundaryOptions::Check() const {
  COMIC_CHECK(depth_ratio > 0 && std::isfinite(depth_ratio), kInvalidArgument,
              "boundary depth ratio must be > 0, got " << depth_ratio);
  COMIC_CHECK(band_px >= 0 && band_px <= 100, kInvalidArgument,
              "boundary band must be in 0..100 px, got " << band_px);
}

cv::Mat OcclusionBoundaryMask(const Scene& scene, const Pose& cam_from_world,
                              const Rasterizer& rasterizer, const RenderedView& view,
                              const BoundaryOptions& options) {
  options.Check();
  // Each piece's plane in camera coordinates: normal · X = offset.
  std::vector<Eigen::Vector3d> normals(scene.pieces.size());
  std::vector<double> offsets(scene.pieces.size());
  for (size_t p = 0; p < scene.pieces.size(); ++p) {
    const Piece& piece = scene.pieces[p];
    normals[p] = cam_from_world.rotation * piece.s_axis.cross(piece.t_axis).normalized();
    offsets[p] = normals[p].dot(cam_from_world.CamFromWorld(piece.origin));
  }
  // Relative depth difference between piece p's plane along pixel (x, y)'s ray and the depth
  // seen there (infinite when the plane does not meet the ray in front of the camera).
  const auto mismatch = [&](int p, int x, int y) {
    const Eigen::Vector2d uv = rasterizer.RayOfPixel(x, y);
    const double along = normals[p].dot(Eigen::Vector3d(uv.x(), uv.y(), 1.0));
    const double z = offsets[p] / along;
    if (!(z > 0) || !std::isfinite(z)) return std::numeric_limits<double>::infinity();
    const double seen = view.depth.at<float>(y, x);
    return std::abs(z - seen) / seen;
  };
  const auto discontinuous = [&](int x0, int y0, int x1, int y1) {
    const int a = view.piece.at<int>(y0, x0);
    const int b = view.piece.at<int>(y1, x1);
    if (a == b) return false;
    if (a < 0 || b < 0) return true;
    return std::min(mismatch(a, x1, y1), mismatch(b, x0, y0)) > options.depth_ratio;
  };
  // 0 on pixels touching a discontinuity, for the distance transform.
  cv::Mat far_from_edge(view.piece.size(), CV_8UC1, cv::Scalar(255));
  for (int y = 0; y < view.piece.rows; ++y) {
    for (int x = 0; x < view.piece.cols; ++x) {
      if (x + 1 < view.piece.cols && discontinuous(x, y, x + 1, y)) {
        far_from_edge.at<uint8_t>(y, x) = 0;
        far_from_edge.at<uint8_t>(y, x + 1) = 0;
      }
      if (y + 1 < view.piece.rows && discontinuous(x, y, x, y + 1)) {
        far_from_edge.at<uint8_t>(y, x) = 0;
        far_from_edge.at<uint8_t>(y + 1, x) = 0;
      }
    }
  }
  cv::Mat distance;
  cv::distanceTransform(far_from_edge, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat mask = distance <= options.band_px;
  return mask;
}

cv::Mat ForegroundMask(const Scene& scene, const RenderedView& view) {
  cv::Mat mask = cv::Mat::zeros(view.piece.size(), CV_8UC1);
  for (int y = 0; y < view.piece.rows; ++y) {
    for (int x = 0; x < view.piece.cols; ++x) {
      const int p = view.piece.at<int>(y, x);
      if (p >= 0 && scene.objects[scene.pieces[p].object_id - 1].foreground) {
        mask.at<uint8_t>(y, x) = 255;
      }
    }
  }
  return mask;
}

cv::Mat ObjectIds(const Scene& scene, const RenderedView& view) {
  cv::Mat ids = cv::Mat::zeros(view.piece.size(), CV_16UC1);
  for (int y = 0; y < view.piece.rows; ++y) {
    for (int x = 0; x < view.piece.cols; ++x) {
      const int p = view.piece.at<int>(y, x);
      if (p >= 0) ids.at<uint16_t>(y, x) = static_cast<uint16_t>(scene.pieces[p].object_id);
    }
  }
  return ids;
}

}  // namespace comic::render
