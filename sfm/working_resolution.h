// Work at a working resolution (DESIGN.md, third round): the tracker's and the mapper's pixel
// thresholds and search radii are tuned at ~700 px, so larger images are worked on scaled down,
// as COLMAP caps its SIFT extraction, and the model is written in the input's pixels. One scale
// factor for both axes, as the project resizes frames (to a height) and scales cameras
// (Camera::Scaled: pixel areas scale, so a pixel centre c maps to (c + 0.5) s - 0.5).
//
//   const int height = WorkingResizeHeight(sequence.SourceFrameSize(), 1280);  // 0: keep
//   const double s = WorkingScale(width, height, 1280);
//   FeatureTracks small = ScaleTracks(tracks, s);
//   ... reconstruct at the working size ...
//   ScaleReconstruction(1.0 / s, width, height, &reconstruction);  // back in the input's pixels
#pragma once

#include <opencv2/core.hpp>
#include <optional>

#include "frontend/matching/track.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

// The factor that brings an image's larger side to at most `max_size` pixels (1 when it is
// already there, or max_size is 0).
double WorkingScale(int width, int height, int max_size);

// The height to resize frames of `source_size` to so that their larger side is at most
// `max_size` (rounded down; 0: no resizing needed).
int WorkingResizeHeight(cv::Size source_size, int max_size);

// The tracks with every feature's position (and scale) in images scaled by `factor`.
frontend::FeatureTracks ScaleTracks(const frontend::FeatureTracks& tracks, double factor);

// Scales the reconstruction's images by `factor`: camera intrinsics (with width x height as the
// new size) and 2-D points; poses and 3-D points stay.
void ScaleReconstruction(double factor, int width, int height, Reconstruction* reconstruction);

// `camera` for images of width x height (scaled by height over its height, as frames are
// resized; Camera::Scaled, with the size set exactly).
Camera ResizedCamera(const Camera& camera, int width, int height);

// A copy of `reconstruction` in images of width x height (its cameras' size scaled by one factor,
// height over height, as frames are resized; ScaleReconstruction); nullopt when it is in images
// of that size already, or has no camera (no copy: a 5000-frame model is hundreds of MB).
std::optional<Reconstruction> ResizedReconstruction(const Reconstruction& reconstruction, int width,
                                                    int height);

}  // namespace comic::sfm
