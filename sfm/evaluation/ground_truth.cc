#include "sfm/evaluation/ground_truth.h"

#include <cmath>
#include <map>

#include "io/core/error.h"

namespace comic::sfm {

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
  std::map<std::string, const io::GroundTruthCamera*> by_image_name;
  std::map<int, const io::GroundTruthCamera*> by_index;
  for (const io::GroundTruthCamera& camera : truth.cameras) {
    if (by_name) {
      by_image_name[camera.image_name] = &camera;
    } else {
      by_index[camera.index] = &camera;
    }
  }
  FrameGroundTruth result;
  result.cams_from_world.resize(frame_names.size());
  const io::GroundTruthCamera* first = nullptr;
  for (size_t i = 0; i < frame_names.size(); ++i) {
    const io::GroundTruthCamera* camera = nullptr;
    if (by_name) {
      const auto it = by_image_name.find(frame_names[i]);
      if (it != by_image_name.end()) camera = it->second;
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
                  << (by_name ? "by image name, e.g. '" + truth.cameras[0].image_name + "'"
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
