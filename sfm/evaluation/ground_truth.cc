#include "sfm/evaluation/ground_truth.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "io/core/error.h"
#include "io/datasets/number_field.h"

namespace comic::sfm {
namespace {

// A name's last path component, and that without its extension: a ground-truth camera names its
// image as the data set does ("images/0000.jpg" in a COLMAP model, "r_0" in a NeRF transforms
// file), the frames by file name.
std::string BaseName(const std::string& name) {
  const size_t slash = name.find_last_of("/\\");
  return slash == std::string::npos ? name : name.substr(slash + 1);
}
std::string Stem(const std::string& name) {
  const std::string base = BaseName(name);
  const size_t dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

// Time-stamped ground truth (TUM, EuRoC) and frames named by their time stamps (TUM's
// rgb/1305031102.175304.png, EuRoC's 1403636579763555584.png): per frame, the camera nearest in
// time within the file's tolerance, or null. Empty when a frame's name is not a number: then line
// i is frame i, as KITTI's.
std::vector<const io::GroundTruthCamera*> MatchByTimestamp(
    const io::GroundTruthCameras& truth, const std::vector<std::string>& frame_names) {
  if (truth.timestamp_tolerance <= 0.0) return {};
  std::vector<double> frame_times(frame_names.size());
  for (size_t i = 0; i < frame_names.size(); ++i) {
    if (!io::ParseNumberField(Stem(frame_names[i]), &frame_times[i])) return {};
  }
  std::vector<const io::GroundTruthCamera*> by_time;
  for (const io::GroundTruthCamera& camera : truth.cameras) by_time.push_back(&camera);
  std::sort(by_time.begin(), by_time.end(),
            [](const auto* a, const auto* b) { return a->timestamp < b->timestamp; });
  std::vector<const io::GroundTruthCamera*> matched(frame_names.size(), nullptr);
  for (size_t i = 0; i < frame_names.size(); ++i) {
    const auto after =
        std::lower_bound(by_time.begin(), by_time.end(), frame_times[i],
                         [](const auto* camera, double time) { return camera->timestamp < time; });
    double best = truth.timestamp_tolerance;
    for (auto it : {after, after == by_time.begin() ? after : after - 1}) {
      if (it == by_time.end()) continue;
      const double difference = std::abs((*it)->timestamp - frame_times[i]);
      if (difference <= best) {
        best = difference;
        matched[i] = *it;
      }
    }
  }
  return matched;
}

}  // namespace

Camera CameraFromK(const Eigen::Matrix3d& K, int width, int height) {
  COMIC_CHECK(std::abs(K(0, 1)) < 1e-9 * std::abs(K(0, 0)), kInvalidArgument,
              "intrinsics with skew are not supported (K(0,1) = " << K(0, 1) << ")");
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = K(0, 0);
  camera.fy = K(1, 1);
  camera.cx = K(0, 2);
  camera.cy = K(1, 2);
  camera.Check();
  return camera;
}

FrameGroundTruth MatchGroundTruthToFrames(const io::GroundTruthCameras& truth,
                                          const std::vector<std::string>& frame_names,
                                          const std::vector<int>& source_indices,
                                          const cv::Size& source_size, const cv::Size& frame_size) {
  COMIC_CHECK(frame_names.size() == source_indices.size(), kInvalidArgument,
              "ground truth: " << frame_names.size() << " frame names for " << source_indices.size()
                               << " source indices");
  COMIC_CHECK(source_size.width > 0 && source_size.height > 0 && frame_size.height > 0,
              kInvalidArgument, "ground truth: empty frame size");
  const bool by_name = !truth.cameras.empty() && !truth.cameras[0].image_name.empty();
  // By the full name first, then by the last path component, then by the stem (a name without
  // extension); a key two cameras share at a level is not used at that level.
  std::map<std::string, const io::GroundTruthCamera*> by_image_name, by_base_name, by_stem;
  std::map<int, const io::GroundTruthCamera*> by_index;
  const auto add_unique = [](std::map<std::string, const io::GroundTruthCamera*>* map,
                             const std::string& key, const io::GroundTruthCamera* camera) {
    const auto [it, inserted] = map->emplace(key, camera);
    if (!inserted) it->second = nullptr;
  };
  for (const io::GroundTruthCamera& camera : truth.cameras) {
    if (by_name) {
      by_image_name[camera.image_name] = &camera;
      add_unique(&by_base_name, BaseName(camera.image_name), &camera);
      add_unique(&by_stem, Stem(camera.image_name), &camera);
    } else {
      by_index[camera.index] = &camera;
    }
  }
  const std::vector<const io::GroundTruthCamera*> by_timestamp =
      MatchByTimestamp(truth, frame_names);
  FrameGroundTruth result;
  result.cams_from_world.resize(frame_names.size());
  const io::GroundTruthCamera* first = nullptr;
  for (size_t i = 0; i < frame_names.size(); ++i) {
    const io::GroundTruthCamera* camera = nullptr;
    if (!by_timestamp.empty()) {
      camera = by_timestamp[i];
    } else if (by_name) {
      const auto it = by_image_name.find(frame_names[i]);
      if (it != by_image_name.end()) {
        camera = it->second;
      } else if (const auto base = by_base_name.find(BaseName(frame_names[i]));
                 base != by_base_name.end()) {
        camera = base->second;
      } else if (const auto stem = by_stem.find(Stem(frame_names[i])); stem != by_stem.end()) {
        camera = stem->second;
      }
    } else {
      const auto it = by_index.find(source_indices[i]);
      if (it != by_index.end()) camera = it->second;
    }
    if (camera == nullptr) continue;
    result.cams_from_world[i] =
        Rigid3d(camera->cam_from_world_rotation, camera->cam_from_world_translation);
    ++result.num_matched;
    if (first == nullptr) first = camera;
  }
  COMIC_CHECK(result.num_matched > 0, kInvalidData,
              "ground truth: no camera matches a frame ("
                  << (!by_timestamp.empty() ? std::string("by time stamp")
                      : by_name ? "by image name, e.g. '" + truth.cameras[0].image_name + "'"
                                : std::string("by frame index"))
                  << ")");
  if (first->has_intrinsics) {
    COMIC_CHECK((first->width == 0 && first->height == 0) ||
                    (first->width == source_size.width && first->height == source_size.height),
                kInvalidData,
                "ground truth: cameras are for " << first->width << "x" << first->height
                                                 << " images, the frames are " << source_size.width
                                                 << "x" << source_size.height);
    const Camera source_camera = CameraFromK(first->K, source_size.width, source_size.height);
    const double factor =
        static_cast<double>(frame_size.height) / static_cast<double>(source_size.height);
    Camera camera = factor == 1.0 ? source_camera : source_camera.Scaled(factor);
    camera.width = frame_size.width;
    camera.height = frame_size.height;
    result.camera = camera;
  } else if (first->horizontal_fov_rad > 0) {
    // A field of view only (NeRF's camera_angle_x): the intrinsics of the frames as used.
    const double f = 0.5 * frame_size.width / std::tan(0.5 * first->horizontal_fov_rad);
    Eigen::Matrix3d k;
    k << f, 0, (frame_size.width - 1) / 2.0, 0, f, (frame_size.height - 1) / 2.0, 0, 0, 1;
    result.camera = CameraFromK(k, frame_size.width, frame_size.height);
  }
  return result;
}

std::vector<std::optional<Rigid3d>> RegisteredPosesByName(
    const Reconstruction& reconstruction, const std::vector<std::string>& frame_names) {
  std::map<std::string, const Image*> by_name;
  for (const auto& [image_id, image] : reconstruction.images()) {
    if (image.registered) by_name[image.name] = &image;
  }
  std::vector<std::optional<Rigid3d>> poses(frame_names.size());
  for (size_t i = 0; i < frame_names.size(); ++i) {
    const auto it = by_name.find(frame_names[i]);
    if (it != by_name.end()) poses[i] = it->second->cam_from_world;
  }
  return poses;
}

void CheckGroundTruthCoverage(const FrameGroundTruth& truth,
                              const std::vector<std::string>& frame_names, const std::string& path,
                              bool allow_partial) {
  if (allow_partial) return;
  for (size_t i = 0; i < truth.cams_from_world.size() && i < frame_names.size(); ++i) {
    COMIC_CHECK(truth.cams_from_world[i].has_value(), kInvalidData,
                path << ": ground truth covers " << truth.num_matched << " of the "
                     << frame_names.size() << " frames (none for " << frame_names[i]
                     << "); --gt-partial evaluates on the frames it covers");
  }
}

}  // namespace comic::sfm
