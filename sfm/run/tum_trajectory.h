// A model's camera path in the TUM RGB-D benchmark's trajectory format, the one `evo` and the
// SLAM evaluation scripts read: one line per registered frame, in frame order,
//   timestamp tx ty tz qx qy qz qw
// with (tx, ty, tz) the camera centre in the model's world and (qx, qy, qz, qw) the
// camera-to-world rotation (world_from_cam, Hamilton, scalar last). The timestamp is the frame's
// source index over the video's frame rate (seconds), or the source index itself when the rate is
// unknown (a folder of images). Frames no model of the run holds are left out.
//
//   io::WriteFileAtomically("out/trajectory_tum.txt",
//                           TumTrajectoryText(reconstruction, names, source_indices, 30.0));
#pragma once

#include <string>
#include <vector>

#include "sfm/reconstruction.h"

namespace comic::sfm {

// The trajectory of `reconstruction`'s registered images matched to frames by name (frame i is
// `frame_names[i]`, source index `source_indices[i]`); `fps` <= 0: timestamps are source indices.
std::string TumTrajectoryText(const Reconstruction& reconstruction,
                              const std::vector<std::string>& frame_names,
                              const std::vector<int>& source_indices, double fps);

}  // namespace comic::sfm
