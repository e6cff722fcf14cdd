#include "io/colmap/colmap_text_model.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/io/colmap/colmap_test_models.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;
using test::RandomModel;

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
