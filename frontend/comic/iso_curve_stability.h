// Stability of iso-curve segments (paper §2.1, Eq. 1):
//
//   ρ(ICS(I, p, s), δ) = len(ICS) / ΔA,
//
// ΔA the area between Up(ICS, δ) and Down(ICS, δ), the iso-curves at I ± δ near the segment,
// connected at their end points. 1/ρ is the mean displacement of the curve per 2δ grey levels, so
// a large ρ is a curve that stays put when the intensity changes. A segment is maximally stable
// (an MSICS) when its ρ exceeds that of the segments at I - 1 and I + 1.
//
// Two forms, one per stage of the search (Algorithm 1):
//
// * Initialisation (unweighted, per block): ρ of each component of the block's ComponentTree,
//   len = its boundary in the block, ΔA = Area(component at the Up level) - Area(main descendant at
//   the Down level), MSER-style. With threshold T = I + 0.5 the Up level is ceil(T + δ) - 1 and the
//   Down level ceil(T - δ) - 1, so the band is the 2δ grey levels centred on the curve.
//
// * Convergence (Gaussian-weighted, at one corner): along-curve 1-D Gaussian weights from p on a
//   reference segment (±k samples at 1 px), every band element taking the weight of its nearest
//   curve point (paper §2.1). The band is measured at sub-pixel resolution along the normals of
//   the reference segment: on the normal of sample i, the Up and Down curves are crossed at
//   u_i(T + δ) and u_i(T - δ) (first crossing of the bilinearly interpolated intensity from the
//   segment, in the image interpolated by cubic convolution). The level-T curve crosses the
//   normals at Q_i = P_i + u_i(T) n_i; ℓ_i is its length element there (half the chords to the
//   neighbouring crossings). The strip of sample i has width u_i(T + δ) - u_i(T - δ), length ℓ_i
//   and weight w_i, so ΔA_w = Σ w_i ℓ_i (u_i(T + δ) - u_i(T - δ)) and len_w = Σ w_i ℓ_i. One pass
//   over the normal profiles gives ρ_w for every level whose curve passes near p. Counting whole
//   band pixels instead would quantise ΔA to ~1 px per column on a sharp edge and make ρ(I) a
//   staircase whose maximum jumps between levels; measured this way ρ(I) is smooth, its maximum
//   can be refined below one grey level, and the level (hence the corner) is chosen
//   consistently.
#pragma once

#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "frontend/comic/component_tree.h"
#include "frontend/comic/image_component_tree.h"

namespace comic::frontend {

// Grey levels bounding the band of the curve at threshold `threshold` (= I + 0.5 for level I):
// the band is the pixels with Down < v <= Up.
int UpLevel(double threshold, double delta);
int DownLevel(double threshold, double delta);

// ---------------------------------------------------------------------------------------------
// Initialisation stage.

// Unweighted ρ of tree node `node` at level `level` (Level(node) <= level < Level(parent)):
// Perimeter(node) / max(1, ΔA). The block's own grey values are used (inverted for upper sets).
double ComponentStability(const ComponentTree& tree, int node, int level, double delta);
// The same on the tree of a whole image (the direct search).
double ComponentStability(const ImageComponentTree& tree, int node, int level, double delta);

struct StableComponent {
  int node = -1;
  // Level (of the tree's values) at which ρ is maximal within the node's span; the middle of a
  // plateau of equal values.
  int level = 0;
  double stability = 0.0;
};

// The block's maximally stable components: nodes with Perimeter >= min_perimeter whose best ρ
// over the levels they span is >= min_stability and is a local maximum along the lineage: above
// ρ of the main line at the `level_radius` levels below the span, at least ρ of the ancestors at
// the `level_radius` levels above it (level_radius = 1: the paper's I ± 1). In processing order.
std::vector<StableComponent> FindMaximallyStableComponents(const ComponentTree& tree, double delta,
                                                           int min_perimeter, double min_stability,
                                                           int level_radius = 1);
std::vector<StableComponent> FindMaximallyStableComponents(const ImageComponentTree& tree,
                                                           double delta, int min_perimeter,
                                                           double min_stability,
                                                           int level_radius = 1);

// ---------------------------------------------------------------------------------------------
// Convergence stage.

// The cubic convolution (Catmull-Rom, Keys a = -0.5, border replicated) that samples the normal
// profiles near the curve, at (x, y) in pixel-centre coordinates of an 8-bit image. Exposed so
// that its vectorised form can be checked against the formula.
float InterpolateProfileCubic(const cv::Mat& gray, double x, double y);
// The bilinear interpolation that samples the profiles beyond cubic_distance (coordinates clamped
// to the image), exposed for the same reason: its fast path inside the image is checked against
// the clamped formula.
float InterpolateProfileBilinear(const cv::Mat& gray, double x, double y);

struct WeightedStabilityOptions {
  // Samples on either side of p in the segment, k (≈ 25 points per ICS, paper §3).
  int half_length = 12;
  // Standard deviation of the along-curve Gaussian weights, in samples (px).
  double sigma = 6.0;
  // δ in grey levels.
  double delta = 5.0;
  // Normals (strips of the band) every this many samples along the segment.
  int normal_step = 2;
  // Half-length of each normal profile in px: band widths are measured up to this far from the
  // segment on each side (wider bands are clipped, which only lowers ρ further).
  double max_distance = 6.0;
  // Profiles are interpolated by cubic convolution up to this far from the segment, px, and
  // bilinearly beyond.
  double cubic_distance = 2.0;
  // Step of the profile samples along the normals, in px.
  double sample_step = 0.5;
  // Levels are evaluated whose curve crosses the central normal within this distance of p, px.
  double search_radius = 3.0;
  // Levels whose ρ_w is within this fraction of the maximum's count as equally stable
  // (SelectMaximallyStableLevel).
  double run_tolerance = 0.10;
  // Maxima of ρ_w separated by a relative dip shallower than this are ripples of one curve
  // (SelectMaximallyStableLevel).
  double ripple_tolerance = 0.25;
  // How far along the normals the two sides' intensities are read for middle_level, px (beyond
  // the ~2.5σ reach of a blurred edge).
  double side_distance = 3.0;
};

// ρ_w as a function of the level near a point, every level evaluated. level(i) = first_level + i.
struct StabilityProfile {
  int first_level = 0;
  std::vector<double> stability;  // ρ_w
  std::vector<double> length;     // len_w
  std::vector<double> band_area;  // ΔA_w
  // Where each level's curve crosses the central normal (signed distance from p along the
  // normal towards the bright side), px.
  std::vector<double> centre_offset;
  // p and the unit normal at p (towards the bright side).
  cv::Point2d centre;
  cv::Point2d normal;
  // The level halfway between the intensities on the two sides of the curve: over the normals, the
  // Gaussian-weighted median of the mid-points between the darkest value on the dark side and the
  // brightest on the bright side within side_distance, fractional.
  double middle_level = 0.0;
  int NumLevels() const { return static_cast<int>(stability.size()); }
};

// The weighted stability around one point of a reference curve, evaluated level by level on
// demand and memoised: choosing the MSICS (SelectMaximallyStableLevel) needs only the levels
// around the previous one, not all the 100-200 levels whose curves pass near a corner. Every
// value is the one ComputeWeightedStabilityProfile gives for that level, bit for bit. Reuse one
// object per thread: it keeps its buffers.
class WeightedStabilityEvaluator {
 public:
  // Sets up the normals of the reference segment, their intensity profiles (read on demand), the
  // middle level and the range of levels (see ComputeWeightedStabilityProfile). Returns false when
  // no level's curve crosses the central normal within search_radius. `gray` must outlive the
  // evaluation.
  bool Prepare(const cv::Mat& gray, const std::vector<cv::Point2f>& reference, int centre_index,
               const WeightedStabilityOptions& options);
  // The same without the middle level (middle_level() is then 0): for a caller that needs ρ_w
  // of given levels only (the direct search), the ~170 profile samples it reads are not needed.
  bool PrepareWithoutMiddleLevel(const cv::Mat& gray, const std::vector<cv::Point2f>& reference,
                                 int centre_index, const WeightedStabilityOptions& options);

  int first_level() const { return first_level_; }
  int NumLevels() const { return num_levels_; }
  double middle_level() const { return middle_level_; }
  cv::Point2d centre() const { return points_[centre_row_]; }
  cv::Point2d normal() const { return normals_[centre_row_]; }
  // ρ_w of level first_level() + l, l in [0, NumLevels()).
  double Stability(int l) { return Evaluate(l).stability; }
  // The same value, bit for bit, for a caller that asks for this one level only: the crossings
  // of its three thresholds (I + 0.5 and I + 0.5 ± δ) alone are computed, not the windows of
  // neighbouring thresholds that Stability() prepares for the level choice.
  double SingleLevelStability(int l);
  // Where the curve of level first_level() + l crosses the central normal, px (as
  // StabilityProfile::centre_offset).
  double CentreOffset(int l);
  // Levels evaluated since Prepare.
  int NumEvaluated() const { return num_evaluated_; }
  // Evaluates every level into `profile`.
  void Fill(StabilityProfile* profile);

 private:
  struct LevelValues {
    double stability = -1.0;  // < 0: not evaluated yet
    double length = 0.0;
    double band_area = 0.0;
  };
  const LevelValues& Evaluate(int l);
  // The level's length (the weighted length of its curve) and band area (the weighted area between
  // Up and Down) into `values`, stability their ratio: curve_crossing(r, &valid) is where the
  // level's curve crosses normal r and whether it does, band_width(r) the band's width there (read
  // only where the curve has length). Evaluate and SingleLevelStability differ only in where they
  // read the crossings.
  template <class CurveCrossing, class BandWidth>
  void IntegrateBand(CurveCrossing curve_crossing, BandWidth band_width, LevelValues* values);
  bool PrepareImpl(const cv::Mat& gray, const std::vector<cv::Point2f>& reference, int centre_index,
                   const WeightedStabilityOptions& options, bool with_middle_level);
  // Signed crossing of threshold index j (threshold first_threshold_ + j) on normal r, and
  // whether the profile ended first (clipped).
  double Crossing(int r, int j, bool* clipped) {
    if (j < computed_begin_ || j >= computed_end_) ComputeCrossings(j);
    const size_t index = static_cast<size_t>(r) * num_thresholds_ + j;
    *clipped = clipped_[index] != 0;
    return crossings_[index];
  }
  // Extends the window of threshold indices whose crossings are computed (on every normal) to
  // include j, with some slack: crossings are found a window at a time, for the thresholds the
  // level choice reaches.
  void ComputeCrossings(int j);
  // Sample k of normal r's profile (read on first use).
  float Sample(int r, int k);
  float ReadSample(int r, int k);
  // exp(-offset² / 2σ²), the along-curve weight of a normal `offset` samples from the centre.
  double Weight(int offset, double sigma);

  const cv::Mat* gray_ = nullptr;
  WeightedStabilityOptions options_;
  int num_normals_ = 0;
  int centre_row_ = 0;
  int m_ = 0;            // index of the centre sample of a normal profile
  int cubic_reach_ = 0;  // samples from the centre read by cubic convolution
  int first_level_ = 0;
  int num_levels_ = 0;
  int delta_steps_ = 0;  // ceil(δ)
  int num_thresholds_ = 0;
  double first_threshold_ = 0.0;
  double weight_sum_ = 0.0;
  double middle_level_ = 0.0;
  int num_evaluated_ = 0;
  std::vector<cv::Point2d> points_;
  std::vector<cv::Point2d> normals_;
  std::vector<double> weights_;
  std::vector<float> samples_;     // num_normals_ x (2m + 1), read on demand
  std::vector<double> crossings_;  // num_normals_ x num_thresholds_
  std::vector<uint8_t> clipped_;
  int computed_begin_ = 0;  // crossings are computed for threshold indices in [begin, end)
  int computed_end_ = 0;
  std::vector<LevelValues> levels_;
  std::vector<double> elements_;
  std::vector<std::pair<double, double>> mids_;
  std::vector<double> single_crossings_;  // SingleLevelStability: 3 x num_normals_
  std::vector<uint8_t> single_clipped_;
  double weight_sigma_ = -1.0;        // σ of weight_table_
  std::vector<double> weight_table_;  // by offset 0, -1, 1, -2, 2, ...; < 0: not computed
};

// Computes the profile around reference[centre_index]. `reference` is a segment of iso-curve
// resampled at 1 px, dark side on the left; it must extend at least 1 sample on either side of
// the centre. Normals are taken every normal_step samples within half_length of the centre.
// Levels range over those whose curve crosses the central normal within search_radius of p,
// plus one on each side (for the local-maximum test). Returns false when no level does.
bool ComputeWeightedStabilityProfile(const cv::Mat& gray, const std::vector<cv::Point2f>& reference,
                                     int centre_index, const WeightedStabilityOptions& options,
                                     StabilityProfile* profile);

struct StableLevel {
  // The threshold at which the MSICS's curve is traced (fractional: the level refined below one
  // grey level) and the integer level I with threshold in (I, I + 1] (its dark side is
  // {v <= I}).
  double threshold = 0.5;
  int level = 0;
  // ρ_w of the MSICS.
  double stability = 0.0;
};

// Among the local maxima of the profile (ρ_w(I) > ρ_w(I - 1) and >= ρ_w(I + 1), not at the ends)
// picks the one whose level is nearest to `previous_level` (ties: larger ρ_w, then lower level),
// the "MSICS similar to the previous one" of Algorithm 1. Maxima separated by a dip shallower
// than `ripple_tolerance` (relative to the lower one) are ripples of one curve's stability, not
// different curves: the choice climbs to the highest of them. All levels of the run around the peak
// with ρ_w >= (1 - run_tolerance) ρ_peak are then equally stable (ρ is nearly flat across the steep
// part of a sharp edge, where ripples and the corner's geometry would decide), and the level
// chosen is the profile's middle_level clamped to that run: the middle of the edge. A run of one
// level is refined by the vertex of a parabola through ρ_w at I - 1, I, I + 1. Returns false if
// there is no maximum.
bool SelectMaximallyStableLevel(const StabilityProfile& profile, double previous_level,
                                double run_tolerance, double ripple_tolerance,
                                StableLevel* selected);
// The same choice, evaluating only the levels it looks at (the nearest maxima, the dips towards
// their neighbours while a climb is still possible, the run).
bool SelectMaximallyStableLevel(WeightedStabilityEvaluator* evaluator, double previous_level,
                                double run_tolerance, double ripple_tolerance,
                                StableLevel* selected);

}  // namespace comic::frontend
