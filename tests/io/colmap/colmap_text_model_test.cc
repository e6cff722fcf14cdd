#include "io/colmap/colmap_text_model.h"

#include <gtest/gtest.h>

#include <random>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;

ColmapTextModel RandomModel(uint32_t seed) {
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

void ExpectSameModel(const ColmapTextModel& a, const ColmapTextModel& b) {
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

TEST(ColmapTextModel, RoundTripIsExact) {
  ScopedTempDir dir;
  const ColmapTextModel model = RandomModel(42);
  WriteColmapTextModel(model, dir.File("model"));
  ExpectSameModel(model, ReadColmapTextModel(dir.File("model")));
  // Written twice, byte-identical files.
  const std::string first = ReadFileToString(dir.File("model/images.txt"));
  WriteColmapTextModel(model, dir.File("model"));
  EXPECT_EQ(first, ReadFileToString(dir.File("model/images.txt")));
}

TEST(ColmapTextModel, ReadsColmapsOwnLayout) {
  // As COLMAP 3.8 writes it: comment header, two lines per image, an empty points line.
  ScopedTempDir dir;
  WriteFileAtomically(dir.File("cameras.txt"),
                      "# Camera list with one line of data per camera:\n"
                      "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
                      "# Number of cameras: 1\n"
                      "1 SIMPLE_RADIAL 3072 2048 2559.68 1536 1024 -0.0204997\n");
  WriteFileAtomically(dir.File("images.txt"),
                      "# Image list with two lines of data per image:\n"
                      "# Number of images: 2, mean observations per image: 1\n"
                      "1 0.851773 0.0165051 0.503764 -0.142941 -0.737434 1.02973 3.74354 1 "
                      "P1180141.JPG\n"
                      "2362.39 248.498 -1 1010.5 300.25 1\n"
                      "2 1 0 0 0 0 0 0 1 P1180142.JPG\n"
                      "\n");
  WriteFileAtomically(dir.File("points3D.txt"),
                      "# 3D point list with one line of data per point:\n"
                      "1 1.5 -2.25 10 255 0 12 0.5 1 1\n");
  const ColmapTextModel model = ReadColmapTextModel(dir.path());
  ASSERT_EQ(model.cameras.size(), 1u);
  EXPECT_EQ(model.cameras[0].model, "SIMPLE_RADIAL");
  EXPECT_EQ(model.cameras[0].params.size(), 4u);
  ASSERT_EQ(model.images.size(), 2u);
  EXPECT_DOUBLE_EQ(model.images[0].cam_from_world_rotation.w(), 0.851773);
  EXPECT_EQ(model.images[0].name, "P1180141.JPG");
  ASSERT_EQ(model.images[0].points2D.size(), 2u);
  EXPECT_EQ(model.images[0].points2D[1].point3D_id, 1);
  EXPECT_TRUE(model.images[1].points2D.empty());
  ASSERT_EQ(model.points3D.size(), 1u);
  EXPECT_EQ(model.points3D[0].rgb[2], 12);
  EXPECT_EQ(model.points3D[0].track.size(), 1u);
}

TEST(ColmapTextModel, MalformedFilesNameFileAndLine) {
  ScopedTempDir dir;
  const ColmapTextModel model = RandomModel(1);
  WriteColmapTextModel(model, dir.path());
  WriteFileAtomically(dir.File("points3D.txt"), "# header\n7 1 2 3 255 255 255 0.1 1 oops\n");
  try {
    ReadColmapTextModel(dir.path());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("points3D.txt:2: malformed line"), std::string::npos)
        << e.what();
  }
  // A track naming a missing image is caught by Check().
  WriteFileAtomically(dir.File("points3D.txt"), "7 1 2 3 255 255 255 0.1 99 0\n");
  EXPECT_THROW(ReadColmapTextModel(dir.path()), Error);
}

TEST(ColmapTextModel, MissingFilesAndBadModels) {
  ScopedTempDir dir;
  EXPECT_THROW(ReadColmapTextModel(dir.File("nope")), Error);
  EXPECT_THROW(ReadColmapTextModel(dir.path()), Error);  // folder without files
  ColmapTextModel model = RandomModel(3);
  model.images[0].name = "has space.png";
  EXPECT_THROW(WriteColmapTextModel(model, dir.File("out")), Error);
  EXPECT_FALSE(PathExists(dir.File("out/images.txt")));
  model = RandomModel(3);
  model.images[1].camera_id = 9;
  EXPECT_THROW(model.Check(), Error);
}

}  // namespace
}  // namespace comic::io
