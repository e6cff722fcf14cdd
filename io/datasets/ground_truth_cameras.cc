#include "io/datasets/ground_truth_cameras.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/input_file.h"
#include "io/datasets/kitti_odometry.h"
#include "io/datasets/nerf_transforms.h"
#include "io/datasets/number_field.h"
#include "io/datasets/timestamped_trajectory.h"

namespace comic::io {
namespace {

struct TextLine {
  int number = 0;                   // 1-based
  std::vector<std::string> fields;  // whitespace separated, a "label:" prefix removed
};

std::vector<TextLine> NonBlankLines(const std::string& path, bool strip_label) {
  std::istringstream in(ReadFileToString(path));
  std::vector<TextLine> lines;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (strip_label) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) line = line.substr(colon + 1);
    }
    std::istringstream fields(line);
    TextLine parsed;
    parsed.number = number;
    std::string field;
    while (fields >> field) parsed.fields.push_back(field);
    if (!parsed.fields.empty()) lines.push_back(std::move(parsed));
  }
  return lines;
}

double Number(const std::string& path, int line, const std::string& text) {
  double value = 0.0;
  COMIC_CHECK(ParseNumberField(text, &value), kInvalidData,
              path << ":" << line << ": " << QuotedField(text) << " is not a number");
  return value;
}

void CheckRotation(const std::string& path, int line, const Eigen::Matrix3d& r) {
  const double error = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  COMIC_CHECK(error < 1e-4 && r.determinant() > 0, kInvalidData,
              path << ":" << line << ": the matrix is not a rotation");
}

void CheckIntrinsics(const std::string& path, int line, const Eigen::Matrix3d& k) {
  COMIC_CHECK(k(0, 0) > 0 && k(1, 1) > 0 && k(1, 0) == 0 && k(2, 0) == 0 && k(2, 1) == 0 &&
                  std::abs(k(2, 2) - 1.0) < 1e-12,
              kInvalidData,
              path << ":" << line
                   << ": intrinsics must be upper triangular with positive focal lengths and "
                      "K(2,2) = 1");
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// "bin" or "txt" for a folder holding a COLMAP model's cameras and images files (binary first),
// nullptr otherwise.
const char* ColmapModelKind(const std::string& folder) {
  for (const char* kind : {"bin", "txt"}) {
    const std::string ext = std::string(".") + kind;
    if (IsRegularFile(JoinPaths(folder, "cameras" + ext)) &&
        IsRegularFile(JoinPaths(folder, "images" + ext))) {
      return kind;
    }
  }
  return nullptr;
}

// K of a COLMAP camera in OpenCV's pixel convention, when the camera has no distortion.
bool UndistortedColmapK(const ColmapCamera& camera, Eigen::Matrix3d* k) {
  const std::vector<double>& p = camera.params;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  size_t first_distortion = p.size();
  if ((camera.model == "SIMPLE_PINHOLE" || camera.model == "SIMPLE_RADIAL" ||
       camera.model == "RADIAL") &&
      p.size() >= 3) {
    fx = fy = p[0];
    cx = p[1];
    cy = p[2];
    first_distortion = 3;
  } else if ((camera.model == "PINHOLE" || camera.model == "OPENCV" ||
              camera.model == "FULL_OPENCV") &&
             p.size() >= 4) {
    fx = p[0];
    fy = p[1];
    cx = p[2];
    cy = p[3];
    first_distortion = 4;
  } else {
    return false;  // fisheye and other models: poses only
  }
  for (size_t i = first_distortion; i < p.size(); ++i) {
    if (p[i] != 0.0) return false;
  }
  if (!(fx > 0 && fy > 0 && std::isfinite(cx) && std::isfinite(cy))) return false;
  *k << fx, 0, cx - 0.5, 0, fy, cy - 0.5, 0, 0, 1;
  return true;
}

}  // namespace

const char* GroundTruthFormatName(GroundTruthFormat format) {
  switch (format) {
    case GroundTruthFormat::kAuto:
      return "auto";
    case GroundTruthFormat::kKitti:
      return "kitti";
    case GroundTruthFormat::kMiddlebury:
      return "middlebury";
    case GroundTruthFormat::kStrecha:
      return "strecha";
    case GroundTruthFormat::kColmap:
      return "colmap";
    case GroundTruthFormat::kNerf:
      return "nerf";
    case GroundTruthFormat::kTum:
      return "tum";
    case GroundTruthFormat::kEuroc:
      return "euroc";
  }
  return "unknown";
}

const char* GroundTruthLengthUnit(GroundTruthFormat format) {
  return format == GroundTruthFormat::kKitti || format == GroundTruthFormat::kStrecha ||
                 format == GroundTruthFormat::kTum || format == GroundTruthFormat::kEuroc
             ? "m"
             : "";
}

GroundTruthFormat ParseGroundTruthFormat(const std::string& name) {
  for (GroundTruthFormat format :
       {GroundTruthFormat::kAuto, GroundTruthFormat::kKitti, GroundTruthFormat::kMiddlebury,
        GroundTruthFormat::kStrecha, GroundTruthFormat::kColmap, GroundTruthFormat::kNerf,
        GroundTruthFormat::kTum, GroundTruthFormat::kEuroc}) {
    if (name == GroundTruthFormatName(format)) return format;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "unknown ground-truth format '" + name +
                  "' (expected auto, kitti, middlebury, strecha, colmap, nerf, tum or euroc)");
}

GroundTruthFormat DetectGroundTruthFormat(const std::string& path) {
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such file or folder");
  if (IsDirectory(path)) {
    if (ColmapModelKind(path) != nullptr) return GroundTruthFormat::kColmap;
    for (const std::string& name : ListFiles(path)) {
      if (EndsWith(name, ".camera")) return GroundTruthFormat::kStrecha;
    }
    throw Error(ErrorKind::kInvalidData,
                path +
                    ": folder holds neither a COLMAP model (cameras.bin, images.bin or "
                    "cameras.txt, images.txt) nor *.camera files (ground-truth cameras)");
  }
  CheckInputFile(path);
  COMIC_CHECK(IsRegularFile(path), kInvalidData,
              path << ": ground truth must be a regular file, not a stream (its format is detected "
                      "from its text, then it is read)");
  if (EndsWith(path, ".camera")) return GroundTruthFormat::kStrecha;
  if (EndsWith(path, ".json")) return GroundTruthFormat::kNerf;
  for (const char* name :
       {"cameras.bin", "images.bin", "points3D.bin", "cameras.txt", "images.txt", "points3D.txt"}) {
    if (FileName(path) == name) return GroundTruthFormat::kColmap;
  }
  const std::string text = ReadFileToString(path);
  if (LooksLikeEurocGroundTruth(text)) return GroundTruthFormat::kEuroc;
  if (LooksLikeTumTrajectory(text)) return GroundTruthFormat::kTum;
  const std::vector<TextLine> lines = NonBlankLines(path, false);
  COMIC_CHECK(!lines.empty(), kInvalidData, path << ": empty ground-truth file");
  double value = 0.0;
  if (lines[0].fields.size() == 1 && ParseNumberField(lines[0].fields[0], &value)) {
    return GroundTruthFormat::kMiddlebury;
  }
  if (lines[0].fields.size() == 12) return GroundTruthFormat::kKitti;
  throw Error(
      ErrorKind::kInvalidData,
      path +
          ": not a known ground-truth format (KITTI poses.txt, Middlebury *_par.txt, "
          "Strecha *.camera, a COLMAP model, a NeRF transforms.json, a TUM trajectory, EuRoC's "
          "groundtruth data.csv)");
}

GroundTruthCameras ReadMiddleburyParFile(const std::string& path) {
  const std::vector<TextLine> lines = NonBlankLines(path, false);
  COMIC_CHECK(!lines.empty() && lines[0].fields.size() == 1, kInvalidData,
              path << ":1: expected the number of cameras");
  const double count = Number(path, lines[0].number, lines[0].fields[0]);
  COMIC_CHECK(count >= 1 && count == std::floor(count), kInvalidData,
              path << ":" << lines[0].number << ": bad camera count " << lines[0].fields[0]);
  // Compared as doubles: a count beyond size_t (fuzzing found 7e22) must not be cast first.
  COMIC_CHECK(count == static_cast<double>(lines.size() - 1), kInvalidData,
              path << ": says " << count << " cameras but lists " << lines.size() - 1);
  GroundTruthCameras result;
  result.format = GroundTruthFormat::kMiddlebury;
  for (size_t i = 1; i < lines.size(); ++i) {
    const TextLine& line = lines[i];
    COMIC_CHECK(line.fields.size() == 22, kInvalidData,
                path << ":" << line.number << ": expected an image name and 21 numbers, got "
                     << line.fields.size() << " fields");
    GroundTruthCamera camera;
    camera.image_name = line.fields[0];
    camera.index = static_cast<int>(i - 1);
    for (int k = 0; k < 9; ++k)
      camera.K(k / 3, k % 3) = Number(path, line.number, line.fields[1 + k]);
    for (int k = 0; k < 9; ++k) {
      camera.cam_from_world_rotation(k / 3, k % 3) = Number(path, line.number, line.fields[10 + k]);
    }
    for (int k = 0; k < 3; ++k) {
      camera.cam_from_world_translation(k) = Number(path, line.number, line.fields[19 + k]);
    }
    CheckIntrinsics(path, line.number, camera.K);
    CheckRotation(path, line.number, camera.cam_from_world_rotation);
    camera.has_intrinsics = true;
    result.cameras.push_back(camera);
  }
  return result;
}

GroundTruthCamera ReadStrechaCameraFile(const std::string& path) {
  const std::vector<TextLine> lines = NonBlankLines(path, false);
  COMIC_CHECK(lines.size() >= 9, kInvalidData,
              path << ": a Strecha camera file has 9 lines (K, distortion, R, C, size), got "
                   << lines.size());
  const auto row = [&](size_t i, size_t n) {
    COMIC_CHECK(lines[i].fields.size() == n, kInvalidData,
                path << ":" << lines[i].number << ": expected " << n << " numbers, got "
                     << lines[i].fields.size());
    std::vector<double> values;
    for (const std::string& field : lines[i].fields)
      values.push_back(Number(path, lines[i].number, field));
    return values;
  };
  GroundTruthCamera camera;
  for (int r = 0; r < 3; ++r) {
    const std::vector<double> k = row(r, 3);
    for (int c = 0; c < 3; ++c) camera.K(r, c) = k[c];
  }
  CheckIntrinsics(path, lines[0].number, camera.K);
  const std::vector<double> distortion = row(3, 3);
  COMIC_CHECK(distortion[0] == 0 && distortion[1] == 0 && distortion[2] == 0, kInvalidData,
              path << ":" << lines[3].number
                   << ": non-zero radial distortion is not supported (images must be undistorted)");
  Eigen::Matrix3d world_from_cam;
  for (int r = 0; r < 3; ++r) {
    const std::vector<double> values = row(4 + r, 3);
    for (int c = 0; c < 3; ++c) world_from_cam(r, c) = values[c];
  }
  CheckRotation(path, lines[4].number, world_from_cam);
  const std::vector<double> center = row(7, 3);
  const std::vector<double> size = row(8, 2);
  COMIC_CHECK(size[0] >= 1 && size[1] >= 1 && size[0] <= 1e6 && size[1] <= 1e6, kInvalidData,
              path << ":" << lines[8].number << ": bad image size");
  camera.cam_from_world_rotation = world_from_cam.transpose();
  camera.cam_from_world_translation =
      -(world_from_cam.transpose() * Eigen::Vector3d(center[0], center[1], center[2]));
  camera.has_intrinsics = true;
  camera.width = static_cast<int>(size[0]);
  camera.height = static_cast<int>(size[1]);
  std::string name = FileName(path);
  name = name.substr(0, name.size() - std::string(".camera").size());
  camera.image_name = name;
  return camera;
}

GroundTruthCameras ReadStrechaCameraFolder(const std::string& folder) {
  GroundTruthCameras result;
  result.format = GroundTruthFormat::kStrecha;
  for (const std::string& name : ListFiles(folder)) {
    if (!EndsWith(name, ".camera")) continue;
    GroundTruthCamera camera = ReadStrechaCameraFile(JoinPaths(folder, name));
    camera.index = static_cast<int>(result.cameras.size());
    result.cameras.push_back(camera);
  }
  COMIC_CHECK(!result.cameras.empty(), kInvalidData, folder << ": holds no *.camera files");
  return result;
}

GroundTruthCameras ReadKittiGroundTruth(const std::string& poses_path,
                                        const std::string& calib_path) {
  GroundTruthCameras result;
  result.format = GroundTruthFormat::kKitti;
  Eigen::Matrix3d k = Eigen::Matrix3d::Identity();
  const bool has_intrinsics = !calib_path.empty();
  if (has_intrinsics) {
    const cv::Matx33d k_cv = ReadKittiIntrinsics(calib_path, 0);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) k(r, c) = k_cv(r, c);
    }
  }
  const std::vector<cv::Matx34d> poses = ReadKittiPoses(poses_path);
  for (size_t i = 0; i < poses.size(); ++i) {
    Eigen::Matrix3d world_from_cam;
    Eigen::Vector3d center;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) world_from_cam(r, c) = poses[i](r, c);
      center(r) = poses[i](r, 3);
    }
    GroundTruthCamera camera;
    camera.index = static_cast<int>(i);
    // Re-orthonormalise: the file's rotations are orthonormal only to ~1e-7.
    const Eigen::Matrix3d rotation =
        Eigen::Quaterniond(world_from_cam).normalized().toRotationMatrix().transpose();
    camera.cam_from_world_rotation = rotation;
    camera.cam_from_world_translation = -(rotation * center);
    camera.has_intrinsics = has_intrinsics;
    camera.K = k;
    result.cameras.push_back(camera);
  }
  return result;
}

GroundTruthCameras ReadColmapGroundTruth(const std::string& path) {
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such file or folder");
  const std::string folder = IsDirectory(path) ? path : ParentPath(path);
  const char* kind = ColmapModelKind(folder);
  COMIC_CHECK(kind != nullptr, kInvalidData,
              folder << ": not a COLMAP model (needs cameras.bin and images.bin, or cameras.txt "
                        "and images.txt)");
  const ColmapTextModel model =
      std::string(kind) == "bin" ? ReadColmapBinaryModel(folder) : ReadColmapTextModel(folder);
  std::map<uint32_t, const ColmapCamera*> cameras;
  for (const ColmapCamera& camera : model.cameras) cameras[camera.camera_id] = &camera;
  // Images by id: the order COLMAP lists them in.
  std::vector<const ColmapImage*> images;
  for (const ColmapImage& image : model.images) images.push_back(&image);
  std::sort(images.begin(), images.end(),
            [](const ColmapImage* a, const ColmapImage* b) { return a->image_id < b->image_id; });
  GroundTruthCameras result;
  result.format = GroundTruthFormat::kColmap;
  for (const ColmapImage* image : images) {
    GroundTruthCamera camera;
    camera.image_name = image->name;
    camera.index = static_cast<int>(result.cameras.size());
    camera.cam_from_world_rotation = image->cam_from_world_rotation.normalized().toRotationMatrix();
    camera.cam_from_world_translation = image->cam_from_world_translation;
    const auto found = cameras.find(image->camera_id);
    if (found != cameras.end() && UndistortedColmapK(*found->second, &camera.K)) {
      camera.has_intrinsics = true;
      camera.width = found->second->width;
      camera.height = found->second->height;
    }
    result.cameras.push_back(camera);
  }
  COMIC_CHECK(!result.cameras.empty(), kInvalidData, folder << ": the COLMAP model has no images");
  return result;
}

GroundTruthCameras ReadGroundTruthCameras(const std::string& path, GroundTruthFormat format) {
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such file or folder");
  if (format == GroundTruthFormat::kAuto) format = DetectGroundTruthFormat(path);
  switch (format) {
    case GroundTruthFormat::kKitti: {
      const std::string calib = JoinPaths(ParentPath(path), "calib.txt");
      return ReadKittiGroundTruth(path, IsRegularFile(calib) ? calib : "");
    }
    case GroundTruthFormat::kMiddlebury:
      return ReadMiddleburyParFile(path);
    case GroundTruthFormat::kStrecha: {
      if (IsDirectory(path)) return ReadStrechaCameraFolder(path);
      GroundTruthCameras result;
      result.format = GroundTruthFormat::kStrecha;
      result.cameras.push_back(ReadStrechaCameraFile(path));
      result.cameras.back().index = 0;
      return result;
    }
    case GroundTruthFormat::kColmap:
      return ReadColmapGroundTruth(path);
    case GroundTruthFormat::kNerf:
      return ReadNerfTransforms(path);
    case GroundTruthFormat::kTum:
      return ReadTumTrajectory(path);
    case GroundTruthFormat::kEuroc:
      return ReadEurocGroundTruth(path);
    case GroundTruthFormat::kAuto:
      break;
  }
  throw Error(ErrorKind::kInvalidArgument, "ground-truth format not resolved");
}

Eigen::Matrix3d ReadIntrinsicsFile(const std::string& path) {
  std::vector<double> values;
  int first_line = 1;
  const std::vector<TextLine> lines = NonBlankLines(path, true);
  if (!lines.empty()) first_line = lines[0].number;
  for (const TextLine& line : lines) {
    for (const std::string& field : line.fields) values.push_back(Number(path, line.number, field));
  }
  Eigen::Matrix3d k = Eigen::Matrix3d::Identity();
  if (values.size() == 4) {
    k(0, 0) = values[0];
    k(1, 1) = values[1];
    k(0, 2) = values[2];
    k(1, 2) = values[3];
  } else if (values.size() == 9) {
    for (int i = 0; i < 9; ++i) k(i / 3, i % 3) = values[i];
  } else if (values.size() >= 12) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) k(r, c) = values[4 * r + c];
    }
  } else {
    throw Error(ErrorKind::kInvalidData,
                path +
                    ": expected intrinsics as 4 numbers (fx fy cx cy), 9 (K) or 12 (a 3x4 "
                    "projection matrix), got " +
                    std::to_string(values.size()));
  }
  CheckIntrinsics(path, first_line, k);
  return k;
}

}  // namespace comic::io
