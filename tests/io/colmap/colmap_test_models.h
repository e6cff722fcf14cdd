// A random COLMAP model (two camera models, an image without 2-D points, unmatched and matched
// points) and an exact comparison of two models, for the tests of every COLMAP model format.
#pragma once

#include <gtest/gtest.h>

#include <random>

#include "io/colmap/colmap_text_model.h"

namespace comic::io::test {

// A model of 2 cameras, 4 images and 5 points drawn from `seed`.
inline ColmapTextModel RandomModel(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-10.0, 10.0);
  ColmapTextModel model;
  model.cameras.push_back({1, "PINHOLE", 1226, 370, {707.0912, 707.0912, 602.3873, 183.6104}});
  model.cameras.push_back({2, "SIMPLE_RADIAL", 640, 480, {800.1, 320.5, 240.5, -0.01}});
  for (uint32_t i = 1; i <= 4; ++i) {
    ColmapImage image;
    image.image_id = i;
    image.cam_from_world_rotation =
        Eigen::Quaterniond(uniform(rng), uniform(rng), uniform(rng), uniform(rng)).normalized();
    image.cam_from_world_translation = {uniform(rng), uniform(rng), uniform(rng)};
    image.camera_id = i <= 2 ? 1 : 2;
    image.name = "seq/" + std::to_string(i) + ".png";
    for (int k = 0; k < 5; ++k)
      image.points2D.push_back({uniform(rng) + 50, uniform(rng) + 50, -1});
    model.images.push_back(image);
  }
  model.images[3].points2D.clear();  // an image without 2-D points has an empty second line
  for (uint64_t p = 1; p <= 5; ++p) {
    ColmapPoint3D point;
    point.point3D_id = p * 7;
    point.xyz = {uniform(rng), uniform(rng), uniform(rng)};
    point.rgb = {static_cast<uint8_t>(p), 128, 255};
    point.error = 0.1 * p + 1e-13;
    for (uint32_t i = 1; i <= 3; ++i) {
      point.track.push_back({i, static_cast<uint32_t>(p - 1)});
      model.images[i - 1].points2D[p - 1].point3D_id = static_cast<int64_t>(point.point3D_id);
    }
    model.points3D.push_back(point);
  }
  return model;
}

// Every field equal, doubles exactly.
inline void ExpectSameModel(const ColmapTextModel& a, const ColmapTextModel& b) {
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    EXPECT_EQ(a.cameras[i].camera_id, b.cameras[i].camera_id);
    EXPECT_EQ(a.cameras[i].model, b.cameras[i].model);
    EXPECT_EQ(a.cameras[i].width, b.cameras[i].width);
    EXPECT_EQ(a.cameras[i].height, b.cameras[i].height);
    EXPECT_EQ(a.cameras[i].params, b.cameras[i].params);  // exact
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) {
    const ColmapImage& x = a.images[i];
    const ColmapImage& y = b.images[i];
    EXPECT_EQ(x.image_id, y.image_id);
    EXPECT_EQ(x.cam_from_world_rotation.coeffs(), y.cam_from_world_rotation.coeffs());
    EXPECT_EQ(x.cam_from_world_translation, y.cam_from_world_translation);
    EXPECT_EQ(x.camera_id, y.camera_id);
    EXPECT_EQ(x.name, y.name);
    ASSERT_EQ(x.points2D.size(), y.points2D.size());
    for (size_t k = 0; k < x.points2D.size(); ++k) {
      EXPECT_EQ(x.points2D[k].x, y.points2D[k].x);
      EXPECT_EQ(x.points2D[k].y, y.points2D[k].y);
      EXPECT_EQ(x.points2D[k].point3D_id, y.points2D[k].point3D_id);
    }
  }
  ASSERT_EQ(a.points3D.size(), b.points3D.size());
  for (size_t i = 0; i < a.points3D.size(); ++i) {
    const ColmapPoint3D& x = a.points3D[i];
    const ColmapPoint3D& y = b.points3D[i];
    EXPECT_EQ(x.point3D_id, y.point3D_id);
    EXPECT_EQ(x.xyz, y.xyz);
    EXPECT_EQ(x.rgb, y.rgb);
    EXPECT_EQ(x.error, y.error);
    ASSERT_EQ(x.track.size(), y.track.size());
    for (size_t k = 0; k < x.track.size(); ++k) {
      EXPECT_EQ(x.track[k].image_id, y.track[k].image_id);
      EXPECT_EQ(x.track[k].point2D_idx, y.track[k].point2D_idx);
    }
  }
}

}  // namespace comic::io::test
