// Patch matching (paper §4, Algorithm 2): 23x23 patches compared by their squared grey-level
// differences, candidates restricted by a gate, one-to-one (mutual best) matching, one threshold.
//
//   PatchMatcherOptions options;                         // radius gate r = 20 px, full patch
//   options.cost = MatchCost::kSplitMinOfFourPairings;   // CoMIC: the patch split by its curve
//   std::vector<PatchMatch> matches = MatchFeatures(gray1, features1, gray2, features2, options);
//
// The three stages are exposed so a caller can sweep the threshold without re-matching:
//
//   auto candidates = ComputeCandidateCosts(gray1, features1, gray2, features2, options);
//   auto mutual = SelectMutualBest(candidates);          // every one-to-one match, any cost
//   auto accepted = ApplyCostThreshold(mutual, 400.0);   // the same as MatchFeatures at T = 400
//
// A frame matched to several others (the tracker) prepares its patches once (patch_set.h) and
// passes them instead of the image:
//
//   PatchSet patches1 = PreparePatches(gray1, features1, options);   // once per frame
//   auto candidates = ComputeCandidateCosts(features1, patches1, features2, patches2, options);
//
// Thresholding after the mutual-best selection gives the same matches as thresholding first: a
// match's cost is the lowest of its row and column, so removing costs above T never changes a
// surviving pair's best partner.
//
// Costs. Every cost is a MEAN squared difference of 0–255 grey values over the pixels compared,
// so one threshold T (e.g. 400 = an RMS difference of 20 grey levels) means the same for every
// mode:
//   kFullPatch              all 529 pixels (the baselines; paper Fig. 7a).
//   kSplitMinOfFourPairings Algorithm 2: each patch is split by its feature's side mask into ic+
//                           and ic− (Feature::side_mask); for each of the four pairings (a, b) of
//                           a side a of patch 1 with a side b of patch 2, the mean over the pixels
//                           lying in a in patch 1 AND in b in patch 2 (same window position); the
//                           cost is the minimum over pairings whose overlap has at least
//                           min_side_overlap pixels (d_min of Algorithm 2).
//   kSplitLikeSides         the same, over the pairings (ic+, ic+) and (ic−, ic−) only.
//   kCalibratedSides        issue 15: the lower of the full-patch cost and the object sides'
//                           cost, the latter first made to mean what a full-patch cost means
//                           (CalibratedSideCost: the same noise gives the same distribution
//                           whatever the pixel count). The object side is the side the corner
//                           points into (level_line_sides.h: CoMIC's polarity, otherwise the
//                           corner's geometry), so a contrast reversal still pairs object with
//                           object. The side cost is the mean over the UNION of the two object
//                           sides: where the two objects' shapes disagree, a pixel on one object
//                           and the other's background is compared too, so a flat side cannot
//                           match any flat region that merely contains it. The union must hold
//                           at least min_side_fraction of the patch. A pair in which either
//                           object side is unknown (a straight edge, no level line) costs the
//                           full patch, unless like_sides_without_object. Features without a
//                           side mask (every detector but CoMIC) get one from the level line
//                           through the point (ComputeLevelLineSides), only for this cost.
//   kTrackSides             issue 15, for tracking: kCalibratedSides for every pair the matcher
//                           sees (the same costs, bit for bit); the Tracker adds a memory along
//                           the track: a feature whose own match into its frame (from the frame
//                           before, at the tracker's threshold) cost its full patch is compared
//                           by its full patch only when it is matched on; a feature matched by
//                           its object side, or not matched into its frame, keeps its side. The
//                           paper's "prefer the side that keeps matching along the track": a
//                           feature on an occluding contour keeps losing its background from frame
//                           to frame, an interior feature that matched by its full patch has no
//                           background to lose, and its object side alone only adds chances to
//                           match the wrong neighbour cheaply.
// A split mode falls back to kFullPatch for a pair in which either feature has no side mask, so
// one options struct serves CoMIC and the baselines. Caution when comparing modes: a split cost
// averages over fewer pixels and takes a minimum over pairings, so it is lower than the
// full-patch cost of the same pair by construction, and at one fixed T it accepts more matches
// without matching better. Compare at equal precision where ground truth allows
// (match_precision.h).
//
// Gates. kRadius (video, paper §4): candidates within `radius` of the feature's position, or
// within a per-feature radius of a per-feature centre when the caller supplies SearchRegions
// (the tracker's motion prediction).
// kRectifiedStereo (Middlebury): |y2 − y1| ≤ row_tolerance and disparity d = x1 − x2 in
// [min_disparity, max_disparity], i.e. x2 = x1 − d (image 1 = left, image 2 = right).
//
// Patches are taken at the rounded feature positions; a feature whose patch does not fit in its
// image (PatchFits) is never matched.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/feature.h"
#include "frontend/matching/patch_set.h"

namespace comic::frontend {

enum class MatchCost {
  kFullPatch,
  kSplitMinOfFourPairings,
  kSplitLikeSides,
  kCalibratedSides,
  kTrackSides
};

// "full", "split", "like-sides", "calibrated", "track-sides" (the command-line names).
const char* MatchCostName(MatchCost cost);
// Throws comic::Error(kInvalidArgument) listing the valid names.
MatchCost ParseMatchCost(const std::string& name);

enum class CandidateGate { kRadius, kRectifiedStereo };

struct PatchMatcherOptions {
  CandidateGate gate = CandidateGate::kRadius;
  // kRadius: largest distance in pixels between a candidate and the feature's (predicted)
  // position (paper §4: r = 20 px at image height 700).
  double radius = 20.0;
  // kRectifiedStereo: largest row difference, in pixels.
  double row_tolerance = 1.0;
  // kRectifiedStereo: disparity range d = x1 − x2, in pixels.
  double min_disparity = 0.0;
  double max_disparity = 64.0;
  // How two patches are compared (see above).
  MatchCost cost = MatchCost::kFullPatch;
  // Split costs: fewest pixels two sides must share for their pairing to count (of 529).
  int min_side_overlap = 40;
  // kCalibratedSides: a side pairing counts only if the two sides cover at least this fraction of
  // the kPatchSize² pixels (a side of a few pixels says little about the match). 0.15 = 80 px: a
  // right-angle corner at the centre holds 11 x 11 = 121 px (23 %) once the curve's own pixels
  // are left out, so corners down to about 60° keep their object side.
  double min_side_fraction = 0.15;
  // kCalibratedSides: σ of the noise model, grey levels: per-pixel differences are taken as
  // N(0, 2σ²), so a mean of n squared differences has mean 2σ² and spread 2σ²·√(2/n). 2σ² = 800
  // puts the noise level at twice the protocol's T = 400. Chosen on Tsukuba and Cones against
  // σ = 10, which lets small sides through at low costs and loses boundary matches at matched
  // precision (docs/side_aware_matching.md).
  double side_noise_sigma = 20.0;
  // kCalibratedSides, kTrackSides: take σ from the pair itself instead (side_noise_sigma is then
  // the fallback for a pair without any match): 2σ² = the median full-patch cost of the pair's
  // mutual-best matches under the full patch (PairNoiseSigma). Most of those matches are correct,
  // and their residual (sensor noise, resampling, a sub-pixel offset, lighting) is what the noise
  // model describes, so σ follows the images instead of one number for every camera.
  bool side_noise_from_pair = false;
  // kCalibratedSides: when a feature's object side is unknown (a straight edge), also try the
  // like pairings (ic+, ic+) and (ic−, ic−), each over the union of its two sides; false = the
  // full patch only (the default: at σ = 10, Harris's boundary M_score(1) at matched precision on
  // Tsukuba was 34.2 % with them and 37.2 % without; an edge's side matches along the edge).
  bool like_sides_without_object = false;
  // SSD threshold T: a mutual-best match is accepted if its cost <= max_cost (mean squared
  // difference, grey levels²). +infinity accepts every mutual-best match.
  double max_cost = 400.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// Where to look in image 2 for each feature of image 1 (kRadius gate; the stereo gate uses only
// the centres). Each vector is empty (every feature's own position / options.radius) or holds one
// entry per feature of image 1.
struct SearchRegions {
  std::vector<cv::Point2f> centres;  // predicted positions in image 2, pixels
  std::vector<float> radii;          // search radii, pixels
};

// A pair of features, index1 into the first set, index2 into the second, with its cost.
struct PatchMatch {
  int index1 = -1;
  int index2 = -1;
  float cost = 0.0f;  // mean squared grey-level difference; +inf if no side pairing overlaps
};

// Every gated pair (index1, index2) with its cost, ordered by index1 then index2. Pairs with no
// valid side pairing (cost +inf) are left out. Throws comic::Error(kInvalidArgument) for images
// that are not CV_8UC1 or search regions of the wrong size.
std::vector<PatchMatch> ComputeCandidateCosts(const cv::Mat& gray1, const FeatureSet& features1,
                                              const cv::Mat& gray2, const FeatureSet& features2,
                                              const PatchMatcherOptions& options,
                                              const SearchRegions& search = {});

// The same from patches prepared once per frame (PreparePatches with these options, or any
// PatchSet for the full patch). Throws comic::Error(kInvalidArgument) if a set does not hold one
// patch per feature or lacks the sides the cost needs. Identical output to the overload above.
std::vector<PatchMatch> ComputeCandidateCosts(const FeatureSet& features1, const PatchSet& patches1,
                                              const FeatureSet& features2, const PatchSet& patches2,
                                              const PatchMatcherOptions& options,
                                              const SearchRegions& search = {});

// The side labels `cost` reads: kNone (full), kDetector (split, like-sides), kLevelLines
// (calibrated, track-sides).
PatchSides SidesFor(MatchCost cost);

// The patches of one frame's features as the matcher compares them under `options.cost`.
PatchSet PreparePatches(const cv::Mat& gray, const FeatureSet& features,
                        const PatchMatcherOptions& options);

// One-to-one matching: the pairs that are each other's lowest-cost candidate (ties broken by the
// lower index), ordered by index1.
std::vector<PatchMatch> SelectMutualBest(const std::vector<PatchMatch>& candidates);

// The matches with cost <= max_cost, order kept.
std::vector<PatchMatch> ApplyCostThreshold(const std::vector<PatchMatch>& matches, double max_cost);

// ComputeCandidateCosts, SelectMutualBest and ApplyCostThreshold(options.max_cost) in one call.
std::vector<PatchMatch> MatchFeatures(const cv::Mat& gray1, const FeatureSet& features1,
                                      const cv::Mat& gray2, const FeatureSet& features2,
                                      const PatchMatcherOptions& options,
                                      const SearchRegions& search = {});

// MatchFeatures from patches prepared once per frame (see ComputeCandidateCosts).
std::vector<PatchMatch> MatchFeatures(const FeatureSet& features1, const PatchSet& patches1,
                                      const FeatureSet& features2, const PatchSet& patches2,
                                      const PatchMatcherOptions& options,
                                      const SearchRegions& search = {});

// side_noise_from_pair: σ with 2σ² = the median cost of `full_patch_mutual` (a pair's mutual-best
// matches under the full patch; the upper median of an even count), or `fallback` if there is no
// match or the median is 0.
double PairNoiseSigma(const std::vector<PatchMatch>& full_patch_mutual, double fallback);

// kCalibratedSides: the full-patch (kPatchSize² pixels) mean squared difference that is as likely
// under the noise model (σ = noise_sigma) as a mean of `mean_squared_difference` over `pixels`
// pixels, by the Wilson–Hilferty cube-root approximation of the χ² distribution: with
// u = mean / 2σ², z = (u^⅓ − (1 − 2/9n)) / √(2/9n), the result is 2σ²·(1 − 2/9N + z·√(2/9N))³
// (0 if the bracket is negative). The identity for pixels = N; monotone in the mean.
double CalibratedSideCost(double mean_squared_difference, int pixels, double noise_sigma);

// True for the costs that compare the object sides of level-line patches (kCalibratedSides,
// kTrackSides).
bool IsCalibratedCost(MatchCost cost);

// The cost of one pair under `options.cost` (no gate), +inf if a patch does not fit or no side
// pairing overlaps enough.
float PatchCost(const cv::Mat& gray1, const Feature& feature1, const cv::Mat& gray2,
                const Feature& feature2, const PatchMatcherOptions& options);
// The same for patch i of `patches1` and patch j of `patches2` (prepared as ComputeCandidateCosts
// needs them).
float PatchCost(const PatchSet& patches1, size_t i, const PatchSet& patches2, size_t j,
                const PatchMatcherOptions& options);

}  // namespace comic::frontend
