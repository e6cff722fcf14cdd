#include "sfm/run/tum_trajectory.h"

#include <cstdio>
#include <cstdlib>

#include "io/core/error.h"
#include "sfm/evaluation/ground_truth.h"

namespace comic::sfm {

namespace {

// The shortest of 15 and 17 significant digits that reads back as `value` ("2.2", not
// "2.2000000000000002", for frame 11 at 5 fps).
std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.15g", value);
  if (std::strtod(text, nullptr) != value) std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

}  // namespace

std::string TumTrajectoryText(const Reconstruction& reconstruction,
                              const std::vector<std::string>& frame_names,
                              const std::vector<int>& source_indices, double fps) {
  COMIC_CHECK(frame_names.size() == source_indices.size(), kInvalidArgument,
              "trajectory_tum.txt: " << frame_names.size() << " frame names but "
                                     << source_indices.size() << " source indices");
  const auto poses = RegisteredPosesByName(reconstruction, frame_names);
  std::string text;
  for (size_t i = 0; i < poses.size(); ++i) {
    if (!poses[i]) continue;
    const Rigid3d world_from_cam = poses[i]->Inverse();
    const Eigen::Quaterniond& q = world_from_cam.rotation;
    const Eigen::Vector3d& c = world_from_cam.translation;
    const double timestamp = fps > 0.0 ? source_indices[i] / fps : source_indices[i];
    for (double value : {timestamp, c.x(), c.y(), c.z(), q.x(), q.y(), q.z()}) {
      text += Number(value) + " ";
    }
    text += Number(q.w()) + "\n";
  }
  return text;
}

}  // namespace comic::sfm
