#include "sfm/keyframe_selection.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

// For each frame, the tracks seen there: track index -> feature index.
std::vector<std::unordered_map<int, int>> TracksPerFrame(const frontend::FeatureTracks& tracks) {
  std::vector<std::unordered_map<int, int>> per_frame(tracks.NumFrames());
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : tracks.tracks[t].observations) {
      per_frame[obs.frame][static_cast<int>(t)] = obs.feature;
    }
  }
  return per_frame;
}

// The share of the keyframe's tracks seen in `frame` and their median image motion between the two.
void CompareWithKeyframe(const frontend::FeatureTracks& tracks,
                         const std::unordered_map<int, int>& keyframe_tracks, int keyframe,
                         const std::unordered_map<int, int>& frame_tracks, int frame,
                         KeyframeDecision* decision) {
  std::vector<double> motions;
  for (const auto& [track, keyframe_feature] : keyframe_tracks) {
    const auto it = frame_tracks.find(track);
    if (it == frame_tracks.end()) continue;
    const frontend::Feature& a = tracks.features[keyframe][keyframe_feature];
    const frontend::Feature& b = tracks.features[frame][it->second];
    motions.push_back(std::hypot(double(b.x) - a.x, double(b.y) - a.y));
  }
  decision->shared_fraction =
      keyframe_tracks.empty() ? 0.0 : double(motions.size()) / double(keyframe_tracks.size());
  if (motions.empty()) {
    decision->median_motion_px = 0.0;
    return;
  }
  // The order statistic does not depend on the hash map's iteration order.
  const size_t middle = motions.size() / 2;
  std::nth_element(motions.begin(), motions.begin() + middle, motions.end());
  decision->median_motion_px = motions[middle];
}

KeyframeReason Decide(const KeyframeDecision& d, int gap, const KeyframeOptions& options) {
  if (gap < options.min_frame_gap) return KeyframeReason::kNotKeyframe;
  if (d.shared_fraction < options.min_shared_fraction) return KeyframeReason::kSharedTracks;
  if (d.median_motion_px >= options.min_median_motion_px) return KeyframeReason::kMotion;
  if (gap >= options.max_frame_gap) return KeyframeReason::kFrameGap;
  return KeyframeReason::kNotKeyframe;
}

}  // namespace

void KeyframeOptions::Check() const {
  COMIC_CHECK(min_shared_fraction >= 0 && min_shared_fraction <= 1, kInvalidArgument,
              "keyframe min_shared_fraction must be in [0, 1], got " << min_shared_fraction);
  COMIC_CHECK(min_median_motion_px > 0, kInvalidArgument,
              "keyframe min_median_motion_px must be > 0, got " << min_median_motion_px);
  COMIC_CHECK(min_frame_gap >= 1 && max_frame_gap >= min_frame_gap, kInvalidArgument,
              "keyframe frame gaps must satisfy 1 <= min <= max, got " << min_frame_gap << ", "
                                                                       << max_frame_gap);
}

const char* KeyframeReasonName(KeyframeReason reason) {
  switch (reason) {
    case KeyframeReason::kFirst:
      return "first";
    case KeyframeReason::kLast:
      return "last";
    case KeyframeReason::kSharedTracks:
      return "shared_tracks";
    case KeyframeReason::kMotion:
      return "motion";
    case KeyframeReason::kFrameGap:
      return "frame_gap";
    case KeyframeReason::kNotKeyframe:
      return "not_keyframe";
    case KeyframeReason::kInitialPair:
      return "initial_pair";
    case KeyframeReason::kPromoted:
      return "promoted";
  }
  return "unknown";
}

std::vector<KeyframeDecision> SelectKeyframes(const frontend::FeatureTracks& tracks,
                                              const KeyframeOptions& options) {
  options.Check();
  const int frames = static_cast<int>(tracks.NumFrames());
  std::vector<KeyframeDecision> decisions(frames);
  if (frames == 0) return decisions;
  const std::vector<std::unordered_map<int, int>> per_frame = TracksPerFrame(tracks);

  decisions[0].keyframe = true;
  decisions[0].reason = KeyframeReason::kFirst;
  int keyframe = 0;
  for (int frame = 1; frame < frames; ++frame) {
    KeyframeDecision& d = decisions[frame];
    d.last_keyframe = keyframe;
    CompareWithKeyframe(tracks, per_frame[keyframe], keyframe, per_frame[frame], frame, &d);
    d.reason = Decide(d, frame - keyframe, options);
    if (d.reason == KeyframeReason::kNotKeyframe && frame == frames - 1) {
      d.reason = KeyframeReason::kLast;
    }
    d.keyframe = d.reason != KeyframeReason::kNotKeyframe;
    if (d.keyframe) keyframe = frame;
  }
  return decisions;
}

}  // namespace comic::sfm
