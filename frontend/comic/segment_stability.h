// ρ_w (paper Eq. 1 with §2.1's Gaussian weights) of one iso-curve segment at its own level, as the
// direct search (comic_direct_detector.h) needs it: every κ maximum of a run is measured on its
// own segment, at its own level only. The measure is WeightedStabilityEvaluator's
// (iso_curve_stability.h: the band between Up and Down measured along normals of the segment,
// each strip weighted by its curve point's Gaussian weight), reduced to what one level needs:
//
//   * the segment lies on the level's curve, so the strips' length elements are the segment's own
//     chords (WeightedStabilityEvaluator finds the level's crossing on every normal first);
//   * only the Up (T + δ) and Down (T - δ) crossings are searched, outwards from the segment;
//   * the profiles are interpolated bilinearly (Algorithm 1's level choice needs the cubic's
//     smooth ρ(T) to refine a level below one grey level; the direct search only compares whole
//     levels, smoothed across the run).
//
//   SegmentStabilityEvaluator evaluator(options);     // weights computed once
//   double rho = evaluator.Evaluate(image, segment, centre_index, level + 0.5);
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace comic::frontend {

struct SegmentStabilityOptions {
  // Samples on either side of the centre in the segment, k (≈ 25 points per ICS, paper §3).
  int half_length = 12;
  // Standard deviation of the along-curve Gaussian weights, in samples (px).
  double sigma = 6.0;
  // δ in grey levels.
  double delta = 5.0;
  // Normals (strips of the band) every this many samples along the segment.
  int normal_step = 2;
  // Band widths are measured up to this far from the segment on each side, px (wider bands are
  // clipped, which only lowers ρ further).
  double max_distance = 6.0;
  // Step of the profile samples along the normals, px.
  double sample_step = 0.5;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

class SegmentStabilityEvaluator {
 public:
  explicit SegmentStabilityEvaluator(const SegmentStabilityOptions& options = {});

  // ρ_w = Σ w ℓ / Σ w ℓ (u_Up - u_Down) of `segment` (resampled at 1 px, dark side on the left)
  // around segment[centre], whose curve is at `threshold`; 0 when the segment has no strip (fewer
  // than 2 samples on either side of the centre). `gray` is the 8-bit image the curve was traced
  // in.
  double Evaluate(const cv::Mat& gray, const std::vector<cv::Point2f>& segment, int centre,
                  double threshold) const;

  const SegmentStabilityOptions& options() const { return options_; }

 private:
  SegmentStabilityOptions options_;
  std::vector<double> weights_;  // by |offset| from the centre, in samples
  int max_steps_ = 0;            // profile samples on each side
};

}  // namespace comic::frontend
