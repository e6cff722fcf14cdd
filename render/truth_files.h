// The true cameras of a rendered sequence in the formats the project's apps read unchanged:
//   poses.txt          KITTI odometry: per frame the 3x4 camera-to-world [R | t], row-major
//                      (comic_sfm FRAMES --gt poses.txt; io/datasets/kitti_odometry.h)
//   calib.txt          KITTI: "P0: fx 0 cx 0 0 fy cy 0 0 0 1 0" (read beside poses.txt for the
//                      intrinsics; a distorted lens's coefficients are in colmap/cameras.txt)
//   colmap/            COLMAP text model of the true cameras (PINHOLE or OPENCV; no points), usable
//                      as --intrinsics colmap/cameras.txt and by COLMAP's tools
#pragma once

#include <string>
#include <vector>

#include "render/lens.h"
#include "render/pose.h"

namespace comic::render {

// Writes the three into `folder` (which must exist). `image_names[i]` is frame i's file name in
// the images folder. Throws comic::Error(kIo) when writing fails.
void WriteTrueCameras(const std::string& folder, const Lens& lens, const std::vector<Pose>& poses,
                      const std::vector<std::string>& image_names);

// One line of poses.txt (12 numbers, 12 significant digits).
std::string KittiPoseLine(const Pose& cam_from_world);

}  // namespace comic::render
