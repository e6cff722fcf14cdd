// The paper's evaluation protocol (§5.1, Eq. 2): how many of the features detected in frame i−n
// are still matched n frames later.
//
//   ResM_{i,n}     the number of features detected in frame i−n that have a match in each of
//                  the n frames i−n+1 .. i (a track through all of them);
//   M_score(i, n) = ResM_{i,n} / N_{i−n}, with N_{i−n} the number of features detected in i−n.
//
// Both are computed with frame i−n = 0, step, 2·step, ... (step = 5: "computed for every fifth
// frame"), for every such start frame with i ≤ the last frame, and averaged. The paper uses n = 5
// (Tables 1–3) and n = 1 (stereo). Features are split by the region label of the frame they were
// detected in (region_labels.h): boundary, non-boundary (interior) and overall = both; features
// outside the object region are left out, as in the paper. Without labels every feature counts
// in "overall" and the boundary / non-boundary scores are undefined.
//
// Averaging. mean_res_m averages ResM over all start frames. mean_m_score averages the per-frame
// ratios over the start frames with N_{i−n} > 0 (a frame with no feature in a class has no
// score); pooled_m_score = Σ ResM / Σ N is reported alongside because it weighs frames by their
// feature counts and is less noisy on small regions.
//
//   MatchingScores scores = ComputeMatchingScores(tracking.tracks, labels, {.n = 5});
//   double boundary_percent = 100 * scores.boundary.mean_m_score;
#pragma once

#include <vector>

#include "frontend/evaluation/region_labels.h"
#include "frontend/matching/track.h"

namespace comic::frontend {

struct MatchingScoreOptions {
  // n: the number of frames a feature must be matched through (paper: 5, and 1 for stereo).
  int n = 5;
  // Start frames i−n are 0, frame_step, 2·frame_step, ... (paper: every fifth frame).
  int frame_step = 5;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The counts of one start frame, per class (index: 0 boundary, 1 non-boundary, 2 overall).
struct MatchingScoreSample {
  int start_frame = 0;            // i − n
  int detections[3] = {0, 0, 0};  // N_{i−n}
  int residual[3] = {0, 0, 0};    // ResM_{i,n}
};

struct RegionScore {
  double mean_m_score = 0.0;     // mean of ResM/N over start frames with N > 0; NaN if none
  double pooled_m_score = 0.0;   // Σ ResM / Σ N; NaN if Σ N = 0
  double mean_res_m = 0.0;       // mean of ResM over all start frames
  double mean_detections = 0.0;  // mean of N over all start frames
  int scored_frames = 0;         // start frames with N > 0
};

struct MatchingScores {
  int n = 0;
  RegionScore boundary;
  RegionScore non_boundary;
  RegionScore overall;
  std::vector<MatchingScoreSample> samples;
};

// Scores `tracks` (features per frame and their tracks; a track must advance one frame at a time
// to count, as the tracker's do). `labels` is empty (no region) or holds one label per feature of
// every frame. Throws comic::Error(kInvalidArgument) if n is not smaller than the number of
// frames (naming both), or the labels do not match the features.
MatchingScores ComputeMatchingScores(const FeatureTracks& tracks,
                                     const std::vector<std::vector<RegionLabel>>& labels,
                                     const MatchingScoreOptions& options);

}  // namespace comic::frontend
