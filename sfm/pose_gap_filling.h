// Poses for the frames a model could not register although the camera was near a registered
// frame (issue 30, "frames through hard stretches"):
//  - rotation against the map: a frame adjacent to a posed frame n whose observed rays are
//    explained by a rotation about n's centre (the camera only turned, or moved too little for
//    its tracks to show it). The rays come from the frame's tracks that have a 3-D point (the
//    point's direction from n's centre) or an observation in n (n's ray); RANSAC over ray pairs,
//    Kabsch (sfm/rotation_only_path.h). Chained: a frame posed so serves its own neighbours.
//  - interpolation: a frame between two posed frames of the model at most max_interpolated_gap
//    frames apart gets the pose interpolated by frame index (slerp, linear centre); a guess.
// Neither adds observations or points. The frames posed by rotation are registered in the model
// (their rotation is estimated from their own observations) and listed. The interpolated ones are
// not: their poses are returned beside the model, never registered in it, so that no model
// written (COLMAP's images.txt has no flag for a guess) and no count of registered frames holds
// a pose nothing observed (issue 47). Interpolation is meant for video, where frames close in
// index are close in time.
//
//   const PoseGapFilling filled = FillPoseGaps(tracks, fillable, options, &model);
#pragma once

#include <vector>

#include "frontend/matching/track.h"
#include "sfm/reconstruction.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

struct PoseGapFillingOptions {
  // Rotation against the map: at least this many rays, and this fraction of the frame's rays,
  // consistent with one rotation within max_error_px (at the focal length), from num_trials
  // RANSAC draws (fixed seed). The fraction keeps out a camera that moved: its far points would
  // still fit a rotation, its near ones not.
  int min_num_inliers = 30;
  double min_inlier_ratio = 0.5;
  double max_error_px = 2.0;
  int num_trials = 200;
  // Interpolation between posed frames at most this many frames apart (0: none).
  int max_interpolated_gap = 10;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct PoseGapFilling {
  std::vector<int> rotation_only_frames;    // ascending, registered in the model
  std::vector<int> interpolated_frames;     // ascending, not registered in the model
  std::vector<Rigid3d> interpolated_poses;  // cam_from_world of each interpolated frame
};

// Poses the frames of `model` (image i + 1 is frame i of `tracks`) that are unregistered and
// `fillable` (one flag per frame): by rotation, registered in `model`; interpolated, returned.
// Throws comic::Error for a model that does not hold the tracks' frames.
PoseGapFilling FillPoseGaps(const frontend::FeatureTracks& tracks,
                            const std::vector<char>& fillable, const PoseGapFillingOptions& options,
                            Reconstruction* model);

}  // namespace comic::sfm
