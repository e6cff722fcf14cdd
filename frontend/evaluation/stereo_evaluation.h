// Middlebury stereo evaluation of detectors and matchers at depth discontinuities (paper §5.2.2,
// Tables 1 and 2, the "Stereo" rows: M_score(1) and ResM_1 for Boundary / Non-Boundary / Overall).
//
//   io::MiddleburyPair pair = io::LoadMiddleburyFolder(dir, options.working_height);
//   StereoEvaluationOptions options;                       // the protocol below, issue defaults
//   StereoPairEvaluation result = EvaluateStereoPair(pair, options);
//   for (const StereoRun& run : result.runs)               // one run per target count N
//     for (const StereoMatching& m : run.matchings)        // one per (detector, matcher)
//       auto scores = ScoreAt(run.DetectionFor(m.method.detector), m, options.max_cost);
//
// Protocol (every number is a field of StereoEvaluationOptions):
//  1. The pair is used at the working size (height 700, paper §5.1), disparities scaled with the
//     images and masks resized with exact nearest-neighbour (io::LoadMiddleburyPair).
//  2. Left pixel classes: unknown disparity (GT = 0), occluded (nonocc = 0), boundary (disc = 255,
//     "near a depth discontinuity") and non-boundary (every other non-occluded pixel of known
//     disparity). Features on unknown or occluded pixels are excluded from the scores, and
//     counted. A feature's class is that of its rounded position.
//  3. Every detector returns all its candidates on both images; candidates whose 23x23 patch
//     does not fit are dropped; the response cut-off is equalised on the LEFT image so that N
//     features lie on valid (boundary or non-boundary) pixels (threshold_equalisation.h: ties at
//     the cut-off resolved by its documented rule), and the same cut-off is applied to the right
//     image (paper §5.1: "for this value of the threshold, features are detected on all other
//     images"). N = 0 in target_counts means "the count the reference detector (CoMIC) gives
//     at its own default threshold on valid pixels of the left image".
//  4. Matching (patch_matcher.h): the rectified-stereo gate (|Δy| ≤ row_tolerance, disparity in
//     [min_disparity, max_disparity]), 23x23 costs as mean squared grey differences, one-to-one
//     mutual best, then the SSD threshold T. All left detections take part in matching (they
//     compete for right partners as they would in use); only valid ones are scored.
//  5. A match is correct when the right feature lies within correct_tolerance pixels (Euclidean,
//     at the working size) of (x − d(x, y), y), d the GT disparity at the left feature.
//  6. Per region: detected = valid left features in the region; ResM_1 = correct accepted
//     matches; M_score(1) = ResM_1 / detected; precision = correct / accepted; share of all =
//     ResM_1 / detected overall (the normalisation under which Boundary + Non-Boundary =
//     Overall, which the paper's Table 1 appears to use — see docs/stereo_evaluation.md).
//  7. Matched precision: per matching, the largest T whose overall precision reaches a common
//     target (by default the precision of full-patch Harris at T = max_cost), so a split cost —
//     lower than the full cost by construction — cannot look better just by accepting more.
//  8. Repeatability per region: the share of valid left features with ANY right feature within
//     each tolerance of their true position (an upper bound for every matcher).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "frontend/detector_factory.h"
#include "frontend/evaluation/match_precision.h"
#include "frontend/evaluation/threshold_equalisation.h"
#include "frontend/matching/patch_matcher.h"
#include "io/datasets/middlebury.h"

namespace comic::frontend {

// What a left-image pixel is in the protocol.
enum class StereoPixelClass : int8_t { kUnknownDisparity, kOccluded, kBoundary, kNonBoundary };

// The regions scores are reported for, in the paper's column order.
enum class StereoRegion { kBoundary = 0, kNonBoundary = 1, kOverall = 2 };
inline constexpr int kNumStereoRegions = 3;
inline constexpr std::array<StereoRegion, kNumStereoRegions> kStereoRegions = {
    StereoRegion::kBoundary, StereoRegion::kNonBoundary, StereoRegion::kOverall};

// "boundary", "non-boundary", "overall".
const char* StereoRegionName(StereoRegion region);

// A detector and the patch cost it is matched with.
struct StereoMethod {
  std::string detector;  // one of DetectorNames()
  MatchCost cost = MatchCost::kFullPatch;

  // "comic/split", "harris/full".
  std::string Label() const;
  bool operator==(const StereoMethod& other) const {
    return detector == other.detector && cost == other.cost;
  }
};

// The paper's pairing (CoMIC with its split matcher, Algorithm 2; the baselines with the full
// patch) plus CoMIC with the like-sides variant and with the full patch, so that the effect of
// the detector and of the matcher can be told apart: comic/split, comic/like-sides, comic/full,
// harris/full, hessian/full, mser/full, fast/full.
std::vector<StereoMethod> DefaultStereoMethods();

// Parses "comic/split,harris/full" ("harris" alone means harris/full). Throws
// comic::Error(kInvalidArgument) for an unknown detector or cost, a repeated method or an empty
// list.
std::vector<StereoMethod> ParseStereoMethods(const std::string& list);

// Every protocol parameter, with the defaults.
struct StereoEvaluationOptions {
  // Height the pair is evaluated at (paper §5.1: 700). EvaluateStereoPair checks the pair has
  // it; 0 accepts any size (synthetic pairs).
  int working_height = 700;
  // Options of every detector (the `name` field is ignored). MSER's merge_radius (default 2 px)
  // merges nested regions' centroids closer than 2 px, which would otherwise compete for the
  // same match.
  DetectorOptions detectors;
  // The (detector, matcher) pairs evaluated.
  std::vector<StereoMethod> methods = DefaultStereoMethods();
  // Target counts N of valid left features, one run each; 0 = the reference detector's own
  // count (see count_reference).
  std::vector<int> target_counts = {0, 1000};
  // The detector whose count at its default threshold defines N = 0 (the issue: CoMIC at its
  // default ρ on valid pixels of the left image).
  std::string count_reference = "comic";
  // Stereo gate: largest row difference between partners, px. 1 px is needed because features
  // shift by a pixel after upscaling to the working size.
  double row_tolerance = 1.0;
  // Stereo gate: disparity range in px at the working size. max_disparity = 0 takes the pair's
  // largest GT disparity plus disparity_margin (so a correct partner at the largest disparity
  // is never gated out: the margin defaults to correct_tolerance).
  double min_disparity = 0.0;
  double max_disparity = 0.0;
  double disparity_margin = 1.5;
  // Split costs: fewest pixels a side pairing must share (of 529), patch_matcher.h.
  int min_side_overlap = 40;
  // The calibrated side cost's smallest side share and noise σ (patch_matcher.h).
  double min_side_fraction = PatchMatcherOptions{}.min_side_fraction;
  double side_noise_sigma = PatchMatcherOptions{}.side_noise_sigma;
  bool side_noise_from_pair = false;
  // The SSD threshold T: mean squared difference of 0–255 grey values (400 = RMS 20 levels).
  double max_cost = 400.0;
  // Further thresholds reported for sensitivity (T = ∞ is always reported too).
  std::vector<double> sensitivity_costs = {200.0, 400.0, 800.0};
  // A match is correct within this distance of the true position, px at the working size.
  double correct_tolerance = 1.5;
  // Tolerances of the repeatability table, px.
  std::vector<double> repeatability_tolerances = {1.0, 1.5, 2.5};
  // Matched precision: the common target is this method's overall precision at max_cost, unless
  // target_precision is in (0, 1], which then fixes it.
  StereoMethod precision_reference = {"harris", MatchCost::kFullPatch};
  double target_precision = 0.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The ground truth of a pair at its working size: pixel classes and true right positions.
class StereoGroundTruth {
 public:
  // Throws comic::Error(kInvalidArgument) for images that are not CV_8UC1 of one size, a
  // disparity map that is not CV_32FC1 of that size, or masks (when present) that are not
  // CV_8UC1 of that size. Without a nonocc mask no pixel is occluded; without a disc mask no
  // pixel is boundary.
  explicit StereoGroundTruth(const io::MiddleburyPair& pair);

  // Class of the pixel at the rounded position; outside the image: kUnknownDisparity.
  StereoPixelClass Classify(float x, float y) const;
  // (x − d, y) with d the GT disparity at the rounded position (meaningful for valid pixels).
  cv::Point2f TrueRightPosition(float x, float y) const;
  // CV_8UC1, 255 on boundary and non-boundary pixels, 0 elsewhere.
  const cv::Mat& ValidMask() const { return valid_; }
  const cv::Mat& ClassMap() const { return classes_; }  // CV_8SC1 of StereoPixelClass
  cv::Size size() const { return classes_.size(); }
  // Largest known GT disparity (occluded pixels included), px.
  double MaxDisparity() const { return max_disparity_; }
  bool has_disc() const { return has_disc_; }
  bool has_nonocc() const { return has_nonocc_; }
  // Pixels per class, indexed by StereoPixelClass.
  std::array<int, 4> PixelCounts() const;

 private:
  cv::Mat disparity_;
  cv::Mat classes_;
  cv::Mat valid_;
  double max_disparity_ = 0.0;
  bool has_disc_ = false;
  bool has_nonocc_ = false;
};

// Counts behind one region's scores.
struct RegionCounts {
  int detected = 0;  // valid left features in the region
  int accepted = 0;  // accepted matches whose left feature is in the region
  int correct = 0;   // of which correct: ResM_1

  // ResM_1 / detected; nullopt when nothing was detected (reported as "–").
  std::optional<double> MScore() const;
  // correct / accepted; nullopt when nothing was accepted.
  std::optional<double> Precision() const;
};
using RegionScores = std::array<RegionCounts, kNumStereoRegions>;

// One detector's thresholded features on the pair, classified.
struct StereoDetection {
  std::string detector;
  // The cut-off chosen on the left image (count = valid left features it keeps).
  ThresholdCut cut;
  int left_candidates = 0;   // candidates whose patch fits, before the cut
  int right_candidates = 0;  // same, right image
  FeatureSet left;           // kept: patch fits and response >= cut.min_response
  FeatureSet right;
  std::vector<StereoPixelClass> left_class;  // one per left feature
  // Valid left features per region (the M_score denominators).
  std::array<int, kNumStereoRegions> detected{};
  int unknown_disparity = 0;  // left features excluded: GT disparity unknown
  int occluded = 0;           // left features excluded: occluded (outside nonocc)
  // repeatable[k][region]: valid left features with a right feature within tolerance k of
  // their true position (k indexes StereoEvaluationOptions::repeatability_tolerances).
  std::vector<std::array<int, kNumStereoRegions>> repeatable;
};

// One (detector, matcher) pair's mutual-best matches with their ground-truth verdicts.
struct StereoMatching {
  StereoMethod method;
  // Every mutual-best match at any cost (T = ∞), ordered by left index.
  std::vector<PatchMatch> mutual;
  // Per mutual match: 1 correct, 0 wrong, -1 left feature excluded (unknown/occluded).
  std::vector<int8_t> verdict;
};

// What a common precision target gives one matching.
struct MatchedPrecision {
  // The largest T whose overall precision (valid left features) reaches the target; nullopt
  // when no T does (or there is no target).
  std::optional<PrecisionPoint> point;
  RegionScores scores;  // at point->max_cost (all zero counts except detected when no point)
};

// One target count N: every detector's features and every method's matches.
struct StereoRun {
  int requested_count = 0;  // as in options.target_counts (0 = the reference's count)
  int target_count = 0;     // N used
  std::vector<StereoDetection> detections;  // one per detector used by the methods
  std::vector<StereoMatching> matchings;    // one per method, in options.methods order
  // The matched-precision target; nullopt when the reference method accepts nothing at T.
  std::optional<double> target_precision;

  // Throws comic::Error(kInvalidArgument) if `detector` was not run.
  const StereoDetection& DetectionFor(const std::string& detector) const;
};

struct StereoPairEvaluation {
  std::string name;
  cv::Size size;                      // working size
  double resize_factor = 1.0;         // working / original width
  double disparity_scale = 0.0;       // stored GT value / disparity
  double max_gt_disparity = 0.0;      // px, working size
  double gate_min_disparity = 0.0;    // px, the stereo gate used
  double gate_max_disparity = 0.0;    // px
  std::array<int, 4> pixel_counts{};  // per StereoPixelClass
  int reference_count = 0;            // the reference detector's own count on valid left pixels
  std::vector<StereoRun> runs;        // one per options.target_counts entry
};

// Progress messages for a long run; library code never prints.
using StereoProgress = std::function<void(const std::string& message)>;

// Runs the whole protocol on one pair (detection once per detector and image, then one run per
// target count). Throws comic::Error(kInvalidArgument) for bad options or a pair that is not at
// options.working_height.
StereoPairEvaluation EvaluateStereoPair(const io::MiddleburyPair& pair,
                                        const StereoEvaluationOptions& options,
                                        const StereoProgress& progress = {});

// Builds a detection from already thresholded features (used by EvaluateStereoPair after the
// cut; tests feed synthetic features): drops features whose patch does not fit, classifies the
// left ones and measures repeatability at each tolerance.
StereoDetection MakeStereoDetection(const StereoGroundTruth& truth, const std::string& detector,
                                    const FeatureSet& left, const FeatureSet& right,
                                    const std::vector<double>& repeatability_tolerances);

// Matches a detection's features with `cost` under the protocol's gate and judges every
// mutual-best match. `gate_max_disparity` is the stereo gate's upper end (px).
StereoMatching MatchStereoDetection(const io::MiddleburyPair& pair, const StereoGroundTruth& truth,
                                    const StereoDetection& detection, MatchCost cost,
                                    const StereoEvaluationOptions& options,
                                    double gate_max_disparity);

// Region scores when every mutual-best match with cost <= max_cost is accepted
// (max_cost = +infinity: T = ∞).
RegionScores ScoreAt(const StereoDetection& detection, const StereoMatching& matching,
                     double max_cost);

// The matched-precision point of `matching` for `target_precision` in [0, 1].
MatchedPrecision ScoreAtPrecision(const StereoDetection& detection, const StereoMatching& matching,
                                  double target_precision);

}  // namespace comic::frontend
