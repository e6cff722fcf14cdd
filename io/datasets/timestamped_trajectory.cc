#include "io/datasets/timestamped_trajectory.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/datasets/number_field.h"

namespace comic::io {
namespace {

struct DataLine {
  int number = 0;  // 1-based
  std::vector<std::string> fields;
};

// The lines that are neither blank nor '#' comments, split at whitespace or (`commas`) at commas
// with the whitespace around the fields dropped.
std::vector<DataLine> DataLines(const std::string& text, bool commas) {
  std::istringstream in(text);
  std::vector<DataLine> lines;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    if (commas) std::replace(line.begin(), line.end(), ',', ' ');
    DataLine parsed;
    parsed.number = number;
    std::istringstream fields(line);
    std::string field;
    while (fields >> field) parsed.fields.push_back(field);
    lines.push_back(std::move(parsed));
  }
  return lines;
}

bool AllNumbers(const std::vector<std::string>& fields, size_t count) {
  double value = 0.0;
  for (size_t i = 0; i < count && i < fields.size(); ++i) {
    if (!ParseNumberField(fields[i], &value)) return false;
  }
  return fields.size() >= count;
}

// A camera from a time stamp, the camera centre and the camera-to-world quaternion.
GroundTruthCamera CameraOf(const std::string& path, const DataLine& line, int index,
                           const double* values, bool scalar_first) {
  const Eigen::Vector3d center(values[1], values[2], values[3]);
  Eigen::Quaterniond world_from_cam =
      scalar_first ? Eigen::Quaterniond(values[4], values[5], values[6], values[7])
                   : Eigen::Quaterniond(values[7], values[4], values[5], values[6]);
  COMIC_CHECK(std::abs(world_from_cam.norm() - 1.0) < 1e-3, kInvalidData,
              path << ":" << line.number << ": the quaternion's norm is " << world_from_cam.norm()
                   << ", not 1");
  world_from_cam.normalize();
  GroundTruthCamera camera;
  camera.index = index;
  camera.timestamp = values[0];
  camera.cam_from_world_rotation = world_from_cam.conjugate().toRotationMatrix();
  camera.cam_from_world_translation = -(camera.cam_from_world_rotation * center);
  return camera;
}

GroundTruthCameras ReadTrajectory(const std::string& path, bool euroc) {
  COMIC_CHECK(IsRegularFile(path), kNotFound, path << ": no such file");
  GroundTruthCameras result;
  result.format = euroc ? GroundTruthFormat::kEuroc : GroundTruthFormat::kTum;
  result.timestamp_tolerance = euroc ? kEurocTimestampTolerance : kTumTimestampTolerance;
  for (const DataLine& line : DataLines(ReadFileToString(path), euroc)) {
    COMIC_CHECK(euroc ? line.fields.size() >= 8 : line.fields.size() == 8, kInvalidData,
                path << ":" << line.number << ": expected " << (euroc ? "at least " : "")
                     << "8 fields (timestamp, position, quaternion), got " << line.fields.size());
    double values[8];
    for (int i = 0; i < 8; ++i) {
      COMIC_CHECK(ParseNumberField(line.fields[i], &values[i]), kInvalidData,
                  path << ":" << line.number << ": '" << line.fields[i] << "' is not a number");
    }
    result.cameras.push_back(
        CameraOf(path, line, static_cast<int>(result.cameras.size()), values, euroc));
  }
  COMIC_CHECK(!result.cameras.empty(), kInvalidData, path << ": no pose in the file");
  return result;
}

}  // namespace

bool LooksLikeTumTrajectory(const std::string& text) {
  const std::vector<DataLine> lines = DataLines(text, false);
  return !lines.empty() && lines[0].fields.size() == 8 && AllNumbers(lines[0].fields, 8);
}

bool LooksLikeEurocGroundTruth(const std::string& text) {
  if (text.rfind("#timestamp", 0) == 0 && text.find("p_RS_R_x") != std::string::npos) return true;
  if (text.find(',') == std::string::npos) return false;
  const std::vector<DataLine> lines = DataLines(text, true);
  return !lines.empty() && AllNumbers(lines[0].fields, 8);
}

GroundTruthCameras ReadTumTrajectory(const std::string& path) {
  return ReadTrajectory(path, false);
}

GroundTruthCameras ReadEurocGroundTruth(const std::string& path) {
  return ReadTrajectory(path, true);
}

}  // namespace comic::io
