// A model as nerfstudio's `transforms.json` (what `ns-process-data` writes from a COLMAP model, and
// what nerfstudio's, instant-ngp's and the Gaussian-splatting trainers read), so a run goes on to
// NeRF or splatting training without COLMAP:
//   {"camera_model": "OPENCV", "fl_x", "fl_y", "cx", "cy", "w", "h", "k1", "k2", "p1", "p2",
//    "frames": [{"file_path": "../frames/0001.png", "transform_matrix": [[4 rows of 4]],
//                "colmap_im_id": 1}, ...],
//    "applied_transform": [[3 rows of 4]]}
// Intrinsics as COLMAP's cameras.bin holds them (pixel-corner principal point: ours + 0.5), every
// model as OPENCV with the coefficients it lacks 0 (nerfstudio's parse_colmap_camera_params does
// the same); with several cameras each frame carries its own instead of the top level.
// transform_matrix is nerfstudio's camera-to-world (colmap_utils.colmap_to_json, by default):
//   c2w = [R t; 0 1]^-1 from COLMAP's cam_from_world; its y and z columns negated (OpenCV's camera
//   axes x right, y down, z forwards become OpenGL's x right, y up, z backwards); then the world
//   turned by applied_transform A = rows (x, z, -y) of the identity (rows 1 and 2 swapped, the new
//   row 2 negated: nerfstudio's viewer wants z up where COLMAP's worlds have y down), c2w = A c2w.
// Registered images only, in image-id order.
//
//   const nlohmann::json json = NerfstudioTransforms(
//       reconstruction, 3072, 2048, [](const Image& image) { return "images/" + image.name; });
//   io::WriteFileAtomically("out/transforms.json", io::JsonText(json, 2));
#pragma once

#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "sfm/reconstruction.h"

namespace comic::sfm {

// The world turn nerfstudio applies (applied_transform, the 3x3 part; its translation is 0).
Eigen::Matrix3d NerfstudioAppliedTransform();

// nerfstudio's transform_matrix of a COLMAP cam_from_world pose, as above.
Eigen::Matrix4d NerfstudioTransformMatrix(const Rigid3d& cam_from_world);

// The transforms.json of `reconstruction`'s registered images, its cameras resized to images of
// width x height (the input's pixels, as the written models; 0: as they are). `file_path` gives
// each image's path as the file should hold it (relative to the file's folder). Throws
// comic::Error(kInvalidArgument) for a reconstruction with no registered image.
nlohmann::json NerfstudioTransforms(const Reconstruction& reconstruction, int width, int height,
                                    const std::function<std::string(const Image&)>& file_path);

}  // namespace comic::sfm
