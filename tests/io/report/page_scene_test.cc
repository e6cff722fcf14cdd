// The 3-D section: points subsampled every k-th beyond max_points (and said so), cameras and
// paths as little-endian Float32 arrays.
#include "io/report/page_scene.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "io/report/data_uri.h"

namespace comic::io {
namespace {

TEST(SceneSection, SubsamplesLargePointSetsEveryKth) {
  Scene scene;
  for (int i = 0; i < 1000; ++i) scene.points.emplace_back(i, 0, 0);
  scene.max_points = 300;
  const PageSection section = SceneSection(scene);
  EXPECT_EQ(section["points"]["total"], 1000);
  EXPECT_EQ(section["points"]["stride"], 4);
  EXPECT_EQ(section["points"]["count"], 250);
  // The first kept points are 0 and 4; colours default to grey.
  std::vector<float> first = {0, 0, 0, 4, 0, 0};
  EXPECT_EQ(section["points"]["positions"].get<std::string>().substr(0, 32),
            Base64OfFloats(first).substr(0, 32));
  EXPECT_EQ(section["points"]["colors"].get<std::string>().substr(0, 4),
            EncodeBase64(std::vector<uint8_t>{150, 150, 150}));
  scene.max_points = 1000;
  EXPECT_EQ(SceneSection(scene)["points"]["count"], 1000);
}

TEST(SceneSection, WritesCamerasAndPaths) {
  Scene scene;
  SceneCameras cameras;
  cameras.name = "model 1";
  cameras.centers = {Eigen::Vector3d(1, 2, 3)};
  cameras.rotations = {Eigen::Quaterniond(2, 0, 0, 0)};  // normalised on the way
  scene.cameras.push_back(cameras);
  scene.paths.push_back({"ground truth", "#3aa655", {Eigen::Vector3d(0, 0, 0)}, false});
  const PageSection section = SceneSection(scene);
  EXPECT_EQ(section["cameras"][0]["centers"], Base64OfFloats({1, 2, 3}));
  EXPECT_EQ(section["cameras"][0]["rotations"], Base64OfFloats({0, 0, 0, 1}));  // x y z w
  EXPECT_EQ(section["paths"][0]["count"], 1);
  EXPECT_EQ(section["up"], nlohmann::json({0.0, 1.0, 0.0}));  // the default
}

TEST(SceneSection, RefusesMismatchedLists) {
  Scene scene;
  scene.points = {Eigen::Vector3d::Zero()};
  scene.colors = {{1, 2, 3}, {4, 5, 6}};
  EXPECT_THROW(SceneSection(scene), Error);
  Scene cameras;
  SceneCameras set;
  set.centers = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()};
  set.rotations = {Eigen::Quaterniond::Identity()};
  cameras.cameras.push_back(set);
  EXPECT_THROW(SceneSection(cameras), Error);
}

}  // namespace
}  // namespace comic::io
