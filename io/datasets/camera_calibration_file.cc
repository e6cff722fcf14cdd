#include "io/datasets/camera_calibration_file.h"

#include <cctype>
#include <cmath>
#include <exception>
#include <fstream>
#include <opencv2/core.hpp>
#include <sstream>

#include "io/colmap/colmap_binary_model.h"
#include "io/core/error.h"
#include "io/core/input_file.h"
#include "io/datasets/ground_truth_cameras.h"
#include "io/datasets/number_field.h"
#include "io/datasets/opencv_storage_text.h"

namespace comic::io {

namespace {

// COLMAP's cameras.txt and OpenCV's files put the top-left pixel centre at (0.5, 0.5) and
// (0, 0) respectively.
constexpr double kColmapPixelOffset = 0.5;

bool EndsWith(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(text[text.size() - suffix.size() + i])) !=
        suffix[i]) {
      return false;
    }
  }
  return true;
}

std::string ReadText(const std::string& path) {
  CheckInputFile(path);
  std::ifstream file(path, std::ios::binary);
  COMIC_CHECK(file.good(), kNotFound, path << ": cannot open intrinsics file");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// The lines that are neither blank nor '#' comments, split into fields.
std::vector<std::pair<int, std::vector<std::string>>> ContentLines(const std::string& text) {
  std::vector<std::pair<int, std::vector<std::string>>> lines;
  std::istringstream stream(text);
  std::string line;
  int number = 0;
  while (std::getline(stream, line)) {
    ++number;
    std::istringstream fields(line);
    std::vector<std::string> values;
    std::string field;
    while (fields >> field) values.push_back(field);
    if (values.empty() || values[0][0] == '#') continue;
    lines.emplace_back(number, std::move(values));
  }
  return lines;
}

// Reads a small matrix node (an !!opencv-matrix map or a plain sequence of numbers). OpenCV's own
// reader trusts the node's rows and cols and allocates rows x cols before it looks at the data, so
// a garbled size ("cols: ls: 5") asks for tens of GB: check the shape against the data first.
cv::Mat ReadSmallMatrix(const cv::FileNode& node, const std::string& path, const char* name) {
  constexpr int kMaxElements = 16;
  cv::Mat matrix;
  if (node.empty() || node.isNone()) return matrix;
  if (node.isSeq()) {
    COMIC_CHECK(node.size() <= static_cast<size_t>(kMaxElements), kInvalidData,
                path << ": " << name << " has " << node.size() << " values (at most "
                     << kMaxElements << " expected)");
  } else {
    COMIC_CHECK(
        node.isMap() && node["rows"].isInt() && node["cols"].isInt() && node["data"].isSeq(),
        kInvalidData, path << ": " << name << " is not a matrix (rows, cols, dt, data)");
    const int rows = static_cast<int>(node["rows"]);
    const int cols = static_cast<int>(node["cols"]);
    COMIC_CHECK(rows >= 1 && cols >= 1 && rows <= kMaxElements && cols <= kMaxElements &&
                    rows * cols <= kMaxElements &&
                    node["data"].size() == static_cast<size_t>(rows * cols),
                kInvalidData,
                path << ": " << name << " is " << rows << " x " << cols << " with "
                     << node["data"].size() << " values");
  }
  node >> matrix;
  return matrix;
}

// Parses the text already read and checked, not the file again: one read, and the bytes checked
// are the bytes parsed even if the file changes meanwhile.
CameraCalibration ReadOpenCvText(const std::string& text, const std::string& path) {
  cv::FileStorage storage;
  try {
    storage.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  } catch (const std::exception&) {
    // cv::Exception, and what OpenCV's parser lets through from below it (an empty YAML key
    // throws std::length_error from std::string, found by fuzz_ground_truth).
    throw Error(ErrorKind::kInvalidData,
                path + ": not a readable OpenCV FileStorage (YAML/XML) file");
  }
  COMIC_CHECK(storage.isOpened(), kInvalidData,
              path << ": not a readable OpenCV FileStorage (YAML/XML) file");
  cv::Mat camera_matrix, distortion;
  int width = 0, height = 0;
  try {
    camera_matrix = ReadSmallMatrix(storage["camera_matrix"], path, "camera_matrix");
    distortion =
        ReadSmallMatrix(storage["distortion_coefficients"], path, "distortion_coefficients");
    if (!storage["image_width"].empty()) storage["image_width"] >> width;
    if (!storage["image_height"].empty()) storage["image_height"] >> height;
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    throw Error(ErrorKind::kInvalidData,
                path + ": camera_matrix or distortion_coefficients is not a matrix of numbers");
  }
  COMIC_CHECK(!camera_matrix.empty() && camera_matrix.rows == 3 && camera_matrix.cols == 3,
              kInvalidData, path << ": expected camera_matrix, a 3x3 matrix");
  camera_matrix.convertTo(camera_matrix, CV_64F);
  const auto k = [&](int r, int c) { return camera_matrix.at<double>(r, c); };
  COMIC_CHECK(std::abs(k(0, 1)) < 1e-9 * std::abs(k(0, 0)) && k(1, 0) == 0 && k(2, 0) == 0 &&
                  k(2, 1) == 0 && k(2, 2) == 1,
              kInvalidData, path << ": camera_matrix must be [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
  COMIC_CHECK(k(0, 0) > 0 && k(1, 1) > 0, kInvalidData,
              path << ": camera_matrix focal lengths must be positive");
  std::vector<double> coefficients;
  if (!distortion.empty()) {
    COMIC_CHECK(distortion.rows == 1 || distortion.cols == 1, kInvalidData,
                path << ": distortion_coefficients must be a vector");
    distortion.convertTo(distortion, CV_64F);
    coefficients.assign(distortion.begin<double>(), distortion.end<double>());
  }
  const size_t count = coefficients.size();
  COMIC_CHECK(
      count == 0 || count == 4 || count == 5 || count == 8, kInvalidData,
      path << ": distortion_coefficients must have 4, 5 or 8 values (k1 k2 p1 p2 [k3 [k4 k5 "
              "k6]]), got "
           << count);
  for (size_t i = 4; i < count; ++i) {
    COMIC_CHECK(coefficients[i] == 0.0, kInvalidData,
                path << ": distortion coefficient " << (i == 4 ? "k3" : "k" + std::to_string(i))
                     << " = " << coefficients[i]
                     << " is not supported (the OPENCV model has k1 k2 p1 p2 only)");
  }
  for (double c : coefficients) {
    COMIC_CHECK(std::isfinite(c), kInvalidData, path << ": distortion coefficients must be finite");
  }
  CameraCalibration calibration;
  calibration.format = "opencv";
  calibration.width = width;
  calibration.height = height;
  calibration.model = "OPENCV";
  calibration.params = {k(0, 0), k(1, 1), k(0, 2), k(1, 2), 0.0, 0.0, 0.0, 0.0};
  for (size_t i = 0; i < std::min<size_t>(count, 4); ++i)
    calibration.params[4 + i] = coefficients[i];
  return calibration;
}

CameraCalibration ReadColmapCameras(
    const std::string& path, const std::vector<std::pair<int, std::vector<std::string>>>& lines) {
  COMIC_CHECK(!lines.empty(), kInvalidData, path << ": no camera in this COLMAP cameras.txt");
  const auto& [line_number, fields] = lines[0];
  const std::string where = path + ":" + std::to_string(line_number);
  COMIC_CHECK(fields.size() >= 4, kInvalidData,
              where << ": expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]");
  const std::string& model = fields[1];
  int num_params = -1;
  try {
    num_params = ColmapCameraModelNumParams(model);
  } catch (const Error&) {
    // Not one of COLMAP's names: said below with the file and line, not as a bare name.
  }
  COMIC_CHECK(num_params > 0 && ColmapCameraModelId(model) <= 4, kInvalidData,
              where << ": camera model " << model
                    << (num_params > 0 ? " is not supported" : " is not one of COLMAP's models")
                    << " (supported: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV)");
  COMIC_CHECK(static_cast<int>(fields.size()) == 4 + num_params, kInvalidData,
              where << ": " << model << " takes " << num_params << " parameters, got "
                    << static_cast<int>(fields.size()) - 4);
  CameraCalibration calibration;
  calibration.format = "colmap";
  calibration.model = model;
  double width = 0, height = 0;
  COMIC_CHECK(ParseNumberField(fields[2], &width) && ParseNumberField(fields[3], &height) &&
                  width >= 1 && height >= 1 && width == std::floor(width) &&
                  height == std::floor(height) && width <= 1e6 && height <= 1e6,
              kInvalidData, where << ": WIDTH and HEIGHT must be positive integers");
  calibration.width = static_cast<int>(width);
  calibration.height = static_cast<int>(height);
  for (int i = 0; i < num_params; ++i) {
    double value = 0;
    COMIC_CHECK(ParseNumberField(fields[4 + i], &value), kInvalidData,
                where << ": parameter " << QuotedField(fields[4 + i]) << " is not a number");
    calibration.params.push_back(value);
  }
  const int pp = (model == "PINHOLE" || model == "OPENCV") ? 2 : 1;  // fx fy, or one f
  COMIC_CHECK(calibration.params[0] > 0 && calibration.params[pp - 1] > 0, kInvalidData,
              where << ": focal lengths must be positive");
  calibration.params[pp] -= kColmapPixelOffset;
  calibration.params[pp + 1] -= kColmapPixelOffset;
  return calibration;
}

// K from 4 numbers (fx fy cx cy), 9 (K, row by row) or 12 and more (a 3x4 projection matrix P =
// K [R | t], as KITTI's calib.txt holds): the values already read, so a stream is read once.
Eigen::Matrix3d IntrinsicsMatrix(const std::vector<double>& values) {
  Eigen::Matrix3d k = Eigen::Matrix3d::Identity();
  if (values.size() == 4) {
    k(0, 0) = values[0];
    k(1, 1) = values[1];
    k(0, 2) = values[2];
    k(1, 2) = values[3];
    return k;
  }
  const int row_length = values.size() == 9 ? 3 : 4;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k(r, c) = values[row_length * r + c];
  }
  return k;
}

}  // namespace

CameraCalibration ReadCameraCalibrationFile(const std::string& path) {
  const std::string text = ReadText(path);
  // Every format here is text. OpenCV 4.6's FileStorage parser dereferences null on an XML
  // header with NUL bytes in it (found by fuzz_calibration_values), so none reaches it.
  const size_t nul = text.find('\0');
  COMIC_CHECK(nul == std::string::npos, kInvalidData,
              path << ": not a text file (a NUL byte at offset " << nul << ")");
  size_t start = text.find_first_not_of(" \t\r\n");
  const std::string head = start == std::string::npos ? "" : text.substr(start, 16);
  if (EndsWith(path, ".yml") || EndsWith(path, ".yaml") || EndsWith(path, ".xml") ||
      head.rfind("%YAML", 0) == 0 || head.rfind("<?xml", 0) == 0) {
    // OpenCV 4.6's parsers hang or crash on some malformed files: only the part of the formats a
    // calibration is written in reaches them.
    CheckOpenCvStorageText(text, path);
    return ReadOpenCvText(text, path);
  }
  const auto lines = ContentLines(text);
  // COLMAP: "CAMERA_ID MODEL ..." (an integer, then a name), or the file is named cameras.txt.
  const bool colmap_row = !lines.empty() && lines[0].second.size() >= 2 &&
                          std::isalpha(static_cast<unsigned char>(lines[0].second[1][0])) &&
                          std::isdigit(static_cast<unsigned char>(lines[0].second[0][0]));
  if (colmap_row || EndsWith(path, "cameras.txt")) return ReadColmapCameras(path, lines);

  // Numbers, each line optionally labelled ("P0:").
  std::vector<double> values;
  for (const auto& [line_number, fields] : lines) {
    for (const std::string& field : fields) {
      if (field.back() == ':') continue;
      double value = 0;
      COMIC_CHECK(ParseNumberField(field, &value), kInvalidData,
                  path << ":" << line_number << ": " << QuotedField(field) << " is not a number");
      values.push_back(value);
    }
  }
  CameraCalibration calibration;
  if (values.size() == 5 || values.size() == 6 || values.size() == 8) {
    COMIC_CHECK(
        values[0] > 0 && values[1] > 0, kInvalidData,
        path << ": focal lengths must be positive, got fx=" << values[0] << " fy=" << values[1]);
    calibration.format = "numbers";
    calibration.model = "OPENCV";
    calibration.params = values;
    calibration.params.resize(8, 0.0);
    return calibration;
  }
  COMIC_CHECK(values.size() == 4 || values.size() == 9 || values.size() >= 12, kInvalidData,
              path << ": expected intrinsics as 4 numbers (fx fy cx cy), 5, 6 or 8 (fx fy cx cy k1 "
                      "[k2 [p1 p2]]), 9 (K) or 12 (a 3x4 projection matrix), got "
                   << values.size());
  const Eigen::Matrix3d k = IntrinsicsMatrix(values);
  COMIC_CHECK(k(0, 0) > 0 && k(1, 1) > 0 && k(1, 0) == 0 && k(2, 0) == 0 && k(2, 1) == 0 &&
                  std::abs(k(2, 2) - 1.0) < 1e-12,
              kInvalidData,
              path << ":" << lines.front().first
                   << ": intrinsics must be upper triangular with positive focal lengths and "
                      "K(2,2) = 1");
  COMIC_CHECK(std::abs(k(0, 1)) < 1e-9 * std::abs(k(0, 0)), kInvalidData,
              path << ": intrinsics with skew are not supported (K(0,1) = " << k(0, 1) << ")");
  calibration.format = values.size() == 4 ? "numbers" : values.size() == 9 ? "K" : "P";
  calibration.model = "PINHOLE";
  calibration.params = {k(0, 0), k(1, 1), k(0, 2), k(1, 2)};
  return calibration;
}

}  // namespace comic::io
