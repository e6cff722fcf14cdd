// Reconstruction statistics, with and without region labels.
#include "sfm/evaluation/reconstruction_stats.h"

#include <gtest/gtest.h>

namespace comic::sfm {
namespace {

// Three images; point A seen by all three at x = 10, point B by two at x = 50, point C by two at
// x = 90; observation errors 0 except one of C's (3 px).
Reconstruction MakeReconstruction() {
  Reconstruction reconstruction;
  Camera camera = Camera::FromImageSize(100, 100);
  reconstruction.AddCamera(camera);
  const std::vector<Eigen::Vector3d> points = {{-0.4, 0, 1}, {0, 0, 1}, {0.4, 0, 1}};
  for (int i = 0; i < 3; ++i) {
    Image image;
    image.camera_id = 1;
    for (const Eigen::Vector3d& p : points) {
      Point2D point2D;
      point2D.xy = *ProjectPoint(camera, image.cam_from_world, p);
      image.points2D.push_back(point2D);
    }
    reconstruction.RegisterImage(reconstruction.AddImage(image));
  }
  reconstruction.AddPoint3D(points[0], {{1, 0}, {2, 0}, {3, 0}});
  reconstruction.AddPoint3D(points[1], {{1, 1}, {2, 1}});
  reconstruction.AddPoint3D(points[2], {{1, 2}, {3, 2}});
  reconstruction.image(3).points2D[2].xy.y() += 3.0;
  Image unregistered;
  unregistered.camera_id = 1;
  reconstruction.AddImage(unregistered);
  return reconstruction;
}

TEST(ReconstructionStats, CountsAndMeans) {
  const ReconstructionStats stats = ComputeReconstructionStats(MakeReconstruction());
  EXPECT_EQ(stats.num_images, 4u);
  EXPECT_EQ(stats.num_registered, 3u);
  EXPECT_EQ(stats.all.num_points, 3u);
  EXPECT_EQ(stats.all.num_observations, 7u);
  EXPECT_NEAR(stats.all.mean_track_length, 7.0 / 3.0, 1e-12);
  EXPECT_NEAR(stats.all.mean_reprojection_error_px, 3.0 / 7.0, 1e-9);
  EXPECT_FALSE(stats.boundary.has_value());
  EXPECT_FALSE(stats.interior.has_value());
}

TEST(ReconstructionStats, SplitsByRegionLabel) {
  // x < 30: boundary; 30..70: interior; beyond: outside.
  const RegionLabelFn label = [](const Image&, const Eigen::Vector2d& xy) {
    if (xy.x() < 30) return frontend::RegionLabel::kBoundary;
    if (xy.x() < 70) return frontend::RegionLabel::kInterior;
    return frontend::RegionLabel::kOutside;
  };
  const ReconstructionStats stats = ComputeReconstructionStats(MakeReconstruction(), label);
  ASSERT_TRUE(stats.boundary.has_value());
  ASSERT_TRUE(stats.interior.has_value());
  EXPECT_EQ(stats.boundary->num_points, 1u);
  EXPECT_EQ(stats.boundary->num_observations, 3u);
  EXPECT_EQ(stats.interior->num_points, 1u);
  EXPECT_NEAR(stats.interior->mean_track_length, 2.0, 1e-12);
  EXPECT_EQ(stats.all.num_points, 3u);  // the outside point counts only in "all"
}

}  // namespace
}  // namespace comic::sfm
