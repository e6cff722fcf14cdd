#include "frontend/evaluation/track_survival.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/video/tracking.hpp>

#include "frontend/matching/usac_params.h"
#include "io/core/error.h"

namespace comic::frontend {

void LkReferenceOptions::Check() const {
  COMIC_CHECK(window >= 3 && window % 2 == 1, kInvalidArgument,
              "LK reference: window must be odd and >= 3, got " << window);
  COMIC_CHECK(levels >= 0, kInvalidArgument, "LK reference: levels must be >= 0");
  COMIC_CHECK(max_iterations >= 1, kInvalidArgument, "LK reference: max_iterations must be >= 1");
  COMIC_CHECK(epsilon > 0, kInvalidArgument, "LK reference: epsilon must be > 0");
  COMIC_CHECK(max_forward_backward_px > 0, kInvalidArgument,
              "LK reference: max_forward_backward_px must be > 0");
}

LkFlow TrackPointsLk(const cv::Mat& gray1, const cv::Mat& gray2,
                     const std::vector<cv::Point2f>& points, const LkReferenceOptions& options) {
  options.Check();
  COMIC_CHECK(!gray1.empty() && gray1.type() == CV_8UC1 && gray2.type() == CV_8UC1 &&
                  gray1.size() == gray2.size(),
              kInvalidArgument, "LK reference: frames must be 8-bit grey of one size");
  LkFlow flow;
  flow.positions = points;
  flow.valid.assign(points.size(), false);
  flow.outside.assign(points.size(), false);
  if (points.empty()) return flow;
  const cv::Size window(options.window, options.window);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS,
                                  options.max_iterations, options.epsilon);
  std::vector<cv::Point2f> forward, backward;
  std::vector<uchar> status_forward, status_backward;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(gray1, gray2, points, forward, status_forward, error, window,
                           options.levels, criteria);
  cv::calcOpticalFlowPyrLK(gray2, gray1, forward, backward, status_backward, error, window,
                           options.levels, criteria);
  const float margin = static_cast<float>(kPatchRadius);
  for (size_t i = 0; i < points.size(); ++i) {
    const cv::Point2f p = forward[i];
    const bool inside = p.x >= margin && p.y >= margin && p.x <= gray2.cols - 1 - margin &&
                        p.y <= gray2.rows - 1 - margin;
    const cv::Point2f back = backward[i] - points[i];
    flow.positions[i] = p;
    flow.outside[i] = !inside;
    flow.valid[i] = status_forward[i] && status_backward[i] && inside &&
                    std::sqrt(back.dot(back)) <= options.max_forward_backward_px;
  }
  return flow;
}

std::vector<int> SurvivalStartFrames(int num_frames, int stride, int horizon) {
  COMIC_CHECK(stride >= 1 && horizon >= 0, kInvalidArgument,
              "survival: stride must be >= 1 and horizon >= 0");
  std::vector<int> starts;
  for (int s = 0; s + horizon <= num_frames - 1; s += stride) starts.push_back(s);
  if (starts.empty() && num_frames > 0) starts.push_back(0);
  return starts;
}

namespace {

bool IsContinued(const TrackingResult& result, int frame, int feature) {
  return frame < static_cast<int>(result.continued.size()) && result.continued[frame][feature];
}

}  // namespace

std::vector<int> FramesFollowedFrom(const TrackingResult& result, const std::vector<int>& starts) {
  const FeatureTracks& tracks = result.tracks;
  // Per frame, per feature: the last frame of its track (its own frame if it is in none).
  std::vector<std::vector<int>> last(tracks.NumFrames());
  for (size_t f = 0; f < tracks.NumFrames(); ++f) {
    last[f].resize(tracks.features[f].size());
    for (size_t k = 0; k < last[f].size(); ++k) last[f][k] = static_cast<int>(f);
  }
  for (const Track& track : tracks.tracks) {
    for (const TrackObservation& obs : track.observations) {
      last[obs.frame][obs.feature] = track.LastFrame();
    }
  }
  std::vector<int> followed;
  for (int s : starts) {
    COMIC_CHECK(s >= 0 && s < static_cast<int>(tracks.NumFrames()), kInvalidArgument,
                "survival: start frame " << s << " out of range");
    for (size_t k = 0; k < last[s].size(); ++k) {
      if (!IsContinued(result, s, static_cast<int>(k))) followed.push_back(last[s][k] - s);
    }
  }
  return followed;
}

std::vector<int> LkFramesFollowedFrom(const std::vector<cv::Mat>& grays,
                                      const TrackingResult& result, const std::vector<int>& starts,
                                      const LkReferenceOptions& options) {
  const FeatureTracks& tracks = result.tracks;
  COMIC_CHECK(grays.size() == tracks.NumFrames(), kInvalidArgument,
              "survival: " << grays.size() << " frames for tracks over " << tracks.NumFrames());
  std::vector<int> followed;
  for (int s : starts) {
    const FeatureSet& start = tracks.features[s];
    std::vector<cv::Point2f> points;
    for (size_t k = 0; k < start.size(); ++k) {
      if (!IsContinued(result, s, static_cast<int>(k))) points.push_back(start[k].Position());
    }
    std::vector<int> frames(points.size(), 0);
    std::vector<int> alive(points.size());  // indices still followed
    for (size_t i = 0; i < alive.size(); ++i) alive[i] = static_cast<int>(i);
    for (int f = s; f + 1 < static_cast<int>(grays.size()) && !alive.empty(); ++f) {
      std::vector<cv::Point2f> current;
      for (int i : alive) current.push_back(points[i]);
      const LkFlow flow = TrackPointsLk(grays[f], grays[f + 1], current, options);
      std::vector<int> still;
      for (size_t k = 0; k < alive.size(); ++k) {
        if (!flow.valid[k]) continue;
        points[alive[k]] = flow.positions[k];
        ++frames[alive[k]];
        still.push_back(alive[k]);
      }
      alive = std::move(still);
    }
    followed.insert(followed.end(), frames.begin(), frames.end());
  }
  return followed;
}

SurvivalSummary SummariseSurvival(const std::vector<int>& frames_followed) {
  SurvivalSummary summary;
  summary.num_features = static_cast<int>(frames_followed.size());
  if (frames_followed.empty()) return summary;
  const std::array<int, 3> bars = {1, 5, 10};
  double sum = 0, sum_tracked = 0;
  int tracked = 0;
  for (int n : frames_followed) {
    sum += n;
    for (size_t b = 0; b < bars.size(); ++b) summary.share_followed[b] += n >= bars[b] ? 1 : 0;
    if (n >= 1) {
      sum_tracked += n + 1;
      ++tracked;
    }
  }
  for (double& share : summary.share_followed) share /= frames_followed.size();
  summary.mean_frames_followed = sum / frames_followed.size();
  summary.mean_track_length = tracked > 0 ? sum_tracked / tracked : 0.0;
  return summary;
}

double MeanTrackLength(const FeatureTracks& tracks) {
  if (tracks.tracks.empty()) return 0.0;
  size_t observations = 0;
  for (const Track& track : tracks.tracks) observations += track.Length();
  return static_cast<double>(observations) / static_cast<double>(tracks.tracks.size());
}

const char* FeatureFateName(FeatureFate fate) {
  switch (fate) {
    case FeatureFate::kContinued:
      return "continued";
    case FeatureFate::kContinuedElsewhere:
      return "continued elsewhere";
    case FeatureFate::kContinuedByAlignment:
      return "continued by alignment";
    case FeatureFate::kLeavesImage:
      return "leaves the image";
    case FeatureFate::kNoReference:
      return "no LK reference";
    case FeatureFate::kNotDetected:
      return "not re-detected";
    case FeatureFate::kCutByMaxFeatures:
      return "cut by max features";
    case FeatureFate::kOutsideSearch:
      return "outside search region";
    case FeatureFate::kAboveThreshold:
      return "above cost threshold";
    case FeatureFate::kLostMutualBest:
      return "lost to mutual best";
    case FeatureFate::kAlignmentUntrusted:
      return "alignment untrusted";
    case FeatureFate::kContinuationLimit:
      return "continuation limit";
    case FeatureFate::kNextToAnotherTrack:
      return "next to another track";
  }
  return "?";
}

namespace {

// Index of the feature of `features` nearest to p within `tolerance`, or -1.
int NearestWithin(const FeatureSet& features, cv::Point2f p, double tolerance) {
  int best = -1;
  double best_d2 = tolerance * tolerance;
  for (int k = 0; k < static_cast<int>(features.size()); ++k) {
    const cv::Point2f d = features[k].Position() - p;
    const double d2 = d.dot(d);
    if (d2 <= best_d2) {
      best_d2 = d2;
      best = k;
    }
  }
  return best;
}

// The same among the detected (not continued) features of `frame`.
int NearestDetectedWithin(const TrackingResult& result, int frame, cv::Point2f p,
                          double tolerance) {
  const FeatureSet& features = result.tracks.features[frame];
  int best = -1;
  double best_d2 = tolerance * tolerance;
  for (int k = 0; k < static_cast<int>(features.size()); ++k) {
    if (IsContinued(result, frame, k)) continue;
    const cv::Point2f d = features[k].Position() - p;
    const double d2 = d.dot(d);
    if (d2 <= best_d2) {
      best_d2 = d2;
      best = k;
    }
  }
  return best;
}

// Per point pair: farther than max_px from the epipolar geometry the pairs agree on.
std::vector<bool> MovingPoints(const std::vector<cv::Point2f>& from,
                               const std::vector<cv::Point2f>& to, double max_px) {
  std::vector<bool> moving(from.size(), false);
  if (from.size() < 15) return moving;
  cv::Mat mask;
  cv::Mat fundamental;
  try {
    fundamental =
        cv::findFundamentalMat(from, to, mask, DeterministicUsacParams(max_px, 0.999, 2000, 1));
  } catch (const cv::Exception&) {
    return moving;
  }
  if (fundamental.empty() || mask.empty()) return moving;
  for (size_t i = 0; i < from.size(); ++i) moving[i] = !mask.at<uchar>(static_cast<int>(i));
  return moving;
}

}  // namespace

LossSplit SplitLosses(const TrackingResult& result, int frame, const cv::Mat& gray,
                      const cv::Mat& gray_next, const FeatureSet& detected_next,
                      const LkReferenceOptions& lk, const LossSplitOptions& options) {
  const FeatureTracks& tracks = result.tracks;
  COMIC_CHECK(frame >= 0 && frame + 1 < static_cast<int>(tracks.NumFrames()), kInvalidArgument,
              "loss split: frame " << frame << " has no next frame");
  const FeatureSet& features = tracks.features[frame];
  const FeatureSet& next = tracks.features[frame + 1];
  // Where each feature's track goes next: the feature of frame + 1, or the frame it resumes in;
  // and how many frames in a row it has been continued.
  std::vector<int> next_feature(features.size(), -1);
  std::vector<bool> resumes(features.size(), false);
  std::vector<int> runs(features.size(), 0);
  for (const Track& track : tracks.tracks) {
    for (size_t o = 0; o < track.observations.size(); ++o) {
      if (track.observations[o].frame != frame) continue;
      for (size_t b = o + 1; b-- > 0;) {
        const TrackObservation& before = track.observations[b];
        if (before.frame != frame - static_cast<int>(o - b) ||
            !IsContinued(result, before.frame, before.feature)) {
          break;
        }
        ++runs[track.observations[o].feature];
      }
      if (o + 1 == track.observations.size()) continue;
      const TrackObservation& after = track.observations[o + 1];
      if (after.frame == frame + 1) {
        next_feature[track.observations[o].feature] = after.feature;
      } else {
        resumes[track.observations[o].feature] = true;
      }
    }
  }
  std::vector<cv::Point2f> points;
  for (const Feature& f : features) points.push_back(f.Position());
  const LkFlow flow = TrackPointsLk(gray, gray_next, points, lk);
  std::vector<cv::Point2f> from, to;
  std::vector<int> valid_index;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!flow.valid[i]) continue;
    from.push_back(points[i]);
    to.push_back(flow.positions[i]);
    valid_index.push_back(static_cast<int>(i));
  }
  const std::vector<bool> moving_valid = MovingPoints(from, to, options.moving_epipolar_px);
  std::vector<bool> moving(points.size(), false);
  for (size_t k = 0; k < valid_index.size(); ++k) moving[valid_index[k]] = moving_valid[k];

  const SearchRegions& search = result.search_regions.at(frame);
  const bool align = result.options.align_patches;
  const PatchMatcherOptions& matcher = result.options.matcher;
  LossSplit split;
  split.num_features = static_cast<int>(features.size());
  for (size_t i = 0; i < features.size(); ++i) {
    const cv::Point2f reference = flow.positions[i];
    FeatureFate fate;
    if (next_feature[i] >= 0) {
      const cv::Point2f d = next[next_feature[i]].Position() - reference;
      if (IsContinued(result, frame + 1, next_feature[i])) {
        fate = FeatureFate::kContinuedByAlignment;
      } else {
        fate = flow.valid[i] && std::sqrt(d.dot(d)) > options.reference_tolerance_px
                   ? FeatureFate::kContinuedElsewhere
                   : FeatureFate::kContinued;
      }
    } else if (!flow.valid[i]) {
      fate = flow.outside[i] ? FeatureFate::kLeavesImage : FeatureFate::kNoReference;
    } else {
      const int found =
          NearestDetectedWithin(result, frame + 1, reference, options.reference_tolerance_px);
      if (found < 0) {
        if (align) {
          if (!IsTrusted(result.alignments.at(frame)[i], result.options.continuation)) {
            fate = FeatureFate::kAlignmentUntrusted;
          } else if (runs[i] >= result.options.continuation.max_continued_frames) {
            fate = FeatureFate::kContinuationLimit;
          } else {
            fate = FeatureFate::kNextToAnotherTrack;
          }
        } else {
          fate = NearestWithin(detected_next, reference, options.reference_tolerance_px) >= 0
                     ? FeatureFate::kCutByMaxFeatures
                     : FeatureFate::kNotDetected;
        }
      } else {
        const cv::Point2f centre = search.centres.empty() ? points[i] : search.centres[i];
        const double radius = search.radii.empty() ? matcher.radius : search.radii[i];
        const cv::Point2f off = next[found].Position() - centre;
        if (std::sqrt(off.dot(off)) > radius) {
          fate = FeatureFate::kOutsideSearch;
        } else if (PatchCost(gray, features[i], gray_next, next[found], matcher) >
                   matcher.max_cost) {
          fate = FeatureFate::kAboveThreshold;
        } else {
          fate = FeatureFate::kLostMutualBest;
        }
      }
    }
    ++split.counts[static_cast<int>(fate)][moving[i] ? 1 : 0];
    if (next_feature[i] < 0 && resumes[i]) ++split.resumed_later;
  }
  return split;
}

TrackAccuracy EvaluateTrackAccuracy(const TrackingResult& result, const cv::Matx33d& K,
                                    const std::vector<cv::Matx34d>& world_from_camera,
                                    double tolerance_px) {
  const FeatureTracks& tracks = result.tracks;
  COMIC_CHECK(world_from_camera.size() == tracks.NumFrames(), kInvalidArgument,
              "track accuracy: " << world_from_camera.size() << " poses for " << tracks.NumFrames()
                                 << " frames");
  // Projection matrices P = K [Rᵀ | −Rᵀ t].
  std::vector<cv::Matx34d> projections;
  for (const cv::Matx34d& pose : world_from_camera) {
    const cv::Matx33d R = pose.get_minor<3, 3>(0, 0);
    const cv::Vec3d t(pose(0, 3), pose(1, 3), pose(2, 3));
    const cv::Matx33d Rt = R.t();
    const cv::Vec3d c = -(Rt * t);
    cv::Matx34d Rc;
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) Rc(r, k) = Rt(r, k);
      Rc(r, 3) = c[r];
    }
    projections.push_back(K * Rc);
  }
  TrackAccuracy accuracy;
  std::array<std::vector<double>, 2> errors;
  for (const Track& track : tracks.tracks) {
    if (track.Length() < 3) continue;
    cv::Mat A(2 * static_cast<int>(track.Length()), 4, CV_64F);
    for (size_t o = 0; o < track.Length(); ++o) {
      const TrackObservation& obs = track.observations[o];
      const cv::Point2f x = tracks.FeatureOf(obs).Position();
      const cv::Matx34d& P = projections[obs.frame];
      for (int k = 0; k < 4; ++k) {
        A.at<double>(2 * o, k) = x.x * P(2, k) - P(0, k);
        A.at<double>(2 * o + 1, k) = x.y * P(2, k) - P(1, k);
      }
    }
    cv::Mat w, u, vt;
    cv::SVD::compute(A, w, u, vt, cv::SVD::MODIFY_A);
    const cv::Vec4d X(vt.at<double>(3, 0), vt.at<double>(3, 1), vt.at<double>(3, 2),
                      vt.at<double>(3, 3));
    std::vector<std::pair<int, double>> track_errors;
    bool in_front = true;
    for (const TrackObservation& obs : track.observations) {
      const cv::Vec3d p = projections[obs.frame] * X;
      if (p[2] * X[3] <= 0) in_front = false;
      const cv::Point2f x = tracks.FeatureOf(obs).Position();
      const double ex = p[0] / p[2] - x.x, ey = p[1] / p[2] - x.y;
      track_errors.emplace_back(IsContinued(result, obs.frame, obs.feature) ? 1 : 0,
                                std::sqrt(ex * ex + ey * ey));
    }
    if (!in_front) continue;
    ++accuracy.tracks;
    for (const auto& [kind, error] : track_errors) {
      ++accuracy.observations[kind];
      if (error > tolerance_px) ++accuracy.beyond_tolerance[kind];
      errors[kind].push_back(error);
    }
  }
  for (int kind = 0; kind < 2; ++kind) {
    std::vector<double>& e = errors[kind];
    if (e.empty()) continue;
    std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
    accuracy.median_error_px[kind] = e[e.size() / 2];
  }
  return accuracy;
}

void Accumulate(const LossSplit& b, LossSplit* a) {
  a->num_features += b.num_features;
  for (int f = 0; f < kNumFeatureFates; ++f) {
    for (int m = 0; m < 2; ++m) a->counts[f][m] += b.counts[f][m];
  }
  a->resumed_later += b.resumed_later;
}

}  // namespace comic::frontend
