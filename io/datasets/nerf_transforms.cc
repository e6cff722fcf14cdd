#include "io/datasets/nerf_transforms.h"

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::io {
namespace {

// A number field of `object`, or `fallback` when absent. Throws for a non-number.
double NumberField(const nlohmann::json& object, const char* key, double fallback,
                   const std::string& where) {
  if (!object.contains(key)) return fallback;
  const nlohmann::json& value = object.at(key);
  COMIC_CHECK(value.is_number() && std::isfinite(value.get<double>()), kInvalidData,
              where << ": '" << key << "' is not a number");
  return value.get<double>();
}

Eigen::Matrix4d TransformMatrix(const nlohmann::json& frame, const std::string& where) {
  COMIC_CHECK(frame.contains("transform_matrix"), kInvalidData, where << ": no transform_matrix");
  const nlohmann::json& rows = frame.at("transform_matrix");
  COMIC_CHECK(rows.is_array() && (rows.size() == 4 || rows.size() == 3), kInvalidData,
              where << ": transform_matrix must have 4 rows of 4 numbers");
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  for (size_t r = 0; r < rows.size(); ++r) {
    COMIC_CHECK(rows[r].is_array() && rows[r].size() == 4, kInvalidData,
                where << ": transform_matrix must have 4 rows of 4 numbers");
    for (size_t c = 0; c < 4; ++c) {
      COMIC_CHECK(rows[r][c].is_number() && std::isfinite(rows[r][c].get<double>()), kInvalidData,
                  where << ": transform_matrix holds a value that is not a number");
      matrix(r, c) = rows[r][c].get<double>();
    }
  }
  COMIC_CHECK(matrix.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-9), kInvalidData,
              where << ": transform_matrix's last row must be 0 0 0 1");
  return matrix;
}

// The last component of a path, whatever the separators.
std::string LastComponent(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

void BlenderCamToWorldToCamFromWorld(const Eigen::Matrix4d& blender_world_from_cam,
                                     Eigen::Matrix3d* cam_from_world_rotation,
                                     Eigen::Vector3d* cam_from_world_translation) {
  Eigen::Matrix3d world_from_cam = blender_world_from_cam.topLeftCorner<3, 3>();
  const double error = (world_from_cam.transpose() * world_from_cam - Eigen::Matrix3d::Identity())
                           .cwiseAbs()
                           .maxCoeff();
  COMIC_CHECK(error < 1e-4 && world_from_cam.determinant() > 0, kInvalidData,
              "the camera-to-world rotation is not a rotation");
  // Blender's camera looks along −z with y up; OpenCV's along +z with y down.
  world_from_cam.col(1) *= -1.0;
  world_from_cam.col(2) *= -1.0;
  // Re-orthonormalise: the files' rotations are orthonormal only to float precision.
  const Eigen::Matrix3d rotation =
      Eigen::Quaterniond(world_from_cam).normalized().toRotationMatrix().transpose();
  const Eigen::Vector3d center = blender_world_from_cam.topRightCorner<3, 1>();
  *cam_from_world_rotation = rotation;
  *cam_from_world_translation = -(rotation * center);
}

namespace {

GroundTruthCameras ReadNerfTransformsJson(const nlohmann::json& json, const std::string& path) {
  COMIC_CHECK(json.is_object() && json.contains("frames") && json.at("frames").is_array(),
              kInvalidData, path << ": not a NeRF transforms file (no \"frames\" array)");
  const nlohmann::json& frames = json.at("frames");
  COMIC_CHECK(!frames.empty(), kInvalidData, path << ": \"frames\" is empty");
  const double angle_x = NumberField(json, "camera_angle_x", 0.0, path);
  const double width = NumberField(json, "w", 0.0, path);
  const double height = NumberField(json, "h", 0.0, path);
  const double fl_x = NumberField(json, "fl_x", 0.0, path);
  const double fl_y = NumberField(json, "fl_y", fl_x, path);
  bool distorted = false;
  for (const char* key : {"k1", "k2", "k3", "k4", "p1", "p2"}) {
    if (NumberField(json, key, 0.0, path) != 0.0) distorted = true;
  }
  COMIC_CHECK(angle_x >= 0 && angle_x < M_PI && fl_x >= 0 && fl_y >= 0 && width >= 0 &&
                  height >= 0 && width <= 1e6 && height <= 1e6,
              kInvalidData,
              path << ": camera_angle_x must be in [0, pi), focal lengths and sizes >= 0");
  COMIC_CHECK(angle_x > 0 || fl_x > 0 || distorted, kInvalidData,
              path << ": gives neither camera_angle_x nor fl_x");

  GroundTruthCameras result;
  result.format = GroundTruthFormat::kNerf;
  for (size_t i = 0; i < frames.size(); ++i) {
    const nlohmann::json& frame = frames[i];
    const std::string where = path + ": frame " + std::to_string(i);
    COMIC_CHECK(frame.is_object(), kInvalidData, where << ": not an object");
    COMIC_CHECK(frame.contains("file_path") && frame.at("file_path").is_string(), kInvalidData,
                where << ": no file_path");
    GroundTruthCamera camera;
    camera.index = static_cast<int>(i);
    camera.image_name = LastComponent(frame.at("file_path").get<std::string>());
    COMIC_CHECK(!camera.image_name.empty(), kInvalidData, where << ": empty file_path");
    try {
      BlenderCamToWorldToCamFromWorld(TransformMatrix(frame, where),
                                      &camera.cam_from_world_rotation,
                                      &camera.cam_from_world_translation);
    } catch (const Error& e) {
      throw Error(ErrorKind::kInvalidData, where + ": " + e.what());
    }
    if (distorted) {
      // Poses only: the intrinsics need the distortion model.
    } else if (fl_x > 0 && width > 0 && height > 0) {
      camera.has_intrinsics = true;
      camera.K << fl_x, 0, NumberField(json, "cx", width / 2, path) - 0.5, 0, fl_y,
          NumberField(json, "cy", height / 2, path) - 0.5, 0, 0, 1;
      camera.width = static_cast<int>(width);
      camera.height = static_cast<int>(height);
    } else if (angle_x > 0 && width > 0 && height > 0) {
      const double f = 0.5 * width / std::tan(0.5 * angle_x);
      camera.has_intrinsics = true;
      camera.K << f, 0, (width - 1) / 2, 0, f, (height - 1) / 2, 0, 0, 1;
      camera.width = static_cast<int>(width);
      camera.height = static_cast<int>(height);
    } else if (angle_x > 0) {
      camera.horizontal_fov_rad = angle_x;  // K once the frames' size is known
    }
    result.cameras.push_back(camera);
  }
  return result;
}

}  // namespace

GroundTruthCameras ReadNerfTransforms(const std::string& path) {
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such file");
  COMIC_CHECK(IsRegularFile(path), kInvalidData, path << ": not a file");
  try {
    return ReadNerfTransformsJson(nlohmann::json::parse(ReadFileToString(path)), path);
  } catch (const nlohmann::json::exception& e) {
    throw Error(ErrorKind::kInvalidData, path + ": not a valid transforms file (" + e.what() + ")");
  }
}

}  // namespace comic::io
