// Calibration files for --intrinsics: plain numbers with distortion, K and P, OpenCV FileStorage
// YAML and XML, COLMAP cameras.txt; and the bad files each must refuse with one line.
#include "io/datasets/camera_calibration_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/core/error.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;

void Write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// An OpenCV calibration as cv::FileStorage writes it (what calibrateCamera users save).
void WriteOpenCv(const std::string& path, const cv::Mat& distortion, bool with_size = true) {
  cv::FileStorage storage(path, cv::FileStorage::WRITE);
  if (with_size) {
    storage << "image_width" << 1226;
    storage << "image_height" << 370;
  }
  storage << "camera_matrix"
          << (cv::Mat_<double>(3, 3) << 707.1, 0, 601.9, 0, 707.2, 183.1, 0, 0, 1);
  if (!distortion.empty()) storage << "distortion_coefficients" << distortion;
}

std::string ErrorOf(const std::string& path) {
  try {
    ReadCameraCalibrationFile(path);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(CameraCalibrationFile, ReadsNumbersWithAndWithoutDistortion) {
  ScopedTempDir dir;
  Write(dir.File("four.txt"), "707.1 707.2 601.9 183.1\n");
  CameraCalibration calibration = ReadCameraCalibrationFile(dir.File("four.txt"));
  EXPECT_EQ(calibration.model, "PINHOLE");
  EXPECT_EQ(calibration.params, (std::vector<double>{707.1, 707.2, 601.9, 183.1}));
  EXPECT_EQ(calibration.width, 0);
  Write(dir.File("eight.txt"), "707.1 707.2 601.9 183.1\n-0.3 0.1 0.001 -0.002\n");
  calibration = ReadCameraCalibrationFile(dir.File("eight.txt"));
  EXPECT_EQ(calibration.model, "OPENCV");
  EXPECT_EQ(calibration.params,
            (std::vector<double>{707.1, 707.2, 601.9, 183.1, -0.3, 0.1, 0.001, -0.002}));
  Write(dir.File("six.txt"), "707.1 707.2 601.9 183.1 -0.3 0.1\n");
  calibration = ReadCameraCalibrationFile(dir.File("six.txt"));
  EXPECT_EQ(calibration.model, "OPENCV");
  EXPECT_EQ(calibration.params[5], 0.1);
  EXPECT_EQ(calibration.params[6], 0.0);
  Write(dir.File("k.txt"), "707.1 0 601.9\n0 707.2 183.1\n0 0 1\n");
  calibration = ReadCameraCalibrationFile(dir.File("k.txt"));
  EXPECT_EQ(calibration.format, "K");
  EXPECT_EQ(calibration.params, (std::vector<double>{707.1, 707.2, 601.9, 183.1}));
}

TEST(CameraCalibrationFile, ReadsTheBundledKittiCalibAsP) {
  const CameraCalibration calibration =
      ReadCameraCalibrationFile(comic::test::ExampleDir() + "/calib.txt");
  EXPECT_EQ(calibration.format, "P");
  EXPECT_EQ(calibration.model, "PINHOLE");
  EXPECT_NEAR(calibration.params[0], 707.0912, 1e-4);
}

// `--intrinsics <(cat calib.txt)`: a pipe, read once (a second read found it empty: "got 0").
TEST(CameraCalibrationFile, ReadsAPipeOnce) {
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  const std::string text = "P0: 707.1 0 601.9 0 0 707.2 183.1 0 0 0 1 0\n";
  ASSERT_EQ(::write(ends[1], text.data(), text.size()), static_cast<ssize_t>(text.size()));
  ::close(ends[1]);
  const CameraCalibration calibration =
      ReadCameraCalibrationFile("/dev/fd/" + std::to_string(ends[0]));
  ::close(ends[0]);
  EXPECT_EQ(calibration.format, "P");
  EXPECT_EQ(calibration.params, (std::vector<double>{707.1, 707.2, 601.9, 183.1}));
}

TEST(CameraCalibrationFile, ReadsOpenCvYamlAndXml) {
  ScopedTempDir dir;
  for (const std::string name : {"calib.yml", "calib.xml"}) {
    WriteOpenCv(dir.File(name), (cv::Mat_<double>(1, 5) << -0.3, 0.1, 0.001, -0.002, 0.0));
    const CameraCalibration calibration = ReadCameraCalibrationFile(dir.File(name));
    EXPECT_EQ(calibration.format, "opencv") << name;
    EXPECT_EQ(calibration.model, "OPENCV");
    EXPECT_EQ(calibration.params,
              (std::vector<double>{707.1, 707.2, 601.9, 183.1, -0.3, 0.1, 0.001, -0.002}));
    EXPECT_EQ(calibration.width, 1226);
    EXPECT_EQ(calibration.height, 370);
  }
  // Four coefficients, a column vector, no size; and no coefficients at all.
  WriteOpenCv(dir.File("four.yaml"), (cv::Mat_<double>(4, 1) << -0.3, 0.1, 0.001, -0.002), false);
  CameraCalibration calibration = ReadCameraCalibrationFile(dir.File("four.yaml"));
  EXPECT_EQ(calibration.params[7], -0.002);
  EXPECT_EQ(calibration.width, 0);
  WriteOpenCv(dir.File("none.yml"), cv::Mat());
  calibration = ReadCameraCalibrationFile(dir.File("none.yml"));
  EXPECT_EQ(calibration.params[4], 0.0);
}

TEST(CameraCalibrationFile, RefusesOpenCvFilesTheModelsCannotHold) {
  ScopedTempDir dir;
  WriteOpenCv(dir.File("k3.yml"), (cv::Mat_<double>(1, 5) << -0.3, 0.1, 0.001, -0.002, 0.05));
  EXPECT_NE(ErrorOf(dir.File("k3.yml")).find("k3"), std::string::npos)
      << ErrorOf(dir.File("k3.yml"));
  WriteOpenCv(dir.File("three.yml"), (cv::Mat_<double>(1, 3) << -0.3, 0.1, 0.001));
  EXPECT_NE(ErrorOf(dir.File("three.yml")).find("4, 5 or 8"), std::string::npos);
  Write(dir.File("nomatrix.yml"), "%YAML:1.0\n---\nimage_width: 640\n");
  EXPECT_NE(ErrorOf(dir.File("nomatrix.yml")).find("camera_matrix"), std::string::npos);
  Write(dir.File("broken.yml"), "%YAML:1.0\n---\ncamera_matrix: [1, 2\n  : :\n");
  EXPECT_NE(ErrorOf(dir.File("broken.yml")).find("broken.yml"), std::string::npos);
  // A garbled size (found by fuzz_ground_truth): OpenCV alone would try to allocate 48 GB.
  Write(dir.File("hugecols.yml"),
        "%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: ls: 5\n"
        "   dt: d\n   data: [ -0.05, 0.01, 0.001, -0.002, 0. ]\n");
  EXPECT_NE(ErrorOf(dir.File("hugecols.yml")).find("camera_matrix"), std::string::npos)
      << ErrorOf(dir.File("hugecols.yml"));
  Write(dir.File("wrongcount.yml"),
        "%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n"
        "   dt: d\n   data: [ 1, 0, 0 ]\n");
  EXPECT_NE(ErrorOf(dir.File("wrongcount.yml")).find("3 x 3 with 3 values"), std::string::npos)
      << ErrorOf(dir.File("wrongcount.yml"));
  // An empty key: OpenCV's YAML parser throws std::length_error, not cv::Exception.
  Write(dir.File("emptykey.yml"),
        "%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
        "   \n   : [ 1., 0., 2., 0., 1., 2., 0., 0., 1. ]\n");
  EXPECT_NE(ErrorOf(dir.File("emptykey.yml")).find("emptykey.yml"), std::string::npos);
  for (const std::string name : {"k3.yml", "three.yml", "nomatrix.yml", "broken.yml",
                                 "hugecols.yml", "wrongcount.yml", "emptykey.yml"}) {
    EXPECT_EQ(ErrorOf(dir.File(name)).find('\n'), std::string::npos) << name;  // one line
  }
}

TEST(CameraCalibrationFile, ReadsTheFirstCameraOfColmapCamerasTxt) {
  ScopedTempDir dir;
  Write(dir.File("cameras.txt"),
        "# Camera list with one line of data per camera:\n"
        "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
        "1 SIMPLE_RADIAL 1226 370 850.5 613 185 -0.02\n"
        "2 PINHOLE 640 480 500 500 320 240\n");
  CameraCalibration calibration = ReadCameraCalibrationFile(dir.File("cameras.txt"));
  EXPECT_EQ(calibration.format, "colmap");
  EXPECT_EQ(calibration.model, "SIMPLE_RADIAL");
  // COLMAP's principal point is half a pixel further than OpenCV's.
  EXPECT_EQ(calibration.params, (std::vector<double>{850.5, 612.5, 184.5, -0.02}));
  EXPECT_EQ(calibration.width, 1226);
  const std::vector<std::pair<std::string, std::vector<double>>> kModels = {
      {"SIMPLE_PINHOLE 64 48 50 32 24", {50, 31.5, 23.5}},
      {"PINHOLE 64 48 50 51 32 24", {50, 51, 31.5, 23.5}},
      {"RADIAL 64 48 50 32 24 0.1 0.2", {50, 31.5, 23.5, 0.1, 0.2}},
      {"OPENCV 64 48 50 51 32 24 0.1 0.2 0.3 0.4", {50, 51, 31.5, 23.5, 0.1, 0.2, 0.3, 0.4}}};
  for (const auto& [row, params] : kModels) {
    Write(dir.File("model_cameras.txt"), "3 " + row + "\n");
    calibration = ReadCameraCalibrationFile(dir.File("model_cameras.txt"));
    EXPECT_EQ(calibration.params, params) << row;
  }
}

TEST(CameraCalibrationFile, RefusesBadFilesWithOneLine) {
  ScopedTempDir dir;
  const std::vector<std::pair<std::string, std::string>> kBad = {
      {"1 OPENCV_FISHEYE 64 48 50 51 32 24 0.1 0.2 0.3 0.4\n", "not supported"},
      {"1 PINHOLE 64 48 50 51 32\n", "takes 4 parameters"},
      {"1 PINHOLE 0 48 50 51 32 24\n", "WIDTH and HEIGHT"},
      {"1 SIMPLE_PINHOLE 64 48 -50 32 24\n", "positive"},
      {"1 PINHOLE 64 48 50 51 32 abc\n", "not a number"},
  };
  for (const auto& [text, words] : kBad) {
    Write(dir.File("cameras.txt"), text);
    const std::string message = ErrorOf(dir.File("cameras.txt"));
    EXPECT_NE(message.find(words), std::string::npos) << text << " -> " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  Write(dir.File("seven.txt"), "1 2 3 4 5 6 7\n");
  EXPECT_NE(ErrorOf(dir.File("seven.txt")).find("got 7"), std::string::npos);
  Write(dir.File("negative.txt"), "-1 2 3 4 0.1\n");
  EXPECT_NE(ErrorOf(dir.File("negative.txt")).find("positive"), std::string::npos);
  EXPECT_THROW(ReadCameraCalibrationFile(dir.File("missing.txt")), Error);
}

// fuzz_calibration_values: an XML header with NUL bytes inside made OpenCV 4.6's FileStorage
// parser dereference null. No calibration format holds a NUL byte, so none reaches a parser.
TEST(CameraCalibrationFile, RefusesFilesWithNulBytesBeforeAnyParser) {
  ScopedTempDir dir;
  std::string xml = "<?xml version=" + std::string(100, '\0') +
                    "\"1.0\"?>\n<opencv_storage>\n<image_width>1226</image_width>\n";
  for (const char* name : {"calib.xml", "calib.yml", "calib.txt", "cameras.txt"}) {
    std::ofstream(dir.File(name), std::ios::binary) << xml;
    const std::string message = ErrorOf(dir.File(name));
    EXPECT_NE(message.find("not a text file (a NUL byte at offset 14)"), std::string::npos)
        << name << " -> " << message;
  }
}

// fuzz_calibration_values: OpenCV 4.6's YAML parser loops forever on a line indented less than
// the top-level keys; such a file is refused before it reaches the parser, and a well-indented
// one with comments and markers still reads.
TEST(CameraCalibrationFile, RefusesYamlIndentedLessThanItsKeysBeforeTheParser) {
  ScopedTempDir dir;
  Write(dir.File("hang.yml"),
        "%YAML:1.0\n---\n   rnws: 3\n   cols: 3\n 99 -: d\n   data: [ 707.0912, 0. ]\n");
  const std::string message = ErrorOf(dir.File("hang.yml"));
  EXPECT_NE(message.find("line 5 is indented less than the top-level keys (column 4)"),
            std::string::npos)
      << message;
  Write(dir.File("fine.yml"),
        "%YAML:1.0\n---\n# a comment\nimage_width: 640\nimage_height: 480\n"
        "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
        "   data: [ 500., 0., 319.5, 0., 500., 239.5, 0., 0., 1. ]\n");
  const CameraCalibration calibration = ReadCameraCalibrationFile(dir.File("fine.yml"));
  EXPECT_EQ(calibration.width, 640);
}

}  // namespace
}  // namespace comic::io
