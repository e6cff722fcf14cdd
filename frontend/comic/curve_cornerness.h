// Corners along an iso-curve (paper §2.2 and §3). The cornerness of sample t of a curve is
//
//   κ(t) = det Σ(t) / trace Σ(t)²,   Σ(t) = G_σ ⊗ [(P - P̄(t))(P - P̄(t))ᵀ]   (P̄(t) = G_σ ⊗ P)
//
// the shape of the distribution of the curve's points around t (Triggs 2004's measure, chosen by
// the paper because the number of points is constant): 0 on a straight line, 1/4 for an isotropic
// spread, about 0.2 at a right angle. The Gaussian along the curve is approximated, as the paper
// does (§3, "an average filter that runs through multiple iterations"), by three passes of a box
// filter, each O(1) per sample with running sums. Corners are the local maxima of κ along the
// curve (non-maximum suppression), refined below one sample by a parabola through κ at the
// maximum and its two neighbours.
//
// A blurred corner's iso-curve is rounded: its κ maximum (the apex) lies inside the true vertex,
// by ~0.8 px for a right angle under a blur of σ = 1 px. RefineCurveCorner therefore also
// intersects straight lines fitted to the two arms of the curve beyond the rounded part; on the
// level of steepest gradient (the one the stability measure selects) the arms are the object's
// edges and the intersection is the vertex. This is an addition to the paper (see
// docs/comic_detector.md), blended in only for clear corners, only where both arms are straight
// (the model it rests on: a polygon corner seen through a blur), and bounded in length. On
// curved or textured arms the intersection lies far out along the bisector and moves with every
// wiggle of the arms, so the corner stays at the apex, the paper's κ maximum.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

// Radius r of the box filter whose three passes approximate a Gaussian of standard deviation
// `sigma` (in samples): three passes of width 2r + 1 have variance r (r + 1).
int BoxRadiusForGaussian(double sigma);

// κ at every sample of a uniformly resampled curve. For an open curve the windows are truncated
// at the ends and renormalised, and samples with fewer than `min_support` samples on either side
// get κ = -1 (no corner may be reported there: its segment would be incomplete). A closed curve is
// filtered circularly.
std::vector<double> CurveCornerness(const std::vector<cv::Point2f>& points, bool closed,
                                    double sigma, int min_support);

// Buffers of CurveCornerness, reused across calls (one per thread).
struct CornernessWorkspace {
  std::vector<double> channels;
  std::vector<double> prefix;
  std::vector<double> filtered;
  std::vector<long> counts;
};
// The same, into *kappa, with reused buffers.
void CurveCornerness(const std::vector<cv::Point2f>& points, bool closed, double sigma,
                     int min_support, CornernessWorkspace* workspace, std::vector<double>* kappa);

// The same κ through triple cumulative sums: the three box passes are one difference of order
// three of the thrice-summed moments (box³ = Δ_w³ S³), computed in blocks of samples with a local
// origin so that the sums stay small. Equal to CurveCornerness up to rounding (|Δκ| < 1e-9 on
// the tests) except within 3r samples of an open curve's ends, where the window is truncated
// once (the triple box of the curve padded with nothing, renormalised) rather than after each
// pass; at under half the instructions. The direct search uses it; Algorithm 1 ("comic-paper")
// keeps CurveCornerness bit for bit.
void CurveCornernessCumulative(const std::vector<cv::Point2f>& points, bool closed, double sigma,
                               int min_support, CornernessWorkspace* workspace,
                               std::vector<double>* kappa);

// Indices of the local maxima of κ with κ >= min_cornerness: κ(t) must exceed every valid value
// in [t - radius, t) and be at least every value in (t, t + radius] (ties go to the first
// sample, so a plateau yields one maximum).
std::vector<int> CornernessMaxima(const std::vector<double>& kappa, bool closed, int radius,
                                  double min_cornerness);

struct CurveCornerOptions {
  // Arms used for the vertex: samples at distances [arm_begin, arm_end] from the apex, in
  // samples (px at unit spacing), on each side.
  double arm_begin = 4.0;
  double arm_end = 12.0;
  // Turning angles (degrees) between which the vertex correction is blended in linearly: none
  // below the first (nearly straight: the intersection is ill-conditioned and the rounding
  // negligible), all of it above the second.
  double blend_begin_degrees = 30.0;
  double blend_end_degrees = 60.0;
  // Longest correction from the apex to the vertex, in px.
  double max_vertex_shift = 3.0;
  // Straightness of the arms (the larger of their RMS distances from their fitted lines, px)
  // between which the correction is faded out linearly: all of it up to the first, none from the
  // second on. Iso-curves of blurred polygon edges are straight to ~0.02 px; the arms of corners
  // of real texture are not (median ~0.4 px on the Middlebury cones), and there the intersection
  // is an extrapolation that amplifies the arms' noise.
  double straight_arms_rms_begin = 0.03;
  double straight_arms_rms_end = 0.1;
};

struct CurveCorner {
  // Sub-sample position of the κ maximum along the curve (sample units).
  double index = 0.0;
  // The curve point at `index` (the apex of the rounded corner).
  cv::Point2f apex;
  // The apex moved towards the intersection of the arms (equal to apex when not applied).
  cv::Point2f vertex;
  // The larger of the two arms' RMS distances from their fitted lines, px (-1: no lines fitted).
  double arm_rms = -1.0;
  // κ at the parabola's peak.
  double cornerness = 0.0;
  // Signed turning angle of the curve at the corner in radians: > 0 when it turns towards its
  // left (dark) side, i.e. when the corner's interior (the angle < 180°) is the dark side.
  double turn_angle = 0.0;
  // kDark when the interior is the dark side (turn_angle > 0), kBright otherwise.
  Polarity polarity = Polarity::kNone;
};

// Refines the maximum at integer sample `index` of `kappa` (from CurveCornerness on `points`).
CurveCorner RefineCurveCorner(const std::vector<cv::Point2f>& points, bool closed,
                              const std::vector<double>& kappa, int index,
                              const CurveCornerOptions& options);

}  // namespace comic::frontend
