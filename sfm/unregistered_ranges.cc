#include "sfm/unregistered_ranges.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/core/error.h"

namespace comic::sfm {

namespace {

image_t ImageOf(int frame) { return static_cast<image_t>(frame + 1); }

bool Registered(const Reconstruction& model, int frame) {
  return model.ExistsImage(ImageOf(frame)) && model.image(ImageOf(frame)).registered;
}

// The reason of one frame, as a range of one.
UnregisteredRange ExplainFrame(const frontend::FeatureTracks& tracks,
                               const std::vector<IncrementalModel>& others,
                               const std::vector<int>& best_failed_pose_inliers,
                               const std::vector<char>& track_has_point,
                               const std::vector<std::vector<int>>& track_of_feature,
                               const AbsolutePoseOptions& pnp, int frame) {
  UnregisteredRange range;
  range.first_frame = range.last_frame = frame;
  range.needed = pnp.min_num_inliers;
  const int num_features = static_cast<int>(tracks.features[frame].size());
  int num_tracked = 0, num_visible = 0;
  for (int t : track_of_feature[frame]) {
    if (t < 0) continue;
    ++num_tracked;
    num_visible += track_has_point[t];
  }
  if (num_features < pnp.min_num_inliers) {
    range.stage = "tracking";
    range.check = "features";
    range.value = num_features;
    return range;
  }
  if (num_tracked < pnp.min_num_inliers) {
    range.stage = "tracking";
    range.check = "tracked_features";
    range.value = num_tracked;
    return range;
  }
  for (size_t m = 0; m < others.size(); ++m) {
    if (!Registered(others[m].reconstruction, frame)) continue;
    range.stage = "linking";
    range.check = "other_model";
    range.other_model = static_cast<int>(m);
    range.value = static_cast<double>(others[m].registered_frames.size());
    range.needed = 0;
    return range;
  }
  range.stage = "registration";
  if (num_visible < pnp.min_num_inliers) {
    range.check = "visible_points";
    range.value = num_visible;
    return range;
  }
  range.check = "pose_inliers";
  range.value = std::max(0, best_failed_pose_inliers[frame]);
  range.needed =
      std::max<double>(pnp.min_num_inliers, std::ceil(pnp.min_inlier_ratio * num_visible));
  return range;
}

std::string FrameRange(const frontend::FeatureTracks& tracks, int first, int last) {
  const auto name = [&](int frame) {
    return frame < static_cast<int>(tracks.frame_names.size()) ? tracks.frame_names[frame]
                                                               : std::to_string(frame);
  };
  std::ostringstream out;
  if (first == last) {
    out << "frame " << first << " (" << name(first) << ")";
  } else {
    out << "frames " << first << "-" << last << " (" << name(first) << "-" << name(last) << ")";
  }
  return out.str();
}

std::string Message(const frontend::FeatureTracks& tracks, const UnregisteredRange& range,
                    bool no_initial_pair_left) {
  std::ostringstream out;
  out << FrameRange(tracks, range.first_frame, range.last_frame) << ": ";
  const bool several = range.first_frame != range.last_frame;
  const std::string at_most = several ? "at most " : "";
  if (range.check == "features") {
    out << at_most << range.value << " features detected, registration needs " << range.needed
        << " (no texture, a blank or smeared view)";
  } else if (range.check == "tracked_features") {
    out << at_most << range.value << " features in tracks, registration needs " << range.needed
        << " (the tracker lost them)";
  } else if (range.check == "other_model") {
    out << "in model " << range.other_model + 1 << " (sparse/" << range.other_model + 1 << ", "
        << range.value << " frames), which shares no frames, points or seam matches with the "
        << "largest model";
  } else if (range.check == "visible_points") {
    out << at_most << range.value << " tracks with a 3-D point of the model, PnP needs "
        << range.needed;
    if (no_initial_pair_left) {
      out << "; in no model: no initial pair qualified among the frames no model holds";
    }
  } else {
    out << "PnP found " << at_most << range.value << " inliers, needs " << range.needed;
  }
  return out.str();
}

}  // namespace

std::vector<UnregisteredRange> ExplainUnregisteredFrames(
    const frontend::FeatureTracks& tracks, const Reconstruction& largest,
    const std::vector<IncrementalModel>& others, const std::vector<int>& best_failed_pose_inliers,
    const AbsolutePoseOptions& pnp, bool no_initial_pair_left) {
  const int num_frames = static_cast<int>(tracks.NumFrames());
  COMIC_CHECK(best_failed_pose_inliers.size() == tracks.NumFrames(), kInvalidArgument,
              "unregistered frames: " << best_failed_pose_inliers.size() << " inlier counts for "
                                      << num_frames << " frames");
  std::vector<std::vector<int>> track_of_feature(num_frames);
  for (int frame = 0; frame < num_frames; ++frame) {
    track_of_feature[frame].assign(tracks.features[frame].size(), -1);
  }
  std::vector<char> track_has_point(tracks.tracks.size(), 0);
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : tracks.tracks[t].observations) {
      track_of_feature[obs.frame][obs.feature] = static_cast<int>(t);
      if (Registered(largest, obs.frame) &&
          largest.image(ImageOf(obs.frame)).points2D[obs.feature].HasPoint3D()) {
        track_has_point[t] = 1;
      }
    }
  }
  std::vector<UnregisteredRange> ranges;
  for (int frame = 0; frame < num_frames; ++frame) {
    if (Registered(largest, frame)) continue;
    UnregisteredRange range = ExplainFrame(tracks, others, best_failed_pose_inliers,
                                           track_has_point, track_of_feature, pnp, frame);
    if (!ranges.empty()) {
      UnregisteredRange& last = ranges.back();
      if (last.last_frame + 1 == frame && last.stage == range.stage && last.check == range.check &&
          last.other_model == range.other_model) {
        last.last_frame = frame;
        if (range.value > last.value) {
          last.value = range.value;
          last.needed = range.needed;
        }
        continue;
      }
    }
    ranges.push_back(range);
  }
  for (UnregisteredRange& range : ranges) {
    range.message = Message(tracks, range, no_initial_pair_left);
  }
  return ranges;
}

}  // namespace comic::sfm
