// --undistort: the largest model with its images undistorted, in the layout COLMAP's
// image_undistorter writes, so that `colmap patch_match_stereo --workspace_path dense` and
// `stereo_fusion` (and the MVS and splatting tools that want pinhole images) run on it:
//   dense/images/<name>                   each registered image, undistorted (cv::remap of the
//                                         model's distortion; the same size and focal lengths)
//   dense/sparse/{cameras,images,points3D}.bin   the model with PINHOLE cameras (fx fy cx cy of
//                                         the distorted ones) and undistorted 2-D points
//   dense/stereo/patch-match.cfg          per image its name and "__auto__, 20" (COLMAP's
//                                         default: the 20 best source images by shared points)
//   dense/stereo/fusion.cfg               the image names, one per line
//   dense/stereo/{depth_maps,normal_maps,consistency_graphs}/   empty, for patch_match_stereo
// Unlike image_undistorter the image keeps its size and K rather than being cropped or rescaled:
// under pincushion distortion (k > 0) the corners the frame did not see are black, under barrel
// distortion (k < 0) the frame's rim falls outside.
//
//   WriteUndistortedWorkspace(reconstruction, read_image, "out/dense");
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sfm/reconstruction.h"

namespace comic::sfm {

// The image a model's image was made from, in the model's pixels (its camera's size).
using ModelImageReader = std::function<cv::Mat(const Image& image)>;

// `reconstruction`'s cameras as PINHOLE (the pinhole part of each) and its 2-D points undistorted
// (Camera::UndistortPixel); poses and points unchanged.
Reconstruction UndistortedReconstruction(const Reconstruction& reconstruction);

// The files WriteUndistortedWorkspace writes for `reconstruction`, relative to its folder.
std::vector<std::string> UndistortedWorkspaceFiles(const Reconstruction& reconstruction);

// Writes the workspace above into `folder` (created), every file atomically. Throws
// comic::Error: kInvalidData when an image read is empty or not of its camera's size, kIo when a
// file cannot be written.
void WriteUndistortedWorkspace(const Reconstruction& reconstruction,
                               const ModelImageReader& read_image, const std::string& folder);

}  // namespace comic::sfm
