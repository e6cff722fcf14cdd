// Writing every model of a run: sparse/0 the largest, sparse/1 ..., the largest as text on top,
// all in the pixels asked for.
#include "sfm/colmap/model_set_writer.h"

#include <gtest/gtest.h>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "sfm/synthetic_scene.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

// A model of frames [first, last] of a small scene at their true poses, with one point.
Reconstruction Model(const SyntheticScene& scene, int first, int last) {
  Reconstruction model;
  const camera_t camera_id = model.AddCamera(scene.camera);
  for (size_t frame = 0; frame < scene.tracks.NumFrames(); ++frame) {
    Image image;
    image.camera_id = camera_id;
    image.name = scene.tracks.frame_names[frame];
    image.cam_from_world = scene.cams_from_world[frame];
    image.points2D.push_back({Eigen::Vector2d(100.0, 50.0)});
    const image_t id = model.AddImage(image);
    if (static_cast<int>(frame) >= first && static_cast<int>(frame) <= last) {
      model.RegisterImage(id);
    }
  }
  model.AddPoint3D(Eigen::Vector3d(0, 0, 10),
                   {{static_cast<image_t>(first + 1), 0}, {static_cast<image_t>(last + 1), 0}});
  return model;
}

IncrementalReconstruction TwoModels() {
  SyntheticSceneOptions options;
  options.num_frames = 6;
  options.num_points = 30;
  const SyntheticScene scene = MakeSyntheticScene(options);
  IncrementalReconstruction mapping;
  mapping.status = ReconstructionStatus::kPartial;
  mapping.reconstruction = Model(scene, 0, 3);
  IncrementalModel other;
  other.reconstruction = Model(scene, 4, 5);
  mapping.other_models.push_back(std::move(other));
  return mapping;
}

TEST(ModelSetWriter, WritesEveryModelTheLargestFirstInTheInputsPixels) {
  const test::ScopedTempDir folder;
  ModelSetWriteOptions options;
  options.width = 1280;  // the input: twice the working size
  options.height = 960;
  const std::vector<std::string> written = WriteModelSet(TwoModels(), folder.path(), options);
  EXPECT_EQ(written, (std::vector<std::string>{"cameras.txt", "images.txt", "points3D.txt",
                                               "sparse/0/cameras.bin", "sparse/0/images.bin",
                                               "sparse/0/points3D.bin", "sparse/1/cameras.bin",
                                               "sparse/1/images.bin", "sparse/1/points3D.bin"}));
  const io::ColmapTextModel top = io::ReadColmapTextModel(folder.path());
  const io::ColmapTextModel largest = io::ReadColmapBinaryModel(folder.File("sparse/0"));
  const io::ColmapTextModel other = io::ReadColmapBinaryModel(folder.File("sparse/1"));
  EXPECT_EQ(top.images.size(), 4u);
  EXPECT_EQ(largest.images.size(), 4u);
  EXPECT_EQ(other.images.size(), 2u);
  EXPECT_EQ(other.cameras[0].width, 1280);
  EXPECT_EQ(other.cameras[0].height, 960);
  EXPECT_NEAR(other.cameras[0].params[0], 1200.0, 1e-9);  // f = 600 at 640 x 480
  // (100, 50) in OpenCV's convention, scaled by 2 in pixel areas, plus COLMAP's half pixel.
  EXPECT_NEAR(other.images[0].points2D[0].x, 201.0, 1e-9);
  EXPECT_NEAR(other.images[0].points2D[0].y, 101.0, 1e-9);
}

TEST(ModelSetWriter, TextOnlyPutsTheOtherModelsInSparseAsText) {
  const test::ScopedTempDir folder;
  ModelSetWriteOptions options;
  options.binary = false;
  const std::vector<std::string> written = WriteModelSet(TwoModels(), folder.path(), options);
  EXPECT_EQ(written, (std::vector<std::string>{"cameras.txt", "images.txt", "points3D.txt",
                                               "sparse/1/cameras.txt", "sparse/1/images.txt",
                                               "sparse/1/points3D.txt"}));
  EXPECT_EQ(io::ReadColmapTextModel(folder.File("sparse/1")).cameras[0].width, 640);
  IncrementalReconstruction none;
  none.status = ReconstructionStatus::kNoInitialPair;
  EXPECT_THROW(WriteModelSet(none, folder.path(), options), Error);
}

}  // namespace
}  // namespace comic::sfm
