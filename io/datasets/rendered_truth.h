// The truth comic_render writes beside its frames (render/sequence_renderer.h), read back for the
// evaluations, which see it only through these files (io/ sits under render/ and sfm/ alike):
//   images/NNNNNN.png                  the frames
//   poses.txt, colmap/cameras.txt      the true cameras (KITTI poses; COLMAP's camera model)
//   depth/NNNNNN.png|pfm               z per pixel centre (io/image/depth_map.h)
//   boundaries/NNNNNN.png              occlusion-boundary band (255)
//   masks/NNNNNN.png                   foreground objects (255)
//
//   const RenderedTruth truth = OpenRenderedTruth("out/street");
//   cv::Mat depth = truth.Depth(3);  // CV_32F metres
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/datasets/camera_calibration_file.h"
#include "io/datasets/ground_truth_cameras.h"

namespace comic::io {

struct RenderedTruth {
  std::string folder;
  std::vector<std::string> frame_names;  // images/, naturally sorted
  CameraCalibration camera;              // colmap/cameras.txt (OpenCV pixel convention)
  GroundTruthCameras cameras;            // poses.txt: camera k for frame k
  std::string depth_extension;           // "png" or "pfm"
  // Half-width of the boundary band in boundaries/ (scene.json render_options.boundary_band_px;
  // 0 when scene.json does not say).
  double band_px = 0.0;
  // scene.json has "composite" (a NeRF set laid over a rendered background): masks/ is the
  // object, whose depth is not given.
  bool composite = false;

  size_t NumFrames() const { return frame_names.size(); }
  std::string ImagesFolder() const;
  // Per frame; throw comic::Error (kNotFound, kInvalidData) naming the file.
  // CV_32F metres, 0 = no surface, +inf beyond a PNG, NaN = unknown: a composite's object, also
  // from a 16-bit PNG (which stores it as 0, no surface, and would make it sky).
  cv::Mat Depth(size_t frame) const;
  std::string DepthPath(size_t frame) const;  // depth/NNNNNN.png|pfm
  cv::Mat Boundaries(size_t frame) const;     // CV_8UC1, 255 = occlusion-boundary band
  cv::Mat Foreground(size_t frame) const;     // CV_8UC1, 255 = foreground object

 private:
  cv::Mat ReadMask(const std::string& subfolder, size_t frame) const;
};

// Opens a folder written by comic_render. Throws comic::Error: kNotFound for a missing folder
// or part (images/, poses.txt, colmap/cameras.txt, depth/, boundaries/), kInvalidData when the
// parts disagree (a pose count other than the frame count, a camera of another size, a depth
// map missing or of another size than the camera's, read from its header).
RenderedTruth OpenRenderedTruth(const std::string& folder);

}  // namespace comic::io
