// CoMIC's feature-convergence stage (paper §3, Algorithm 1 lines 7-17). Starting from an initial
// corner found at scale 2s, a B/2 x B/2 block is centred on the corner and, at scale s with
// Gaussian weights along the curve from the corner, the maximally stable iso-curve segment most
// similar to the previous one is re-detected (the local maximum of the weighted ρ over levels
// nearest to the previous level, refined below one grey level), its curve traced with sub-pixel
// precision in the block, and the corner of that curve nearest to the previous corner taken as
// the new corner. This repeats until the corner stops moving (moves at most `tolerance`); a
// corner that has not settled after `max_iterations` is dropped.
//
//   ConvergedCorner corner;
//   if (ConvergeCorner(gray, initial.position, initial.curve, initial.level, options, &corner))
//     ... corner.position, corner.stability (ρ), corner.cornerness (κ), corner.segment (MSICS)
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/comic/curve_cornerness.h"
#include "frontend/comic/iso_curve.h"
#include "frontend/comic/iso_curve_stability.h"
#include "frontend/feature.h"

namespace comic::frontend {

struct ConvergenceOptions {
  // Side of the block centred on the corner in which the curve is re-traced, px (B/2).
  int block_size = 50;
  // Samples on either side of the corner in its segment, k (≈ 25 points per ICS at scale s).
  int half_length = 12;
  // Standard deviation of the along-curve Gaussians (ρ weights and κ window), samples (∝ s).
  double sigma = 5.94;
  // δ in grey levels.
  double delta = 5.0;
  // Corners need κ >= this.
  double min_cornerness = 0.03;
  // Iterations before a corner that keeps moving is dropped.
  int max_iterations = 5;
  // Iterations stop when the corner moves at most this far, px (Algorithm 1: "while d > 0").
  double stop_tolerance = 0.05;
  // After the last iteration, a corner whose last move was farther than this (px) has not settled
  // and is dropped.
  double tolerance = 1.0;
  // Arms and bounds of the vertex refinement (curve_cornerness.h).
  CurveCornerOptions corner;

  void Check() const;
  // The weighted-stability settings these options imply.
  WeightedStabilityOptions StabilityOptions() const;
};

struct ConvergedCorner {
  // The feature position: the corner's vertex (apex refined by the arms), sub-pixel.
  cv::Point2f position;
  // The κ maximum on the curve.
  cv::Point2f apex;
  // The MSICS: integer level I (dark side {v <= I}) and the refined threshold of its curve.
  int level = 0;
  double threshold = 0.5;
  // Weighted ρ (1/px) and κ at the corner.
  double stability = 0.0;
  double cornerness = 0.0;
  Polarity polarity = Polarity::kNone;
  // The MSICS: ±half_length samples (1 px apart) around the corner, dark side on the left.
  std::vector<cv::Point2f> segment;
  // The whole curve traced in the block, resampled at 1 px (the reference of the next iteration).
  std::vector<cv::Point2f> curve;
  // Apexes of the other corners (κ maxima) on the curve within 2 half_length samples of this one:
  // corners closer together than the initialisation scale may have been seeded only once.
  std::vector<cv::Point2f> other_corners;
  // Iterations used (1 if the first re-detection did not move).
  int iterations = 0;
};

// Buffers reused across calls (one per thread).
struct ConvergenceWorkspace {
  WeightedStabilityEvaluator profile;
  CornernessWorkspace cornerness;
  std::vector<double> kappa;
  IsoCurve traced;
  std::vector<double> arc_lengths;
};

// One convergence iteration: weights centred on the point of `reference` (a polyline along the
// previous MSICS, dark side on the left) nearest to `position`; re-detects the MSICS nearest in
// level to `previous_level` and the corner on it nearest to `position`. False if there is no
// stable level, no curve or no corner within half_length px.
bool RedetectCorner(const cv::Mat& gray, const cv::Point2f& position,
                    const std::vector<cv::Point2f>& reference, double previous_level,
                    const ConvergenceOptions& options, ConvergedCorner* result,
                    ConvergenceWorkspace* workspace = nullptr);

// Iterates RedetectCorner from an initial corner (`position`: a point on the curve, e.g. an
// initial apex) until it stops moving (the apex moves at most stop_tolerance, its MSICS's level
// changing by at most one grey level), or returns to the state
// of two iterations before (a 2-cycle between two MSICSs: the more stable one is kept), or
// max_iterations are done. False if it is lost, or if its last move was farther than
// `tolerance` (it has not settled).
bool ConvergeCorner(const cv::Mat& gray, const cv::Point2f& position,
                    const std::vector<cv::Point2f>& reference, double level,
                    const ConvergenceOptions& options, ConvergedCorner* result,
                    ConvergenceWorkspace* workspace = nullptr);

// ConvergeCorner one iteration at a time, so that a caller can advance many corners in lock-step
// and stop those that reach a state another corner has already been in (their futures are the
// same). Start, then Step until it no longer returns kRunning; ConvergeCorner is exactly that.
class CornerConvergence {
 public:
  enum class Status { kRunning, kSettled, kLost };

  void Start(const cv::Point2f& position, std::vector<cv::Point2f> reference, double level);
  // One iteration (options checked by the caller). kSettled: result() holds the corner; kLost:
  // the corner is dropped.
  Status Step(const cv::Mat& gray, const ConvergenceOptions& options,
              ConvergenceWorkspace* workspace = nullptr);
  // The corner found by the last iteration (valid after kRunning).
  const ConvergedCorner& current() const { return last_; }
  ConvergedCorner& result() { return result_; }
  int iteration() const { return iteration_; }

 private:
  cv::Point2f current_;                 // apex the next iteration starts from
  std::vector<cv::Point2f> reference_;  // the seed's curve (first iteration only)
  double level_ = 0.0;                  // level of the previous MSICS
  int iteration_ = 0;
  ConvergedCorner last_;         // the result of the last iteration
  ConvergedCorner before_last_;  // and of the one before it
  ConvergedCorner result_;
};

}  // namespace comic::frontend
