// COLMAP's text model format (cameras.txt, images.txt, points3D.txt), read and written as plain
// structs in COLMAP's own conventions, so that COLMAP, its viewers and other tools open what we
// write, and we can read (and evaluate) what COLMAP writes.
//
// Conventions, as COLMAP's: image coordinates put the centre of the top-left pixel at (0.5, 0.5)
// (OpenCV puts it at (0, 0): add 0.5 to go from OpenCV to COLMAP, for keypoints and the principal
// point alike); the pose of an image is cam_from_world, x_cam = R · x_world + t, with the rotation
// written as the quaternion QW QX QY QZ; ids start at 1; POINT3D_ID -1 marks an unmatched 2-D
// point.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace comic::io {

struct ColmapCamera {
  uint32_t camera_id = 0;
  std::string model;  // e.g. "PINHOLE" (fx fy cx cy), "SIMPLE_RADIAL" (f cx cy k)
  int width = 0;
  int height = 0;
  std::vector<double> params;  // in the model's parameter order
};

struct ColmapPoint2D {
  double x = 0.0;  // COLMAP pixel convention (+0.5 from OpenCV)
  double y = 0.0;
  int64_t point3D_id = -1;  // -1: not part of a 3-D point
};

struct ColmapImage {
  uint32_t image_id = 0;
  Eigen::Quaterniond cam_from_world_rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d cam_from_world_translation = Eigen::Vector3d::Zero();
  uint32_t camera_id = 0;
  std::string name;  // path relative to the image folder; no whitespace
  std::vector<ColmapPoint2D> points2D;
};

struct ColmapTrackElement {
  uint32_t image_id = 0;
  uint32_t point2D_idx = 0;  // index into that image's points2D
};

struct ColmapPoint3D {
  uint64_t point3D_id = 0;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  std::array<uint8_t, 3> rgb = {0, 0, 0};
  double error = 0.0;  // mean reprojection error in pixels
  std::vector<ColmapTrackElement> track;
};

struct ColmapTextModel {
  std::vector<ColmapCamera> cameras;
  std::vector<ColmapImage> images;
  std::vector<ColmapPoint3D> points3D;

  // Throws comic::Error(kInvalidData) if ids repeat, an image names a missing camera, a track
  // element names a missing image or 2-D point, or an image name holds whitespace.
  void Check() const;
};

// Throws comic::Error(kInvalidData), naming `what` (the frames' folder) and the name, if `name`
// cannot name an image of a COLMAP model: empty, or holding whitespace, which COLMAP's
// images.txt reader splits at. Run on the frame names before any work (issue 29: a frame named
// 'img 000000.png' failed only after the whole reconstruction).
void CheckColmapImageName(const std::string& name, const std::string& what);

// Reads cameras.txt, images.txt and points3D.txt from `folder`. Throws comic::Error naming the
// file and line: kNotFound for a missing file, kInvalidData for a malformed line.
ColmapTextModel ReadColmapTextModel(const std::string& folder);

// Writes the three files into `folder` (created if needed), with 17 significant digits so that
// reading them back gives the same numbers. Checks the model first. Streamed to disk, and all
// three written before any replaces an old file (io::WriteFilesAtomically): an error while
// writing leaves the old model whole.
void WriteColmapTextModel(const ColmapTextModel& model, const std::string& folder);

// The three files' text, streamed (what WriteColmapTextModel writes).
void WriteColmapCamerasText(const ColmapTextModel& model, std::ostream& out);
void WriteColmapImagesText(const ColmapTextModel& model, std::ostream& out);
void WriteColmapPoints3DText(const ColmapTextModel& model, std::ostream& out);

// The same as strings.
std::string ColmapCamerasText(const ColmapTextModel& model);
std::string ColmapImagesText(const ColmapTextModel& model);
std::string ColmapPoints3DText(const ColmapTextModel& model);

}  // namespace comic::io
