// A model found in a folder as pycolmap.Reconstruction(path) finds one: the folder itself (binary
// preferred over text), else its sparse/0/; anything else fails with one line naming the path.
#include "io/colmap/colmap_model_folder.h"

#include <gtest/gtest.h>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;

ColmapTextModel SmallModel(double focal) {
  ColmapTextModel model;
  model.cameras.push_back({1, "PINHOLE", 640, 480, {focal, focal, 320.5, 240.5}});
  ColmapImage image;
  image.image_id = 1;
  image.camera_id = 1;
  image.name = "a.png";
  image.points2D.push_back({10.5, 20.5, 1});
  model.images.push_back(image);
  ColmapPoint3D point;
  point.point3D_id = 1;
  point.xyz = {1.0, 2.0, 3.0};
  point.rgb = {10, 20, 30};
  point.track.push_back({1, 0});
  model.points3D.push_back(point);
  return model;
}

ErrorKind KindOf(const std::string& path) {
  try {
    FindColmapModel(path);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    return e.kind();
  }
  ADD_FAILURE() << path << ": a model was found";
  return ErrorKind::kExternal;  // never a kind FindColmapModel throws
}

TEST(ColmapModelFolder, FindsTextBinaryAndSparseZero) {
  ScopedTempDir dir;
  WriteColmapTextModel(SmallModel(500), dir.File("text"));
  WriteColmapBinaryModel(SmallModel(600), dir.File("out/sparse/0"));
  WriteColmapTextModel(SmallModel(700), dir.File("both"));
  WriteColmapBinaryModel(SmallModel(800), dir.File("both"));

  EXPECT_FALSE(FindColmapModel(dir.File("text")).binary);
  EXPECT_EQ(ReadColmapModel(dir.File("text")).cameras[0].params[0], 500.0);
  // comic_sfm --model-format bin, or COLMAP's mapper output: the model is in sparse/0/.
  EXPECT_EQ(FindColmapModel(dir.File("out")).folder, JoinPaths(dir.File("out"), "sparse/0"));
  EXPECT_TRUE(FindColmapModel(dir.File("out")).binary);
  EXPECT_EQ(ReadColmapModel(dir.File("out")).cameras[0].params[0], 600.0);
  // Both in one folder: the binary one, as COLMAP reads it.
  EXPECT_EQ(ReadColmapModel(dir.File("both")).cameras[0].params[0], 800.0);
}

TEST(ColmapModelFolder, NoModelFailsNamingThePath) {
  ScopedTempDir dir;
  EnsureWritableDirectory(dir.File("partial"));
  WriteFileAtomically(dir.File("partial/cameras.txt"), "");
  WriteFileAtomically(dir.File("file.txt"), "x");
  EXPECT_EQ(KindOf(dir.File("missing")), ErrorKind::kNotFound);
  EXPECT_EQ(KindOf(dir.File("partial")), ErrorKind::kNotFound);
  EXPECT_EQ(KindOf(dir.File("file.txt")), ErrorKind::kInvalidArgument);
}

}  // namespace
}  // namespace comic::io
