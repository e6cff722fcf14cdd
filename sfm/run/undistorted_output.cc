#include "sfm/run/undistorted_output.h"

#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "io/colmap/colmap_binary_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"
#include "sfm/colmap/colmap_model_conversion.h"

namespace comic::sfm {

namespace {

const char* const kStereoFolders[] = {"depth_maps", "normal_maps", "consistency_graphs"};

// The pixel maps taking the distorted image to the pinhole one of the same K and size.
struct UndistortionMaps {
  cv::Mat x;
  cv::Mat y;
};

UndistortionMaps MapsOf(const Camera& camera) {
  const cv::Matx33d k(camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0);
  const cv::Vec4d distortion(camera.k1, camera.k2, camera.p1, camera.p2);
  UndistortionMaps maps;
  cv::initUndistortRectifyMap(k, distortion, cv::noArray(), k,
                              cv::Size(camera.width, camera.height), CV_32FC1, maps.x, maps.y);
  return maps;
}

std::string StereoConfig(const Reconstruction& reconstruction, bool patch_match) {
  std::string text;
  for (image_t id : reconstruction.RegisteredImageIds()) {
    text += reconstruction.image(id).name + "\n";
    if (patch_match) text += "__auto__, 20\n";
  }
  return text;
}

}  // namespace

Reconstruction UndistortedReconstruction(const Reconstruction& reconstruction) {
  Reconstruction undistorted = reconstruction;
  for (const auto& [camera_id, camera] : reconstruction.cameras()) {
    Camera& pinhole = undistorted.camera(camera_id);
    pinhole = Camera::FromParams(CameraModelId::kPinhole, camera.width, camera.height,
                                 {camera.fx, camera.fy, camera.cx, camera.cy});
  }
  for (const auto& [image_id, image] : reconstruction.images()) {
    const Camera& camera = reconstruction.camera(image.camera_id);
    if (!camera.HasDistortion()) continue;
    for (Point2D& point : undistorted.image(image_id).points2D) {
      point.xy = camera.UndistortPixel(point.xy);
    }
  }
  undistorted.UpdatePoint3DErrors();
  return undistorted;
}

std::vector<std::string> UndistortedWorkspaceFiles(const Reconstruction& reconstruction) {
  std::vector<std::string> files;
  for (image_t id : reconstruction.RegisteredImageIds()) {
    files.push_back("images/" + reconstruction.image(id).name);
  }
  for (const char* name : {"cameras.bin", "images.bin", "points3D.bin"}) {
    files.push_back(std::string("sparse/") + name);
  }
  files.insert(files.end(), {"stereo/patch-match.cfg", "stereo/fusion.cfg"});
  return files;
}

void WriteUndistortedWorkspace(const Reconstruction& reconstruction,
                               const ModelImageReader& read_image, const std::string& folder) {
  const std::string images = io::JoinPaths(folder, "images");
  io::EnsureWritableDirectory(images);
  std::map<camera_t, UndistortionMaps> maps;
  for (image_t id : reconstruction.RegisteredImageIds()) {
    const Image& image = reconstruction.image(id);
    const Camera& camera = reconstruction.camera(image.camera_id);
    const cv::Mat distorted = read_image(image);
    COMIC_CHECK(distorted.cols == camera.width && distorted.rows == camera.height, kInvalidData,
                "--undistort: " << image.name << " is " << distorted.cols << "x" << distorted.rows
                                << ", its camera " << camera.width << "x" << camera.height);
    cv::Mat undistorted = distorted;
    if (camera.HasDistortion()) {
      auto it = maps.find(image.camera_id);
      if (it == maps.end()) it = maps.emplace(image.camera_id, MapsOf(camera)).first;
      cv::remap(distorted, undistorted, it->second.x, it->second.y, cv::INTER_LINEAR,
                cv::BORDER_CONSTANT);
    }
    const std::string path = io::JoinPaths(images, image.name);
    io::EnsureWritableDirectory(io::ParentPath(path));
    io::WriteImageAtomically(path, undistorted);
  }
  io::WriteColmapBinaryModel(ToColmapTextModel(UndistortedReconstruction(reconstruction)),
                             io::JoinPaths(folder, "sparse"));
  const std::string stereo = io::JoinPaths(folder, "stereo");
  for (const char* name : kStereoFolders) io::EnsureWritableDirectory(io::JoinPaths(stereo, name));
  io::WriteFileAtomically(io::JoinPaths(stereo, "patch-match.cfg"),
                          StereoConfig(reconstruction, true));
  io::WriteFileAtomically(io::JoinPaths(stereo, "fusion.cfg"), StereoConfig(reconstruction, false));
}

}  // namespace comic::sfm
