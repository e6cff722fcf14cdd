// The round trip every COLMAP model format keeps, said once and run over the text and the binary
// format: what we write reads back exactly, writing again gives the same bytes, the folder reader
// finds it, and bad input fails with comic::Error before anything is written. Each format's own
// test file holds what only it does (COLMAP's text layout and line errors, the binary byte
// layout, corrupt files, the real colmap binary).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_model_folder.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/io/colmap/colmap_test_models.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;

struct ModelFormat {
  std::string name;
  void (*write)(const ColmapTextModel&, const std::string&);
  ColmapTextModel (*read)(const std::string&);
  std::vector<std::string> files;
};

// gtest_discover_tests names each test after this: ".../Text", ".../Binary".
void PrintTo(const ModelFormat& format, std::ostream* out) { *out << format.name; }

class ColmapModelRoundTrip : public ::testing::TestWithParam<ModelFormat> {};

// Every camera model both formats know, with parameters that need all 17 digits.
ColmapTextModel ModelOfEveryCamera() {
  ColmapTextModel model = test::RandomModel(5);
  model.cameras = {{1, "SIMPLE_PINHOLE", 100, 80, {0.1 + 1e-16, 50.5, 40.25}},
                   {2, "PINHOLE", 1226, 370, {707.0912, 707.0913, 602.3873, 183.6104}},
                   {3, "SIMPLE_RADIAL", 640, 480, {800.1, 320.5, 240.5, -1e-300}},
                   {4, "RADIAL", 640, 480, {800.1, 320.5, 240.5, 1e-3, -2.5e-7}},
                   {5, "OPENCV", 640, 480, {1e300, 801.2, 320.5, 240.5, 0.01, -0.02, 3e-5, -4e-5}}};
  for (size_t i = 0; i < model.images.size(); ++i) {
    model.images[i].camera_id = static_cast<uint32_t>(i + 2);
  }
  return model;
}

TEST_P(ColmapModelRoundTrip, ReadsBackExactlyWhatItWrote) {
  const ModelFormat& format = GetParam();
  ScopedTempDir dir;
  for (uint32_t seed : {1u, 42u, 1000u}) {
    const ColmapTextModel model = test::RandomModel(seed);
    const std::string folder = dir.File("seed" + std::to_string(seed));
    format.write(model, folder);
    test::ExpectSameModel(model, format.read(folder));
  }
  format.write(ModelOfEveryCamera(), dir.File("cameras"));
  test::ExpectSameModel(ModelOfEveryCamera(), format.read(dir.File("cameras")));
}

TEST_P(ColmapModelRoundTrip, WritingAgainGivesTheSameBytes) {
  const ModelFormat& format = GetParam();
  ScopedTempDir dir;
  const ColmapTextModel model = test::RandomModel(42);
  format.write(model, dir.File("a"));
  format.write(format.read(dir.File("a")), dir.File("b"));
  format.write(model, dir.File("a"));  // over the first
  for (const std::string& file : format.files) {
    const std::string bytes = ReadFileToString(dir.File("a/" + file));
    EXPECT_FALSE(bytes.empty()) << file;
    EXPECT_EQ(bytes, ReadFileToString(dir.File("b/" + file))) << file;
  }
}

TEST_P(ColmapModelRoundTrip, TheFolderReaderFindsItAsModelOrSparseZero) {
  const ModelFormat& format = GetParam();
  ScopedTempDir dir;
  const ColmapTextModel model = test::RandomModel(7);
  format.write(model, dir.File("model"));
  test::ExpectSameModel(model, ReadColmapModel(dir.File("model")));
  format.write(model, dir.File("project/sparse/0"));
  test::ExpectSameModel(model, ReadColmapModel(dir.File("project")));
}

TEST_P(ColmapModelRoundTrip, AMissingFolderIsNotFound) {
  ScopedTempDir dir;
  try {
    GetParam().read(dir.File("missing"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kNotFound) << e.what();
  }
}

TEST_P(ColmapModelRoundTrip, AModelFailingCheckIsRefusedBeforeWriting) {
  const ModelFormat& format = GetParam();
  ScopedTempDir dir;
  ColmapTextModel model = test::RandomModel(3);
  model.images[1].camera_id = 9;  // no such camera
  EXPECT_THROW(format.write(model, dir.File("out")), Error);
  for (const std::string& file : format.files) {
    EXPECT_FALSE(PathExists(dir.File("out/" + file))) << file;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Formats, ColmapModelRoundTrip,
    ::testing::Values(ModelFormat{"Text",
                                  WriteColmapTextModel,
                                  ReadColmapTextModel,
                                  {"cameras.txt", "images.txt", "points3D.txt"}},
                      ModelFormat{"Binary",
                                  WriteColmapBinaryModel,
                                  ReadColmapBinaryModel,
                                  {"cameras.bin", "images.bin", "points3D.bin"}}));

}  // namespace
}  // namespace comic::io
