// Keyframes of a video: the frames that add points to the map and join global adjustments, chosen
// from the tracks alone, before any pose exists. A frame close to the last keyframe (most of its
// tracks still seen, little image motion since) adds little but cost at 30 frames/s; it is still
// registered against the map, so every frame keeps a pose. ORB-SLAM's rule, on tracks: a new
// keyframe when the tracked share of the last keyframe's points drops, when the image has moved
// enough for parallax, or after a maximum gap.
#pragma once

#include <string>
#include <vector>

#include "frontend/matching/track.h"

namespace comic::sfm {

struct KeyframeOptions {
  // A frame becomes a keyframe when fewer than this share of the last keyframe's tracks reach it.
  double min_shared_fraction = 0.8;
  // ... or when the median image motion of the shared tracks since the last keyframe reaches
  // this many pixels (the parallax a new view needs to add points).
  double min_median_motion_px = 12.0;
  // ... or when this many frames have passed since the last keyframe.
  int max_frame_gap = 10;
  // ... and never fewer frames apart than this (1: consecutive frames may both be keyframes).
  int min_frame_gap = 1;

  void Check() const;
};

enum class KeyframeReason {
  kFirst,         // the first frame
  kLast,          // the last frame (the end of the clip is always mapped)
  kSharedTracks,  // too few of the last keyframe's tracks remain
  kMotion,        // the image moved enough since the last keyframe
  kFrameGap,      // max_frame_gap reached
  kNotKeyframe,   // close to the last keyframe
  // Decided by the mapper, not by SelectKeyframes:
  kInitialPair,  // a model's initial pair (its first two keyframes)
  kPromoted,     // the keyframes before and after it had not registered when it did
};

// "first", "last", "shared_tracks", "motion", "frame_gap", "not_keyframe", "initial_pair",
// "promoted".
const char* KeyframeReasonName(KeyframeReason reason);

struct KeyframeDecision {
  bool keyframe = false;
  KeyframeReason reason = KeyframeReason::kNotKeyframe;
  int last_keyframe = -1;         // the keyframe this frame was compared with (-1 for the first)
  double shared_fraction = 1.0;   // of the last keyframe's tracks, the share seen here
  double median_motion_px = 0.0;  // median motion of those shared tracks since the keyframe
};

// One decision per frame of `tracks`, in frame order; deterministic.
std::vector<KeyframeDecision> SelectKeyframes(const frontend::FeatureTracks& tracks,
                                              const KeyframeOptions& options);

}  // namespace comic::sfm
