#include "frontend/evaluation/matching_evaluation.h"

#include <cmath>
#include <limits>

#include "io/core/error.h"

namespace comic::frontend {

void MatchingScoreOptions::Check() const {
  COMIC_CHECK(n >= 1, kInvalidArgument, "matching scores: n must be >= 1, got " << n);
  COMIC_CHECK(frame_step >= 1, kInvalidArgument,
              "matching scores: frame_step must be >= 1, got " << frame_step);
}

namespace {

RegionScore Summarise(const std::vector<MatchingScoreSample>& samples, int cls) {
  RegionScore score;
  double ratio_sum = 0.0;
  int64_t residual_sum = 0, detection_sum = 0;
  for (const MatchingScoreSample& s : samples) {
    residual_sum += s.residual[cls];
    detection_sum += s.detections[cls];
    if (s.detections[cls] > 0) {
      ratio_sum += static_cast<double>(s.residual[cls]) / s.detections[cls];
      ++score.scored_frames;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  score.mean_m_score = score.scored_frames > 0 ? ratio_sum / score.scored_frames : nan;
  score.pooled_m_score =
      detection_sum > 0 ? static_cast<double>(residual_sum) / detection_sum : nan;
  score.mean_res_m = static_cast<double>(residual_sum) / samples.size();
  score.mean_detections = static_cast<double>(detection_sum) / samples.size();
  return score;
}

}  // namespace

MatchingScores ComputeMatchingScores(const FeatureTracks& tracks,
                                     const std::vector<std::vector<RegionLabel>>& labels,
                                     const MatchingScoreOptions& options) {
  options.Check();
  const int num_frames = static_cast<int>(tracks.NumFrames());
  COMIC_CHECK(options.n < num_frames, kInvalidArgument,
              "n = " << options.n << " needs at least " << options.n + 1
                     << " frames, the sequence has " << num_frames);
  COMIC_CHECK(
      labels.empty() || static_cast<int>(labels.size()) == num_frames, kInvalidArgument,
      "matching scores: labels for " << labels.size() << " frames, tracks have " << num_frames);
  for (size_t f = 0; f < labels.size(); ++f) {
    COMIC_CHECK(labels[f].size() == tracks.features[f].size(), kInvalidArgument,
                "matching scores: frame " << f << " has " << tracks.features[f].size()
                                          << " features but " << labels[f].size() << " labels");
  }
  // How far each feature's track reaches forward one frame at a time: reach[f][k] = the number of
  // consecutive later frames it is matched through.
  std::vector<std::vector<int>> reach(num_frames);
  for (int f = 0; f < num_frames; ++f) reach[f].assign(tracks.features[f].size(), 0);
  for (const Track& track : tracks.tracks) {
    const auto& obs = track.observations;
    // Walk backwards so each observation knows the run of consecutive frames after it.
    int run = 0;
    for (int k = static_cast<int>(obs.size()) - 1; k >= 0; --k) {
      if (k + 1 < static_cast<int>(obs.size()) && obs[k + 1].frame == obs[k].frame + 1) {
        ++run;
      } else {
        run = 0;
      }
      reach[obs[k].frame][obs[k].feature] = run;
    }
  }
  MatchingScores scores;
  scores.n = options.n;
  for (int start = 0; start + options.n < num_frames; start += options.frame_step) {
    MatchingScoreSample sample;
    sample.start_frame = start;
    for (size_t k = 0; k < tracks.features[start].size(); ++k) {
      int cls = -1;  // -1: counts in "overall" only
      if (!labels.empty()) {
        const RegionLabel label = labels[start][k];
        if (label == RegionLabel::kOutside) continue;
        cls = label == RegionLabel::kBoundary ? 0 : 1;
      }
      const bool survives = reach[start][k] >= options.n;
      if (cls >= 0) {
        ++sample.detections[cls];
        sample.residual[cls] += survives ? 1 : 0;
      }
      ++sample.detections[2];
      sample.residual[2] += survives ? 1 : 0;
    }
    scores.samples.push_back(sample);
  }
  scores.boundary = Summarise(scores.samples, 0);
  scores.non_boundary = Summarise(scores.samples, 1);
  scores.overall = Summarise(scores.samples, 2);
  return scores;
}

}  // namespace comic::frontend
