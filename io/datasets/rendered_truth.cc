#include "io/datasets/rendered_truth.h"

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/depth_map.h"
#include "io/image/image_header.h"
#include "io/image/image_io.h"

namespace comic::io {
namespace {

std::string Stem(const std::string& name) {
  const size_t dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

// A map of another size than the camera's cannot be laid over the frames: refused naming it.
void CheckMapSize(const std::string& path, int64_t width, int64_t height,
                  const CameraCalibration& camera) {
  COMIC_CHECK(width == camera.width && height == camera.height, kInvalidData,
              path << ": " << width << "x" << height << ", but the frames are " << camera.width
                   << "x" << camera.height);
}

}  // namespace

std::string RenderedTruth::ImagesFolder() const { return JoinPaths(folder, "images"); }

std::string RenderedTruth::DepthPath(size_t frame) const {
  return JoinPaths(folder, "depth/" + Stem(frame_names[frame]) + "." + depth_extension);
}

cv::Mat RenderedTruth::Depth(size_t frame) const {
  COMIC_CHECK(frame < frame_names.size(), kInvalidArgument, "frame " << frame << " out of range");
  const std::string path = DepthPath(frame);
  cv::Mat depth = ReadDepthMap(path);
  CheckMapSize(path, depth.cols, depth.rows, camera);
  if (composite) depth.setTo(std::numeric_limits<float>::quiet_NaN(), Foreground(frame));
  return depth;
}

cv::Mat RenderedTruth::ReadMask(const std::string& subfolder, size_t frame) const {
  COMIC_CHECK(frame < frame_names.size(), kInvalidArgument, "frame " << frame << " out of range");
  const std::string path = JoinPaths(folder, subfolder + "/" + Stem(frame_names[frame]) + ".png");
  const cv::Mat mask = ToGray8(ReadImageUnchanged(path));
  CheckMapSize(path, mask.cols, mask.rows, camera);
  return mask;
}

cv::Mat RenderedTruth::Boundaries(size_t frame) const { return ReadMask("boundaries", frame); }

cv::Mat RenderedTruth::Foreground(size_t frame) const { return ReadMask("masks", frame); }

RenderedTruth OpenRenderedTruth(const std::string& folder) {
  COMIC_CHECK(IsDirectory(folder), kNotFound, folder << ": no such folder (a comic_render output)");
  RenderedTruth truth;
  truth.folder = folder;
  for (const char* part : {"images", "depth", "boundaries"}) {
    COMIC_CHECK(IsDirectory(JoinPaths(folder, part)), kNotFound,
                folder << ": no " << part << "/ (render without --frames-only)");
  }
  for (const std::string& name : ListFiles(JoinPaths(folder, "images"))) {
    if (IsImageExtension(FileExtension(name))) truth.frame_names.push_back(name);
  }
  COMIC_CHECK(!truth.frame_names.empty(), kNotFound, folder << "/images: no frames");
  truth.camera = ReadCameraCalibrationFile(JoinPaths(folder, "colmap/cameras.txt"));
  truth.cameras = ReadKittiGroundTruth(JoinPaths(folder, "poses.txt"));
  COMIC_CHECK(truth.cameras.cameras.size() == truth.frame_names.size(), kInvalidData,
              folder << "/poses.txt: " << truth.cameras.cameras.size() << " poses for "
                     << truth.frame_names.size() << " frames");
  const std::string first = Stem(truth.frame_names.front());
  for (const char* extension : {"pfm", "png"}) {
    if (PathExists(JoinPaths(folder, "depth/" + first + "." + extension))) {
      truth.depth_extension = extension;
    }
  }
  COMIC_CHECK(!truth.depth_extension.empty(), kNotFound,
              folder << "/depth: no " << first << ".png or .pfm");
  // Every depth map's size from its header, before any tracking: a wrong one found while judging
  // the tracks would cost the whole run.
  for (size_t frame = 0; frame < truth.frame_names.size(); ++frame) {
    const std::string path = truth.DepthPath(frame);
    COMIC_CHECK(PathExists(path), kNotFound, path << ": no such depth map");
    const ImageHeader header = RequireImageHeader(path);
    CheckMapSize(path, header.width, header.height, truth.camera);
  }
  const std::string scene = JoinPaths(folder, "scene.json");
  if (PathExists(scene)) {
    try {
      const nlohmann::json json = nlohmann::json::parse(ReadFileToString(scene));
      truth.band_px = json.at("render_options").at("boundary_band_px").get<double>();
      truth.composite = json.contains("composite");
    } catch (const nlohmann::json::exception& e) {
      throw Error(ErrorKind::kInvalidData,
                  scene + ": no render_options.boundary_band_px (" + e.what() + ")");
    }
  }
  return truth;
}

}  // namespace comic::io
