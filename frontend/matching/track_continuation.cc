#include "frontend/matching/track_continuation.h"

#include <algorithm>
#include <cmath>
#include <opencv2/video/tracking.hpp>

#include "io/core/error.h"

namespace comic::frontend {

void TrackContinuationOptions::Check() const {
  alignment.Check();
  COMIC_CHECK(max_residual >= 0, kInvalidArgument,
              "track continuation: max_residual must be >= 0, got " << max_residual);
  COMIC_CHECK(aligned_radius > 0, kInvalidArgument,
              "track continuation: aligned_radius must be > 0 px, got " << aligned_radius);
  COMIC_CHECK(
      max_continued_frames >= 0, kInvalidArgument,
      "track continuation: max_continued_frames must be >= 0, got " << max_continued_frames);
  COMIC_CHECK(min_separation >= 0, kInvalidArgument,
              "track continuation: min_separation must be >= 0 px, got " << min_separation);
  COMIC_CHECK(bridge_frames >= 0, kInvalidArgument,
              "track continuation: bridge_frames must be >= 0, got " << bridge_frames);
}

std::vector<PatchAlignment> AlignFeatures(const FeatureSet& features1, const ImagePyramid& pyramid1,
                                          const ImagePyramid& pyramid2,
                                          const SearchRegions& predicted,
                                          const std::vector<AlignmentWeights>& weights,
                                          const PatchAlignmentOptions& options) {
  COMIC_CHECK(predicted.centres.empty() || predicted.centres.size() == features1.size(),
              kInvalidArgument, "align features: one search centre per feature needed");
  COMIC_CHECK(weights.empty() || weights.size() == features1.size(), kInvalidArgument,
              "align features: one weight set per feature needed");
  static const AlignmentWeights kFullWindow;
  std::vector<PatchAlignment> aligned(features1.size());
  if (features1.empty()) return aligned;
  // Coarse to fine by OpenCV's pyramidal Lucas–Kanade (fast, plain SSD), then the affine
  // photometric refinement at full resolution.
  std::vector<cv::Point2f> points, flow;
  for (size_t i = 0; i < features1.size(); ++i) {
    points.push_back(features1[i].Position());
    flow.push_back(predicted.centres.empty() ? features1[i].Position() : predicted.centres[i]);
  }
  std::vector<uchar> status;
  std::vector<float> error;
  const int levels = std::min(options.levels, pyramid1.NumLevels() - 1);
  cv::calcOpticalFlowPyrLK(pyramid1.OpticalFlowLevels(), pyramid2.OpticalFlowLevels(), points, flow,
                           status, error, cv::Size(options.window, options.window), levels,
                           cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS,
                                            options.max_iterations, options.min_step_px),
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  std::vector<uchar> back_status(status.size(), 1);
  std::vector<cv::Point2f> back = points;
  if (options.max_forward_backward_px > 0) {
    cv::calcOpticalFlowPyrLK(pyramid2.OpticalFlowLevels(), pyramid1.OpticalFlowLevels(), flow, back,
                             back_status, error, cv::Size(options.window, options.window), levels,
                             cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS,
                                              options.max_iterations, options.min_step_px),
                             cv::OPTFLOW_USE_INITIAL_FLOW);
  }
  PatchAlignmentOptions refine = options;
  refine.levels = 0;
  refine.max_iterations = 5;
  const float max_fb2 =
      static_cast<float>(options.max_forward_backward_px * options.max_forward_backward_px);
  for (size_t i = 0; i < features1.size(); ++i) {
    if (!status[i]) continue;
    const cv::Point2f fb = back[i] - points[i];
    if (options.max_forward_backward_px > 0 && (!back_status[i] || fb.dot(fb) > max_fb2)) continue;
    aligned[i] = AlignPatch(pyramid1, points[i], pyramid2, flow[i],
                            weights.empty() ? kFullWindow : weights[i], refine);
  }
  return aligned;
}

std::vector<cv::Point2f> PredictFromNeighbours(const std::vector<cv::Point2f>& points,
                                               const std::vector<MotionSample>& samples, int k,
                                               double max_distance) {
  std::vector<cv::Point2f> predicted = points;
  const float max_d2 = static_cast<float>(max_distance * max_distance);
  std::vector<std::pair<float, int>> near;
  std::vector<float> xs, ys;
  auto median = [](std::vector<float>& v) {
    std::sort(v.begin(), v.end());
    const size_t m = v.size() / 2;
    return v.size() % 2 == 1 ? v[m] : 0.5f * (v[m - 1] + v[m]);
  };
  for (cv::Point2f& p : predicted) {
    near.clear();
    for (int s = 0; s < static_cast<int>(samples.size()); ++s) {
      const cv::Point2f d = samples[s].position - p;
      const float d2 = d.dot(d);
      if (d2 <= max_d2) near.emplace_back(d2, s);
    }
    if (near.empty()) continue;
    const size_t n = std::min<size_t>(k, near.size());
    std::partial_sort(near.begin(), near.begin() + n, near.end());
    xs.clear();
    ys.clear();
    for (size_t i = 0; i < n; ++i) {
      xs.push_back(samples[near[i].second].displacement.x);
      ys.push_back(samples[near[i].second].displacement.y);
    }
    p += cv::Point2f(median(xs), median(ys));
  }
  return predicted;
}

bool IsTrusted(const PatchAlignment& alignment, const TrackContinuationOptions& options) {
  return alignment.converged && alignment.residual <= options.max_residual &&
         alignment.correlation >= options.min_correlation;
}

SearchRegions GuidedSearchRegions(const FeatureSet& features1, const SearchRegions& predicted,
                                  double default_radius, const std::vector<PatchAlignment>& aligned,
                                  const TrackContinuationOptions& options) {
  COMIC_CHECK(aligned.size() == features1.size(), kInvalidArgument,
              "guided search: one alignment per feature needed");
  SearchRegions search;
  search.centres.resize(features1.size());
  search.radii.resize(features1.size());
  for (size_t i = 0; i < features1.size(); ++i) {
    if (IsTrusted(aligned[i], options)) {
      search.centres[i] = aligned[i].position;
      search.radii[i] = static_cast<float>(options.aligned_radius);
    } else {
      search.centres[i] =
          predicted.centres.empty() ? features1[i].Position() : predicted.centres[i];
      search.radii[i] =
          predicted.radii.empty() ? static_cast<float>(default_radius) : predicted.radii[i];
    }
  }
  return search;
}

std::vector<Continuation> ContinueUnmatched(const FeatureSet& features1,
                                            const std::vector<int>& runs1,
                                            const FeatureSet& features2,
                                            const std::vector<PatchMatch>& accepted,
                                            const std::vector<PatchAlignment>& aligned,
                                            const TrackContinuationOptions& options) {
  COMIC_CHECK(runs1.size() == features1.size() && aligned.size() == features1.size(),
              kInvalidArgument, "continuation: one run and one alignment per feature needed");
  std::vector<Continuation> continued;
  if (options.max_continued_frames == 0) return continued;
  std::vector<bool> matched1(features1.size(), false);
  std::vector<cv::Point2f> taken;  // features of frame 2 held by a track
  for (const PatchMatch& m : accepted) {
    COMIC_CHECK(m.index1 >= 0 && m.index1 < static_cast<int>(features1.size()) && m.index2 >= 0 &&
                    m.index2 < static_cast<int>(features2.size()),
                kInvalidArgument, "continuation: match index out of range");
    matched1[m.index1] = true;
    taken.push_back(features2[m.index2].Position());
  }
  const double separation2 = options.min_separation * options.min_separation;
  auto near = [&](cv::Point2f a, cv::Point2f b) {
    const cv::Point2f d = a - b;
    return d.dot(d) <= separation2;
  };
  // Candidates, best (lowest residual, then lowest index) first, so a candidate near a better
  // one is the one left out.
  std::vector<int> candidates;
  for (size_t i = 0; i < features1.size(); ++i) {
    if (matched1[i] || runs1[i] >= options.max_continued_frames) continue;
    if (!IsTrusted(aligned[i], options)) continue;
    if (std::any_of(taken.begin(), taken.end(),
                    [&](cv::Point2f t) { return near(t, aligned[i].position); })) {
      continue;
    }
    candidates.push_back(static_cast<int>(i));
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](int a, int b) { return aligned[a].residual < aligned[b].residual; });
  std::vector<int> kept;
  for (int i : candidates) {
    const bool crowded = std::any_of(kept.begin(), kept.end(), [&](int k) {
      return near(aligned[k].position, aligned[i].position);
    });
    if (!crowded) kept.push_back(i);
  }
  std::sort(kept.begin(), kept.end());
  for (int i : kept) {
    Continuation c;
    c.index1 = i;
    c.feature = features1[i];
    c.feature.x = aligned[i].position.x;
    c.feature.y = aligned[i].position.y;
    // The curve drawn for a CoMIC feature moves with it.
    const cv::Point2f shift = aligned[i].position - features1[i].Position();
    for (cv::Point2f& p : c.feature.curve) p += shift;
    c.residual = aligned[i].residual;
    continued.push_back(std::move(c));
  }
  return continued;
}

}  // namespace comic::frontend
