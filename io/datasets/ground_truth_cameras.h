// Ground-truth cameras of the evaluation data, read from each data set's own format into one plain
// form (pose cam_from_world, optional intrinsics, the image each camera belongs to), so the SfM
// can be measured against any of them with the same code:
//
//   kKitti       KITTI odometry poses.txt: line i = 3x4 camera-to-world [R | t] of frame i; the
//                intrinsics come from P0 of calib.txt in the same folder when it is there
//                (io/datasets/kitti_odometry.h reads both). Cameras are matched to frames by index.
//   kMiddlebury  Middlebury multi-view *_par.txt: a count, then per line
//                "name k11..k33 r11..r33 t1 t2 t3" with P = K [R | t] (R, t world-to-camera).
//   kStrecha     Strecha et al. *.camera files (a folder of them, or one file): K (3 lines),
//                radial distortion (1 line), R camera-to-world (3 lines), the centre C (1 line),
//                "width height"; P = K [Rᵀ | −Rᵀ C]. "NNNN.jpg.camera" belongs to image "NNNN.jpg".
//   kColmap      a COLMAP model, binary (cameras.bin, images.bin, points3D.bin) or text: its
//                folder or one of its files. Poses by image name; intrinsics from the cameras
//                without distortion (pinhole models, or zero distortion parameters), in OpenCV's
//                pixel convention (−0.5 on the principal point); a distorted camera gives poses
//                only (--intrinsics reads its cameras.txt).
//   kNerf        a NeRF-style transforms.json (io/datasets/nerf_transforms.h: Blender camera axes
//                turned into OpenCV's).
//   kTum         a TUM RGB-D trajectory, "timestamp tx ty tz qx qy qz qw" per line (what evo and
//                comic_sfm's trajectory_tum.txt hold), and
//   kEuroc       EuRoC MAV's groundtruth/data.csv (io/datasets/timestamped_trajectory.h): poses by
//                time stamp, matched to frames named by theirs, else by index as KITTI's.
//
// Pixel convention of all intrinsics here: OpenCV's (top-left pixel centre at (0, 0)), which is
// what these data sets' calibrations use.
//
//   const GroundTruthCameras truth = ReadGroundTruthCameras("strecha/gt_dense_cameras");
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace comic::io {

enum class GroundTruthFormat { kAuto, kKitti, kMiddlebury, kStrecha, kColmap, kNerf, kTum, kEuroc };

// "auto", "kitti", "middlebury", "strecha", "colmap", "nerf", "tum", "euroc"; Parse throws
// comic::Error(kInvalidArgument) listing the valid names.
const char* GroundTruthFormatName(GroundTruthFormat format);
GroundTruthFormat ParseGroundTruthFormat(const std::string& name);

// The length unit of a format's camera positions: "m" for KITTI (the vehicle's odometry), Strecha
// (surveyed metres), TUM and EuRoC (motion capture, laser tracker); "" where the format does not
// say (Middlebury's multi-view sets).
const char* GroundTruthLengthUnit(GroundTruthFormat format);

struct GroundTruthCamera {
  // The image this camera belongs to ("templeSR0001.png", "0000.jpg"); empty for formats that
  // identify frames by index (KITTI).
  std::string image_name;
  // Position in the file (KITTI: the source frame index).
  int index = -1;
  // The pose's time stamp in the file's unit (TUM: seconds, EuRoC: nanoseconds); NaN for formats
  // without time stamps.
  double timestamp = std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix3d cam_from_world_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d cam_from_world_translation = Eigen::Vector3d::Zero();
  // Intrinsics K when the file gives them (OpenCV pixel convention).
  bool has_intrinsics = false;
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  // Image size the intrinsics belong to, when the file states it (Strecha, COLMAP); 0 otherwise.
  int width = 0;
  int height = 0;
  // Without intrinsics, a horizontal field of view (radians) that gives them for any image size:
  // f = w / 2 / tan(fov / 2), principal point at the centre (NeRF's camera_angle_x); 0 if none.
  double horizontal_fov_rad = 0.0;
};

struct GroundTruthCameras {
  GroundTruthFormat format = GroundTruthFormat::kAuto;  // the format actually read
  std::vector<GroundTruthCamera> cameras;               // in file order
  // Time-stamped formats: how far apart a frame's and a pose's time stamps may be and still match
  // (the file's unit); 0 otherwise.
  double timestamp_tolerance = 0.0;
};

// Detects the format of `path`: a folder holding *.camera files or a *.camera file -> kStrecha;
// a folder holding cameras.bin and images.bin, or cameras.txt and images.txt, or one of those
// files -> kColmap; a *.json file -> kNerf; EuRoC's "#timestamp, p_RS_R_x ..." header or a first
// line of 8 or more comma-separated numbers -> kEuroc; a first line (after '#' comments) of 8
// numbers -> kTum; a file whose first non-blank line is a single count
// -> kMiddlebury; a file of lines of 12 numbers -> kKitti. Throws comic::Error: kNotFound for a
// missing path, kInvalidData when none fits.
GroundTruthFormat DetectGroundTruthFormat(const std::string& path);

// Reads ground-truth cameras in `format` (kAuto: detected). Throws comic::Error: kNotFound for a
// missing path, kInvalidData naming the file and line for malformed content (wrong number of
// fields, a rotation that is not one, non-positive focal lengths, a count that disagrees with the
// lines).
GroundTruthCameras ReadGroundTruthCameras(const std::string& path,
                                          GroundTruthFormat format = GroundTruthFormat::kAuto);

GroundTruthCameras ReadMiddleburyParFile(const std::string& path);
GroundTruthCamera ReadStrechaCameraFile(const std::string& path);
// Every *.camera file of `folder`, naturally sorted.
GroundTruthCameras ReadStrechaCameraFolder(const std::string& folder);
// A COLMAP model (binary preferred when both are there) in `path`, a folder or one of its files.
GroundTruthCameras ReadColmapGroundTruth(const std::string& path);
// KITTI poses.txt, with the intrinsics of P0 from `calib_path` if not empty.
GroundTruthCameras ReadKittiGroundTruth(const std::string& poses_path,
                                        const std::string& calib_path = "");

// Reads intrinsics from a text file of numbers (whitespace separated, an optional "P0:"-style
// label per line): 4 numbers "fx fy cx cy", 9 numbers K row-major, or 12 or more numbers whose
// first 12 are a 3x4 projection matrix K [I | t] (e.g. KITTI's calib.txt, first line). Returns K
// (OpenCV pixel convention). Throws comic::Error: kNotFound, or kInvalidData naming the file for
// another count, non-positive focal lengths or a K that is not upper triangular with K(2,2) = 1.
Eigen::Matrix3d ReadIntrinsicsFile(const std::string& path);

}  // namespace comic::io
