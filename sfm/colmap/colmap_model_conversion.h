// Conversion between a Reconstruction and COLMAP's text model (io/colmap/colmap_text_model.h). Our
// pixels follow OpenCV (top-left pixel centre at (0, 0)), COLMAP's put it at (0.5, 0.5): keypoints
// and principal points shift by +0.5 on the way out and −0.5 on the way back. Cameras are written
// as PINHOLE (fx fy cx cy); only registered images are written, as COLMAP does.
//
//   io::WriteColmapTextModel(ToColmapTextModel(reconstruction), "out/sparse");
//   Reconstruction colmap = FromColmapTextModel(io::ReadColmapTextModel("colmap/sparse/0"),
//                                               /*ignore_distortion=*/true);
#pragma once

#include "io/colmap/colmap_text_model.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

// COLMAP's pixel convention minus ours.
inline constexpr double kColmapPixelOffset = 0.5;

// The registered images of `reconstruction` with all their 2-D points, their cameras, and every
// 3-D point (mean reprojection error recomputed), ids unchanged.
io::ColmapTextModel ToColmapTextModel(const Reconstruction& reconstruction);

// A Reconstruction holding the model's cameras, images (all registered) and points, ids
// unchanged. Reads the five models of sfm/camera_model.h with their distortion, or with
// `ignore_distortion` their pinhole part only (poses stay exact, reprojection errors become
// approximate). Throws comic::Error(kInvalidData) for other models or an inconsistent model.
Reconstruction FromColmapTextModel(const io::ColmapTextModel& model,
                                   bool ignore_distortion = false);

}  // namespace comic::sfm
