#include "frontend/comic/corner_convergence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "frontend/comic/iso_curve.h"
#include "io/core/error.h"

namespace comic::frontend {

void ConvergenceOptions::Check() const {
  COMIC_CHECK(block_size >= 8, kInvalidArgument, "convergence: block_size must be >= 8");
  COMIC_CHECK(half_length >= 2, kInvalidArgument, "convergence: half_length must be >= 2");
  COMIC_CHECK(sigma > 0, kInvalidArgument, "convergence: sigma must be > 0");
  COMIC_CHECK(delta > 0, kInvalidArgument, "convergence: delta must be > 0");
  COMIC_CHECK(min_cornerness >= 0, kInvalidArgument, "convergence: min_cornerness must be >= 0");
  COMIC_CHECK(max_iterations >= 1, kInvalidArgument, "convergence: max_iterations must be >= 1");
  COMIC_CHECK(tolerance >= 0, kInvalidArgument, "convergence: tolerance must be >= 0");
  COMIC_CHECK(stop_tolerance >= 0, kInvalidArgument, "convergence: stop_tolerance must be >= 0");
  COMIC_CHECK(
      corner.straight_arms_rms_begin >= 0 &&
          corner.straight_arms_rms_end > corner.straight_arms_rms_begin,
      kInvalidArgument,
      "convergence: need 0 <= corner.straight_arms_rms_begin < corner.straight_arms_rms_end");
}

WeightedStabilityOptions ConvergenceOptions::StabilityOptions() const {
  WeightedStabilityOptions stability;
  stability.half_length = half_length;
  stability.sigma = sigma;
  stability.delta = delta;
  // Bands wider than half a segment are of curves too unstable to matter.
  stability.max_distance = std::max(3.0, 0.5 * half_length);
  return stability;
}

namespace {

double Distance(const cv::Point2f& a, const cv::Point2f& b) {
  return std::hypot(static_cast<double>(a.x) - b.x, static_cast<double>(a.y) - b.y);
}

// Where the selected level's curve crosses the central normal, interpolated between levels.
cv::Point2f CurvePointOnCentralNormal(WeightedStabilityEvaluator* profile,
                                      const StableLevel& level) {
  const double index = level.threshold - 0.5 - profile->first_level();
  const int i0 = std::clamp(static_cast<int>(std::floor(index)), 0, profile->NumLevels() - 1);
  const int i1 = std::min(i0 + 1, profile->NumLevels() - 1);
  const double t = std::clamp(index - i0, 0.0, 1.0);
  const double u0 = profile->CentreOffset(i0);
  const double u = u0 + t * (profile->CentreOffset(i1) - u0);
  const cv::Point2d q = profile->centre() + u * profile->normal();
  return cv::Point2f(q);
}

}  // namespace

bool RedetectCorner(const cv::Mat& gray, const cv::Point2f& position,
                    const std::vector<cv::Point2f>& reference, double previous_level,
                    const ConvergenceOptions& options, ConvergedCorner* result,
                    ConvergenceWorkspace* workspace) {
  ConvergenceWorkspace local_workspace;
  if (workspace == nullptr) workspace = &local_workspace;
  const int k = options.half_length;
  // Weights centred on p, the point of the previous MSICS nearest to the corner.
  const double s_p = ProjectOntoPolyline(reference, false, position);
  int centre = 0;
  const std::vector<cv::Point2f> segment =
      ResamplePolyline(reference, false, 1.0, s_p, k + 1, k + 1, &centre);
  // The MSICS nearest in level to the previous one (ρ_w evaluated only at the levels the choice
  // looks at).
  WeightedStabilityEvaluator& profile = workspace->profile;
  const WeightedStabilityOptions stability_options = options.StabilityOptions();
  StableLevel stable;
  if (!profile.Prepare(gray, segment, centre, stability_options) ||
      !SelectMaximallyStableLevel(&profile, previous_level, stability_options.run_tolerance,
                                  stability_options.ripple_tolerance, &stable)) {
    return false;
  }

  // Trace the MSICS at its refined threshold in the B/2 block centred on the corner.
  const int half = options.block_size / 2;
  const cv::Rect block(static_cast<int>(std::lround(position.x)) - half,
                       static_cast<int>(std::lround(position.y)) - half, options.block_size,
                       options.block_size);
  const IsoCurveTracer tracer(gray, block, stable.threshold);
  CurveEdge seed;
  if (!tracer.FindNearestCrossing(CurvePointOnCentralNormal(&profile, stable), 2, &seed)) {
    return false;
  }
  // The new corner may lie up to k px along the curve from p; κ there needs the filter's support
  // (3 box radii) beyond the segment. Crossings are 0.5-1 px apart.
  const int reach = 2 * k + 3 * BoxRadiusForGaussian(options.sigma) + 2;
  IsoCurve& traced = workspace->traced;
  tracer.Trace(seed, 2 * reach, &traced);
  std::vector<double>& arc_lengths = workspace->arc_lengths;
  PolylineArcLengths(traced.points, traced.closed, &arc_lengths);
  if (traced.closed && arc_lengths.back() < 4 * k + 1) return false;
  int origin = 0;
  const double s_seed = arc_lengths[traced.seed_index];  // the seed is always one of the points
  std::vector<cv::Point2f> samples = ResamplePolyline(traced.points, arc_lengths, traced.closed,
                                                      1.0, s_seed, reach, reach, &origin);
  const int n = static_cast<int>(samples.size());
  if (n < 2 * k + 1) return false;

  // The corner on it nearest to the previous one.
  std::vector<double>& kappa = workspace->kappa;
  CurveCornerness(samples, traced.closed, options.sigma, k, &workspace->cornerness, &kappa);
  const int nms_radius = std::max(1, static_cast<int>(std::lround(options.sigma)));
  double best_distance = std::numeric_limits<double>::infinity();
  int best_index = -1;
  const std::vector<int> maxima =
      CornernessMaxima(kappa, traced.closed, nms_radius, options.min_cornerness);
  for (int index : maxima) {
    const double d = Distance(samples[index], position);
    if (d < best_distance) {
      best_distance = d;
      best_index = index;
    }
  }
  if (best_index < 0) return false;
  result->other_corners.clear();
  for (int index : maxima) {
    const int gap = traced.closed
                        ? std::min(std::abs(index - best_index), n - std::abs(index - best_index))
                        : std::abs(index - best_index);
    if (index != best_index && gap <= 2 * k) result->other_corners.push_back(samples[index]);
  }
  const CurveCorner best =
      RefineCurveCorner(samples, traced.closed, kappa, best_index, options.corner);
  if (!(Distance(best.vertex, position) <= k)) return false;

  result->position = best.vertex;
  result->apex = best.apex;
  result->level = stable.level;
  result->threshold = stable.threshold;
  result->stability = stable.stability;
  result->cornerness = best.cornerness;
  result->polarity = best.polarity;
  const int corner_index = static_cast<int>(std::lround(best.index));
  const int half_segment = traced.closed ? std::min(k, (n - 1) / 2) : k;
  result->segment.clear();
  for (int j = corner_index - half_segment; j <= corner_index + half_segment; ++j) {
    if (!traced.closed && (j < 0 || j >= n)) continue;
    result->segment.push_back(samples[((j % n) + n) % n]);
  }
  if (traced.closed) {
    // Open the loop opposite the corner so the next iteration sees a simple polyline.
    std::rotate(samples.begin(), samples.begin() + ((corner_index + n / 2) % n), samples.end());
  }
  result->curve = std::move(samples);
  return true;
}

void CornerConvergence::Start(const cv::Point2f& position, std::vector<cv::Point2f> reference,
                              double level) {
  current_ = position;
  reference_ = std::move(reference);
  level_ = level;
  iteration_ = 0;
  last_ = ConvergedCorner();
  before_last_ = ConvergedCorner();
  result_ = ConvergedCorner();
}

CornerConvergence::Status CornerConvergence::Step(const cv::Mat& gray,
                                                  const ConvergenceOptions& options,
                                                  ConvergenceWorkspace* workspace) {
  ConvergenceWorkspace local_workspace;
  if (workspace == nullptr) workspace = &local_workspace;
  ++iteration_;
  ConvergedCorner next;
  // The previous MSICS: the seed's curve at first, then the curve the last iteration traced.
  const std::vector<cv::Point2f>& reference = iteration_ == 1 ? reference_ : last_.curve;
  if (!RedetectCorner(gray, current_, reference, level_, options, &next, workspace)) {
    return Status::kLost;
  }
  // The iteration runs on the apex, the κ maximum on the curve (the paper's corner): the vertex
  // correction is an output refinement and would move the weights' centre off the curve.
  const double moved = Distance(next.apex, current_);
  // A fixed point keeps its MSICS too: a corner that barely moved while its curve jumped to
  // another level (typical of the first iteration, from the initialisation's level) goes on.
  const bool same_curve = std::abs(next.threshold - 0.5 - level_) <= 1.0;
  if (moved <= options.stop_tolerance && same_curve) {
    result_ = std::move(next);
    result_.iterations = iteration_;
    return Status::kSettled;
  }
  // Back where it was two iterations ago (within a quarter of the settle tolerance): the
  // iteration alternates between two MSICSs near the corner. It has stopped moving in the sense
  // of Algorithm 1; keep the more stable of the two.
  if (iteration_ >= 3 &&
      Distance(next.apex, before_last_.apex) <=
          std::max(options.stop_tolerance, 0.25 * options.tolerance) &&
      std::abs(next.threshold - before_last_.threshold) <= 1.0) {
    result_ = next.stability >= last_.stability ? std::move(next) : std::move(last_);
    result_.iterations = iteration_;
    return Status::kSettled;
  }
  if (iteration_ >= options.max_iterations) {
    if (moved > options.tolerance) return Status::kLost;  // still moving: not settled
    result_ = std::move(next);
    result_.iterations = iteration_;
    return Status::kSettled;
  }
  current_ = next.apex;
  level_ = next.threshold - 0.5;
  before_last_ = std::move(last_);
  last_ = std::move(next);
  if (iteration_ == 1) std::vector<cv::Point2f>().swap(reference_);
  return Status::kRunning;
}

bool ConvergeCorner(const cv::Mat& gray, const cv::Point2f& position,
                    const std::vector<cv::Point2f>& reference, double level,
                    const ConvergenceOptions& options, ConvergedCorner* result,
                    ConvergenceWorkspace* workspace) {
  options.Check();
  CornerConvergence convergence;
  convergence.Start(position, reference, level);
  for (;;) {
    switch (convergence.Step(gray, options, workspace)) {
      case CornerConvergence::Status::kRunning:
        continue;
      case CornerConvergence::Status::kSettled:
        *result = std::move(convergence.result());
        return true;
      case CornerConvergence::Status::kLost:
        return false;
    }
  }
}

}  // namespace comic::frontend
