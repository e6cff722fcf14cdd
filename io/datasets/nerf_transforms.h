// NeRF-style `transforms.json` (the NeRF synthetic scenes, instant-ngp and nerfstudio) as
// ground-truth cameras:
//   {"camera_angle_x": 0.69,                      horizontal field of view (radians), or
//    "fl_x": 1111, "fl_y": 1111, "cx": 400, "cy": 400, "w": 800, "h": 800,   (optional)
//    "frames": [{"file_path": "./train/r_0", "transform_matrix": [[...4 rows of 4...]]}, ...]}
// Each transform_matrix is camera-to-world in Blender's (OpenGL's) camera axes: x right, y up,
// z backwards (the camera looks along −z). OpenCV's camera axes are x right, y down, z forwards,
// so world_from_cam(OpenCV) = world_from_cam(Blender) · diag(1, −1, −1): the y and z columns of
// the rotation change sign, the centre stays; then cam_from_world = (R^T, −R^T C).
// Intrinsics: fl_x/fl_y/cx/cy (pixel-corner convention, as COLMAP's, from which these files are
// usually made: cx − 0.5 in OpenCV's), or camera_angle_x alone: f = w / 2 / tan(angle / 2) with
// the principal point at the image centre ((w − 1) / 2 in OpenCV's convention; Blender renders
// the principal point at the sensor's centre). Without w and h in the file the size is the
// frames' (horizontal_fov_rad, resolved by sfm/evaluation/ground_truth.h). A file with non-zero
// distortion (k1, k2, p1, p2) gives poses only.
// Image names are the file_path's last component ("r_0"; matched to frame "r_0.png" by stem).
//
//   const GroundTruthCameras truth = ReadNerfTransforms("lego/transforms_train.json");
#pragma once

#include <Eigen/Core>
#include <string>

#include "io/datasets/ground_truth_cameras.h"

namespace comic::io {

// Reads `path`. Throws comic::Error: kNotFound for a missing file, kInvalidData naming the file
// and the frame for malformed JSON, missing fields, a transform that is not rigid, or
// non-positive focal lengths or field of view.
GroundTruthCameras ReadNerfTransforms(const std::string& path);

// The pose of a Blender/OpenGL camera-to-world matrix (4x4, rigid) in OpenCV's convention, as
// above. Throws comic::Error(kInvalidData) if the upper-left 3x3 is not a rotation.
void BlenderCamToWorldToCamFromWorld(const Eigen::Matrix4d& blender_world_from_cam,
                                     Eigen::Matrix3d* cam_from_world_rotation,
                                     Eigen::Vector3d* cam_from_world_translation);

}  // namespace comic::io
