#include "io/datasets/kitti_odometry.h"

#include <cmath>
#include <sstream>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/datasets/number_field.h"

namespace comic::io {
namespace {

// The non-blank lines of a text file, with their 1-based line numbers.
std::vector<std::pair<int, std::string>> NonBlankLines(const std::string& path) {
  std::istringstream in(ReadFileToString(path));
  std::vector<std::pair<int, std::string>> lines;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.emplace_back(number, line);
  }
  return lines;
}

// Parses 12 whitespace-separated numbers after an optional "label:" prefix.
cv::Matx34d ParseMatrix34(const std::string& path, int line_number, const std::string& line) {
  std::string body = line;
  const size_t colon = body.find(':');
  if (colon != std::string::npos) body = body.substr(colon + 1);
  std::istringstream in(body);
  std::vector<double> values;
  std::string field;
  while (in >> field) {
    double value = 0.0;
    COMIC_CHECK(ParseNumberField(field, &value), kInvalidData,
                path << ":" << line_number << ": " << QuotedField(field) << " is not a number");
    values.push_back(value);
  }
  COMIC_CHECK(
      values.size() == 12, kInvalidData,
      path << ":" << line_number << ": expected 12 numbers (a 3x4 matrix), got " << values.size());
  cv::Matx34d m;
  for (int i = 0; i < 12; ++i) m.val[i] = values[i];
  return m;
}

}  // namespace

std::vector<cv::Matx34d> ReadKittiPoses(const std::string& path) {
  std::vector<cv::Matx34d> poses;
  for (const auto& [number, line] : NonBlankLines(path)) {
    const cv::Matx34d pose = ParseMatrix34(path, number, line);
    const cv::Matx33d r = pose.get_minor<3, 3>(0, 0);
    const cv::Matx33d rtr = r.t() * r;
    const double error = cv::norm(rtr - cv::Matx33d::eye(), cv::NORM_INF);
    COMIC_CHECK(error < 1e-4 && cv::determinant(r) > 0, kInvalidData,
                path << ":" << number << ": the 3x3 part is not a rotation");
    poses.push_back(pose);
  }
  COMIC_CHECK(!poses.empty(), kInvalidData, path << ": holds no pose");
  return poses;
}

cv::Matx34d ReadKittiProjection(const std::string& path, int camera) {
  COMIC_CHECK(camera >= 0, kInvalidArgument, "camera index must be >= 0, got " << camera);
  const auto lines = NonBlankLines(path);
  COMIC_CHECK(camera < static_cast<int>(lines.size()), kInvalidData,
              path << ": has " << lines.size() << " matrices, P" << camera << " requested");
  return ParseMatrix34(path, lines[camera].first, lines[camera].second);
}

cv::Matx33d ReadKittiIntrinsics(const std::string& path, int camera) {
  const cv::Matx34d p = ReadKittiProjection(path, camera);
  const cv::Matx33d k = p.get_minor<3, 3>(0, 0);
  COMIC_CHECK(
      k(0, 0) > 0 && k(1, 1) > 0 && k(1, 0) == 0 && k(2, 0) == 0 && k(2, 1) == 0 && k(2, 2) == 1,
      kInvalidData,
      path << ": P" << camera << " is not of the form K [I | t] with K upper triangular");
  return k;
}

}  // namespace comic::io
