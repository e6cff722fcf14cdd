// Occlusion boundaries (render/occlusion_boundary.h): a box standing on the ground in front of a
// wall. Its silhouette against the wall is a boundary; the crease between its two visible faces
// and the line where it stands on the ground are not, though the piece changes across them.
#include "render/occlusion_boundary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace comic::render {
namespace {

Piece Quad(const Eigen::Vector3d& origin, const Eigen::Vector3d& s, const Eigen::Vector3d& t,
           int texture, int object) {
  Piece piece;
  piece.origin = origin;
  piece.s_axis = s;
  piece.t_axis = t;
  piece.texture = texture;
  piece.object_id = object;
  return piece;
}

// World y up; the camera at (0.3, 1.5, 0) looks along +z, slightly down.
struct BoxScene {
  Scene scene;
  Pose pose = LookAlong({0.3, 1.5, 0.0}, {0.0, 0.0, 1.0}, -0.12);
};

BoxScene MakeBoxScene() {
  BoxScene s;
  Scene& scene = s.scene;
  for (int k = 0; k < 3; ++k) {
    scene.textures.push_back(
        Texture::Solid({60.0f + 60 * k, 80.0f + 40 * k, 100.0f + 30 * k}, "grey"));
  }
  const int ground = scene.AddObject("ground", false);
  const int wall = scene.AddObject("wall", false);
  const int box = scene.AddObject("box", true);
  scene.pieces.push_back(Quad({-50, 0, -5}, {100, 0, 0}, {0, 0, 80}, 0, ground));
  scene.pieces.push_back(Quad({-50, 20, 14}, {100, 0, 0}, {0, -20, 0}, 1, wall));
  // A 2 x 1.6 x 2 m box turned by 35 degrees about the vertical, standing on the ground 8 m away;
  // its faces are quads from top to bottom, and its lid.
  const double c = std::cos(0.61), sn = std::sin(0.61);
  const Eigen::Vector3d ex(c, 0.0, sn), ez(-sn, 0.0, c), center(0.0, 0.0, 8.0);
  const Eigen::Vector3d corners[4] = {center - ex - ez, center + ex - ez, center + ex + ez,
                                      center - ex + ez};
  const Eigen::Vector3d up(0.0, 1.6, 0.0);
  for (int k = 0; k < 4; ++k) {
    scene.pieces.push_back(Quad(corners[k] + up, corners[(k + 1) % 4] - corners[k], -up, 2, box));
  }
  scene.pieces.push_back(
      Quad(corners[0] + up, corners[1] - corners[0], corners[3] - corners[0], 2, box));
  return s;
}

TEST(OcclusionBoundary, SilhouettesAreBoundariesCreasesAndContactsAreNot) {
  const BoxScene s = MakeBoxScene();
  const Lens lens;
  const Rasterizer rasterizer(lens, RasterOptions());
  const RenderedView view = rasterizer.Render(s.scene, s.pose);
  BoundaryOptions options;
  options.band_px = 0.0;  // only the pixels touching a discontinuity
  const cv::Mat mask = OcclusionBoundaryMask(s.scene, s.pose, rasterizer, view, options);
  // Against the depth maps themselves: a pixel whose four neighbours all lie within 0.5 % of its
  // depth is on no boundary, even where the piece changes (a crease of the box, or where it
  // stands on the ground); a pixel with a neighbour 10 % farther or nearer is on one.
  int silhouettes = 0, seams = 0;
  for (int y = 1; y + 1 < lens.height; ++y) {
    for (int x = 1; x + 1 < lens.width; ++x) {
      const float z = view.depth.at<float>(y, x);
      double jump = 0.0;
      bool seam = false;
      for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const float n = view.depth.at<float>(y + dy, x + dx);
        jump = std::max(jump, std::abs(n - z) / std::min<double>(n, z));
        seam |= view.piece.at<int>(y + dy, x + dx) != view.piece.at<int>(y, x);
      }
      const bool marked = mask.at<uint8_t>(y, x) != 0;
      if (jump > 0.1) {
        ++silhouettes;
        EXPECT_TRUE(marked) << "depth jump " << jump << " at " << x << ", " << y;
      } else if (jump < 0.005) {
        seams += seam;
        EXPECT_FALSE(marked) << "smooth depth at " << x << ", " << y << (seam ? " (seam)" : "");
      }
    }
  }
  EXPECT_GT(silhouettes, 300);
  EXPECT_GT(seams, 300);  // creases and the contact with the ground were seen and left out
}

TEST(OcclusionBoundary, TheBandWidensTheMarkedPixelsByItsHalfWidth) {
  const BoxScene s = MakeBoxScene();
  const Rasterizer rasterizer{Lens(), RasterOptions()};
  const RenderedView view = rasterizer.Render(s.scene, s.pose);
  BoundaryOptions thin;
  thin.band_px = 0.0;
  BoundaryOptions wide;
  wide.band_px = 3.0;
  const cv::Mat a = OcclusionBoundaryMask(s.scene, s.pose, rasterizer, view, thin);
  const cv::Mat b = OcclusionBoundaryMask(s.scene, s.pose, rasterizer, view, wide);
  // Every thin pixel is in the wide band; the wide band holds every pixel within 3 px of a thin
  // one and no other.
  cv::Mat distance;
  cv::distanceTransform(255 - a, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  for (int y = 0; y < a.rows; ++y) {
    for (int x = 0; x < a.cols; ++x) {
      EXPECT_EQ(b.at<uint8_t>(y, x) != 0, distance.at<float>(y, x) <= 3.0f) << x << ", " << y;
    }
  }
  EXPECT_GT(cv::countNonZero(b), 4 * cv::countNonZero(a));
}

TEST(OcclusionBoundary, ForegroundMaskAndIdsFollowTheObjects) {
  const BoxScene s = MakeBoxScene();
  const RenderedView view = Rasterizer(Lens(), RasterOptions()).Render(s.scene, s.pose);
  const cv::Mat foreground = ForegroundMask(s.scene, view);
  const cv::Mat ids = ObjectIds(s.scene, view);
  int box = 0;
  for (int y = 0; y < ids.rows; ++y) {
    for (int x = 0; x < ids.cols; ++x) {
      EXPECT_EQ(foreground.at<uint8_t>(y, x) != 0, ids.at<uint16_t>(y, x) == 3);
      box += ids.at<uint16_t>(y, x) == 3;
    }
  }
  EXPECT_GT(box, 5000);
}

}  // namespace
}  // namespace comic::render
