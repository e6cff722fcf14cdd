// Reconstruction bookkeeping: observations link both ways, points vanish below two observations,
// reprojection errors, and misuse throws.
#include "sfm/reconstruction.h"

#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

// Two cameras 1 m apart looking down +z, three points, each seen by both.
Reconstruction MakeTwoViewReconstruction(std::vector<point3D_t>* point_ids) {
  Reconstruction reconstruction;
  const Camera camera = Camera::FromImageSize(640, 480);
  const camera_t camera_id = reconstruction.AddCamera(camera);
  const std::vector<Eigen::Vector3d> points = {{0, 0, 5}, {1, -0.5, 6}, {-1, 0.5, 4}};
  for (int i = 0; i < 2; ++i) {
    Image image;
    image.camera_id = camera_id;
    image.name = "frame" + std::to_string(i);
    image.cam_from_world.translation = Eigen::Vector3d(-1.0 * i, 0, 0);
    for (const Eigen::Vector3d& p : points) {
      Point2D point2D;
      point2D.xy = *ProjectPoint(camera, image.cam_from_world, p);
      image.points2D.push_back(point2D);
    }
    const image_t id = reconstruction.AddImage(image);
    reconstruction.RegisterImage(id);
  }
  for (point2D_t k = 0; k < points.size(); ++k) {
    point_ids->push_back(reconstruction.AddPoint3D(points[k], {{1, k}, {2, k}}));
  }
  return reconstruction;
}

TEST(Reconstruction, ProjectsAndMeasuresErrors) {
  std::vector<point3D_t> ids;
  Reconstruction reconstruction = MakeTwoViewReconstruction(&ids);
  EXPECT_EQ(reconstruction.NumRegisteredImages(), 2u);
  EXPECT_EQ(reconstruction.NumPoints3D(), 3u);
  EXPECT_EQ(reconstruction.NumObservations(), 6u);
  EXPECT_DOUBLE_EQ(reconstruction.ComputeMeanTrackLength(), 2.0);
  EXPECT_LT(reconstruction.ComputeMeanReprojectionError(), 1e-9);
  // Move one observation by 3-4-5 pixels.
  reconstruction.image(2).points2D[0].xy += Eigen::Vector2d(3, 4);
  EXPECT_NEAR(reconstruction.ReprojectionError(2, 0), 5.0, 1e-9);
  EXPECT_NEAR(reconstruction.ComputeMeanReprojectionError(), 5.0 / 6.0, 1e-9);
  reconstruction.UpdatePoint3DErrors();
  EXPECT_NEAR(reconstruction.point3D(ids[0]).error, 2.5, 1e-9);
  // A point behind a camera has infinite error.
  reconstruction.point3D(ids[1]).xyz.z() = -3;
  EXPECT_TRUE(std::isinf(reconstruction.ReprojectionError(1, 1)));
  EXPECT_FALSE(ProjectPoint(reconstruction.camera(1), Rigid3d(), {0, 0, -1}).has_value());
}

TEST(Reconstruction, ObservationsLinkBothWaysAndPointsNeedTwo) {
  std::vector<point3D_t> ids;
  Reconstruction reconstruction = MakeTwoViewReconstruction(&ids);
  EXPECT_EQ(reconstruction.image(1).points2D[2].point3D_id, ids[2]);
  EXPECT_EQ(reconstruction.image(1).NumPoints3D(), 3u);
  reconstruction.DeleteObservation(2, 2);  // leaves one observation: the point goes
  EXPECT_FALSE(reconstruction.ExistsPoint3D(ids[2]));
  EXPECT_FALSE(reconstruction.image(1).points2D[2].HasPoint3D());
  EXPECT_FALSE(reconstruction.image(2).points2D[2].HasPoint3D());
  // Re-adding the point with a fresh id, then a third image observation.
  Image third;
  third.camera_id = 1;
  third.points2D.resize(1);
  const image_t third_id = reconstruction.AddImage(third);
  EXPECT_EQ(third_id, 3u);
  const point3D_t id = reconstruction.AddPoint3D({-1, 0.5, 4}, {{1, 2}, {2, 2}});
  EXPECT_GT(id, ids[2]);
  reconstruction.AddObservation(id, {third_id, 0});
  EXPECT_EQ(reconstruction.point3D(id).track.size(), 3u);
  reconstruction.DeleteObservation(1, 2);  // three -> two: the point stays
  EXPECT_TRUE(reconstruction.ExistsPoint3D(id));
  EXPECT_EQ(reconstruction.point3D(id).track.size(), 2u);
  // Deregistering removes the image's observations.
  reconstruction.DeRegisterImage(2);
  EXPECT_FALSE(reconstruction.image(2).registered);
  EXPECT_EQ(reconstruction.image(2).NumPoints3D(), 0u);
  EXPECT_EQ(reconstruction.NumPoints3D(), 0u);
  EXPECT_EQ(reconstruction.RegisteredImageIds(), std::vector<image_t>({1}));
}

// The journal an owner keeps its counts from: every link and unlink in order, the implicit ones
// (a point deleted with its second-last observation, a deregistered image) included.
TEST(Reconstruction, RecordsEveryLinkChangeOnceAskedTo) {
  std::vector<point3D_t> ids;
  Reconstruction reconstruction = MakeTwoViewReconstruction(&ids);
  EXPECT_TRUE(reconstruction.TakeLinkChanges().empty()) << "nothing recorded until asked";
  reconstruction.RecordLinkChanges(true);
  const auto changes = [&reconstruction]() {
    std::vector<std::tuple<image_t, point2D_t, bool>> out;
    for (const Reconstruction::LinkChange& c : reconstruction.TakeLinkChanges()) {
      out.emplace_back(c.element.image_id, c.element.point2D_idx, c.linked);
    }
    return out;
  };
  using Changes = std::vector<std::tuple<image_t, point2D_t, bool>>;
  reconstruction.DeleteObservation(2, 2);  // the point goes: both observations unlinked
  EXPECT_EQ(changes(), Changes({{1, 2, false}, {2, 2, false}}));
  EXPECT_TRUE(changes().empty()) << "taken once";
  Image third;
  third.camera_id = 1;
  third.points2D.resize(1);
  const image_t third_id = reconstruction.AddImage(third);
  const point3D_t id = reconstruction.AddPoint3D({-1, 0.5, 4}, {{1, 2}, {2, 2}});
  reconstruction.AddObservation(id, {third_id, 0});
  reconstruction.DeleteObservation(1, 2);  // three -> two: only this one
  EXPECT_EQ(changes(), Changes({{1, 2, true}, {2, 2, true}, {3, 0, true}, {1, 2, false}}));
  reconstruction.DeRegisterImage(2);  // every point of image 2 had two observations: all go
  EXPECT_EQ(changes(), Changes({{1, 0, false},
                                {2, 0, false},
                                {1, 1, false},
                                {2, 1, false},
                                {2, 2, false},
                                {3, 0, false}}));
  EXPECT_THROW(reconstruction.AddObservation(ids[0], {1, 0}), Error);  // the point is gone
  EXPECT_TRUE(changes().empty()) << "a refused change records nothing";
}

TEST(Reconstruction, MisuseThrows) {
  std::vector<point3D_t> ids;
  Reconstruction reconstruction = MakeTwoViewReconstruction(&ids);
  EXPECT_THROW(reconstruction.image(9), Error);
  EXPECT_THROW(reconstruction.point3D(999), Error);
  EXPECT_THROW(reconstruction.AddCamera(Camera()), Error);                        // invalid camera
  EXPECT_THROW(reconstruction.AddCamera(Camera::FromImageSize(4, 4), 1), Error);  // id in use
  Image image;
  image.camera_id = 7;
  EXPECT_THROW(reconstruction.AddImage(image), Error);  // unknown camera
  image.camera_id = 1;
  image.image_id = 2;
  EXPECT_THROW(reconstruction.AddImage(image), Error);                          // id in use
  EXPECT_THROW(reconstruction.AddPoint3D({0, 0, 1}, {{1, 0}, {2, 1}}), Error);  // already linked
  EXPECT_THROW(reconstruction.AddPoint3D({0, 0, 1}, {{1, 9}}), Error);          // no such point2D
  EXPECT_THROW(reconstruction.AddObservation(ids[0], {1, 1}), Error);  // image observes it already
  EXPECT_THROW(reconstruction.DeleteObservation(1, 9), Error);
  // Nothing half-done: the failed calls left the model as it was.
  EXPECT_EQ(reconstruction.NumPoints3D(), 3u);
  EXPECT_EQ(reconstruction.NumObservations(), 6u);
}

}  // namespace
}  // namespace comic::sfm
