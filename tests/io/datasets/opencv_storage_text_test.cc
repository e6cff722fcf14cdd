// The allow-list in front of cv::FileStorage: what OpenCV and ROS write for a calibration passes
// (checked against cv::FileStorage's own output), and the malformed files that hang or crash
// OpenCV 4.6's parsers are refused with one line naming the file and line.
#include "io/datasets/opencv_storage_text.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/core.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/core/error.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    CheckOpenCvStorageText(text, "calib");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

// A calibration as calibrateCamera's users save it, in each of OpenCV's text formats.
std::string WrittenByOpenCv(const std::string& name) {
  comic::test::ScopedTempDir dir;
  {
    cv::FileStorage storage(dir.File(name), cv::FileStorage::WRITE);
    storage << "calibration_time"
            << "Fri Dec  4 15:00:00 2026";
    storage << "image_width" << 1226 << "image_height" << 370;
    storage << "flags" << 0;
    storage.writeComment("flags: +fix_aspectRatio");
    storage << "camera_matrix"
            << (cv::Mat_<double>(3, 3) << 707.0912, 0, 601.8873, 0, 707.0912, 183.1104, 0, 0, 1);
    storage << "distortion_coefficients" << (cv::Mat_<double>(1, 5) << -0.3, 0.1, 1e-3, -2e-3, 0);
    storage << "per_view_reprojection_errors" << cv::Mat(cv::Mat_<float>(40, 1, 0.25f));
    storage << "avg_reprojection_error" << 0.25;
  }
  std::ifstream file(dir.File(name), std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

TEST(OpenCvStorageText, PassesWhatOpenCvWrites) {
  for (const std::string name : {"calib.yml", "calib.xml"}) {
    const std::string text = WrittenByOpenCv(name);
    ASSERT_GT(text.size(), 200u) << name;
    EXPECT_EQ(ErrorOf(text), "") << name << ":\n" << text;
    EXPECT_EQ(ErrorOf("\xEF\xBB\xBF" + text), "") << name << " with a byte-order mark";
  }
}

TEST(OpenCvStorageText, PassesARosCameraInfoWithADirective) {
  const std::string ros =
      "%YAML:1.0\n"
      "image_width: 640\nimage_height: 480\ncamera_name: narrow_stereo\n"
      "camera_matrix:\n  rows: 3\n  cols: 3\n  data: [500.0, 0.0, 319.5, 0.0, 500.0, 239.5,\n"
      "         0.0, 0.0, 1.0]\n"
      "distortion_model: plumb_bob\n"
      "distortion_coefficients:\n  rows: 1\n  cols: 5\n  data: [-0.3, 0.1, 0.001, -0.002, 0.0]\n";
  EXPECT_EQ(ErrorOf(ros), "");
}

TEST(OpenCvStorageText, RefusesTheInputsThatHangOrCrashOpenCvWithOneLine) {
  const std::vector<std::pair<std::string, std::string>> kBad = {
      // Found by fuzz_calibration_values: OpenCV 4.6 loops forever on each.
      {"%YAML:1.0\n---\n   rnws: 3\n   cols: 3\n 99 -: d\n", "line 5 is indented less"},
      {"%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 3\n xy -: d\n", "line 5"},
      // An empty key: OpenCV throws std::length_error from inside its parser.
      {"%YAML:1.0\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   : [ 1. ]\n", "line 4"},
      {"%YAML:1.0\ncamera_matrix: [1, 2\n  : :\n", "expected numbers"},
      {"%YAML:1.0\ncamera_matrix: [1, 2\n", "not closed"},
      {"%YAML:1.0\ncamera_matrix: [1, , 2]\n", "expected numbers"},
      {"%YAML:1.0\ncamera_matrix: [1, 2] 3\n", "expected numbers"},
      {"%YAML:1.0\ncamera_matrix: !!opencv-matrix\n   cols: ls: 5\n", "under camera_matrix"},
      {"%YAML:1.0\nimage_width: 640\n   rows: 3\n", "has a value"},
      {"%YAML:1.0\na:\n  b:\n    c: 1\n", "line 3"},
      {"%YAML:1.0\na:\n  b: 1\n   c: 1\n", "unlike the keys beside it"},
      {"%YAML:1.0\na: - 5\n", "line 2"},
      {"%YAML:1.0\na: \"x\\\"y\"\n", "quoted"},
      {"%YAML:1.0\na: {b: 1}\n", "line 2"},
      {"%YAML:1.0\n- a: 1\n", "key: value"},
      {"%YAML:1.0\n\ta: 1\n", "tab"},
      {"%YAML:1.0\na: 1\n%YAML:1.0\n", "directive"},
      {"{\"camera_matrix\": 1}", "neither %YAML nor <?xml"},
      {" %YAML:1.0\na: 1\n", "neither %YAML nor <?xml"},
      {"<?xml version=\"1.0\"?>\n<a><b>1</c></a>", "does not close"},
      {"<?xml version=\"1.0\"?>\n<a><b>1</b>", "<a> is not closed"},
      {"<?xml version=\"1.0\"?>\n<a></a><a></a>", "second root"},
      {"<?xml version=\"1.0\"?>\n<a><b><c><d>1</d></c></b></a>", "three deep"},
      {"<?xml version=\"1.0\"?>\n<a x=1></a>", "name=\"value\""},
      {"<?xml version=\"1.0\"?>\n<a>&amp;</a>", "characters"},
      {"<?xml version=\"1.0\"?>\n<!DOCTYPE a>\n<a></a>", "line 2"},
      {"<?xml version=\"1.0\"?>\n<!-- open\n<a></a>", "comment is not closed"},
      {"<?xml version=\"1.0\" \n", "declaration is not closed"},
      {"<?xml version=\"1.0\"?>\n", "no root element"},
  };
  for (const auto& [text, words] : kBad) {
    const std::string message = ErrorOf(text);
    EXPECT_NE(message.find(words), std::string::npos) << text << "\n -> " << message;
    EXPECT_EQ(message.rfind("calib: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(OpenCvStorageText, RefusesAFileFarLargerThanACalibration) {
  const std::string huge = "%YAML:1.0\n" + std::string(9u << 20, '#');
  EXPECT_NE(ErrorOf(huge).find("too large"), std::string::npos);
}

}  // namespace
}  // namespace comic::io
