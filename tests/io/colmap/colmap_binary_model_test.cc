// COLMAP's binary model: the byte layout COLMAP 3.8 writes, cross-checked against the real
// `colmap model_converter` both ways, and truncated or corrupt files failing cleanly. The exact
// round trip both formats keep is in colmap_model_round_trip_test.cc.
#include "io/colmap/colmap_binary_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/io/colmap/colmap_test_models.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::RunCommand;
using comic::test::ScopedTempDir;
using test::ExpectSameModel;
using test::RandomModel;

// COLMAP writes its text files in hash-map order; sort by id before comparing.
ColmapTextModel SortedById(ColmapTextModel model) {
  std::sort(model.cameras.begin(), model.cameras.end(),
            [](const auto& a, const auto& b) { return a.camera_id < b.camera_id; });
  std::sort(model.images.begin(), model.images.end(),
            [](const auto& a, const auto& b) { return a.image_id < b.image_id; });
  std::sort(model.points3D.begin(), model.points3D.end(),
            [](const auto& a, const auto& b) { return a.point3D_id < b.point3D_id; });
  return model;
}

// COLMAP normalises every quaternion it reads (NormalizeQuaternion), which may move the last bit
// of an already normalised one: checks the rotations to 1e-15 and then takes ours, so that
// ExpectSameModel holds everything else to exactness.
ColmapTextModel WithOurRotations(ColmapTextModel read, const ColmapTextModel& ours) {
  EXPECT_EQ(read.images.size(), ours.images.size());
  for (size_t i = 0; i < std::min(read.images.size(), ours.images.size()); ++i) {
    const Eigen::Vector4d difference = read.images[i].cam_from_world_rotation.coeffs() -
                                       ours.images[i].cam_from_world_rotation.coeffs();
    EXPECT_LT(difference.cwiseAbs().maxCoeff(), 1e-15) << "image " << ours.images[i].image_id;
    read.images[i].cam_from_world_rotation = ours.images[i].cam_from_world_rotation;
  }
  return read;
}

bool ColmapOnPath() { return RunCommand("command -v colmap").exit_code == 0; }

template <typename T>
T ReadAt(const std::string& bytes, size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

TEST(ColmapBinaryModel, BytesFollowColmapsLayout) {
  const ColmapTextModel model = RandomModel(3);
  const std::string cameras = ColmapCamerasBinary(model);
  // count, then PINHOLE: id 1, model 1, 1226 x 370, 4 doubles; SIMPLE_RADIAL: id 2, model 2.
  ASSERT_EQ(cameras.size(), 8u + 2 * (4 + 4 + 8 + 8) + 8 * 8);
  EXPECT_EQ(ReadAt<uint64_t>(cameras, 0), 2u);
  EXPECT_EQ(ReadAt<uint32_t>(cameras, 8), 1u);
  EXPECT_EQ(ReadAt<int32_t>(cameras, 12), 1);
  EXPECT_EQ(ReadAt<uint64_t>(cameras, 16), 1226u);
  EXPECT_EQ(ReadAt<uint64_t>(cameras, 24), 370u);
  EXPECT_EQ(ReadAt<double>(cameras, 32), 707.0912);
  EXPECT_EQ(ReadAt<int32_t>(cameras, 8 + 56 + 4), 2);

  const std::string images = ColmapImagesBinary(model);
  EXPECT_EQ(ReadAt<uint64_t>(images, 0), 4u);
  EXPECT_EQ(ReadAt<uint32_t>(images, 8), 1u);
  EXPECT_EQ(ReadAt<double>(images, 12), model.images[0].cam_from_world_rotation.w());
  EXPECT_EQ(ReadAt<double>(images, 12 + 32), model.images[0].cam_from_world_translation.x());
  EXPECT_EQ(ReadAt<uint32_t>(images, 12 + 56), 1u);  // camera id
  const size_t name_at = 12 + 56 + 4;
  EXPECT_EQ(std::string(images.data() + name_at), "seq/1.png");
  const size_t points_at = name_at + std::string("seq/1.png").size() + 1;
  EXPECT_EQ(ReadAt<uint64_t>(images, points_at), 5u);
  // Image 1's first 2-D point is point 7's.
  EXPECT_EQ(ReadAt<uint64_t>(images, points_at + 8 + 16), 7u);

  const std::string points = ColmapPoints3DBinary(model);
  const size_t per_point = 8 + 24 + 3 + 8 + 8 + 3 * 8;
  ASSERT_EQ(points.size(), 8u + 5 * per_point);
  EXPECT_EQ(ReadAt<uint64_t>(points, 8), 7u);
  EXPECT_EQ(static_cast<uint8_t>(points[8 + 8 + 24 + 2]), 255);
  EXPECT_EQ(ReadAt<uint64_t>(points, 8 + 8 + 24 + 3 + 8), 3u);  // track length
}

TEST(ColmapBinaryModel, UnmatchedPointsAreColmapsInvalidId) {
  ColmapTextModel model = RandomModel(5);
  model.images[3].points2D.push_back({10.5, 20.5, -1});
  model.images[3].points2D.push_back({30.5, 40.5, -1});
  ScopedTempDir dir;
  WriteColmapBinaryModel(model, dir.path());
  const ColmapTextModel read = ReadColmapBinaryModel(dir.path());
  // Image 4's points are unmatched: stored as 2^64 - 1, read back as -1.
  ASSERT_EQ(read.images[3].points2D.size(), 2u);
  for (const ColmapPoint2D& point : read.images[3].points2D) EXPECT_EQ(point.point3D_id, -1);
  EXPECT_EQ(read.images[3].points2D[1].x, 30.5);
  const std::string images = ReadFileToString(dir.File("images.bin"));
  EXPECT_EQ(ReadAt<uint64_t>(images, images.size() - 8), ~uint64_t{0});
}

TEST(ColmapBinaryModel, ColmapReadsWhatWeWriteAndWeReadWhatColmapWrites) {
  if (!ColmapOnPath()) GTEST_SKIP() << "colmap is not installed";
  ScopedTempDir dir;
  const ColmapTextModel model = RandomModel(11);
  WriteColmapBinaryModel(model, dir.File("ours_bin"));
  EnsureWritableDirectory(dir.File("colmap_txt"));
  const std::string colmap = "QT_QPA_PLATFORM=offscreen colmap model_converter --input_path ";
  const auto to_text = RunCommand(colmap + dir.File("ours_bin") + " --output_path " +
                                  dir.File("colmap_txt") + " --output_type TXT");
  ASSERT_EQ(to_text.exit_code, 0) << to_text.output;
  ExpectSameModel(model,
                  WithOurRotations(SortedById(ReadColmapTextModel(dir.File("colmap_txt"))), model));

  WriteColmapTextModel(model, dir.File("ours_txt"));
  EnsureWritableDirectory(dir.File("colmap_bin"));
  const auto to_binary = RunCommand(colmap + dir.File("ours_txt") + " --output_path " +
                                    dir.File("colmap_bin") + " --output_type BIN");
  ASSERT_EQ(to_binary.exit_code, 0) << to_binary.output;
  ExpectSameModel(
      model, WithOurRotations(SortedById(ReadColmapBinaryModel(dir.File("colmap_bin"))), model));
}

TEST(ColmapBinaryModel, CorruptFilesFailCleanly) {
  ScopedTempDir dir;
  const ColmapTextModel model = RandomModel(8);
  WriteColmapBinaryModel(model, dir.path());
  const std::string images = ReadFileToString(dir.File("images.bin"));
  const auto expect_invalid = [&](const std::string& what) {
    try {
      ReadColmapBinaryModel(dir.path());
      ADD_FAILURE() << what << ": no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidData) << what << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("images.bin"), std::string::npos) << e.what();
    }
  };
  WriteFileAtomically(dir.File("images.bin"), images.substr(0, images.size() - 3));
  expect_invalid("truncated");
  WriteFileAtomically(dir.File("images.bin"), images + "x");
  expect_invalid("bytes left over");
  std::string huge_count = images;
  const uint64_t count = uint64_t{1} << 60;
  std::memcpy(huge_count.data(), &count, 8);
  WriteFileAtomically(dir.File("images.bin"), huge_count);
  expect_invalid("count larger than the file");
  WriteFileAtomically(dir.File("images.bin"), "");
  expect_invalid("empty");

  WriteColmapBinaryModel(model, dir.path());
  std::string cameras = ReadFileToString(dir.File("cameras.bin"));
  const int32_t unknown_model = 99;
  std::memcpy(cameras.data() + 12, &unknown_model, 4);
  WriteFileAtomically(dir.File("cameras.bin"), cameras);
  EXPECT_THROW(ReadColmapBinaryModel(dir.path()), Error);

  try {
    ReadColmapBinaryModel(dir.File("missing"));
    ADD_FAILURE() << "missing folder: no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kNotFound);
  }
}

TEST(ColmapBinaryModel, BadModelsAreRefusedBeforeWriting) {
  ScopedTempDir dir;
  ColmapTextModel wrong_params = RandomModel(1);
  wrong_params.cameras[0].params.pop_back();  // PINHOLE with 3 parameters
  EXPECT_THROW(WriteColmapBinaryModel(wrong_params, dir.File("a")), Error);
  ColmapTextModel unknown_model = RandomModel(1);
  unknown_model.cameras[0].model = "PANORAMA";
  EXPECT_THROW(WriteColmapBinaryModel(unknown_model, dir.File("b")), Error);
  EXPECT_FALSE(PathExists(dir.File("a/cameras.bin")));
  EXPECT_FALSE(PathExists(dir.File("b/cameras.bin")));
  EXPECT_EQ(ColmapCameraModelId("SIMPLE_RADIAL"), 2);
  EXPECT_EQ(ColmapCameraModelNumParams("OPENCV"), 8);
  EXPECT_THROW(ColmapCameraModelId("PANORAMA"), Error);
}

}  // namespace
}  // namespace comic::io
