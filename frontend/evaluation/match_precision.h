// Precision of thresholded matches against ground truth, and the threshold that reaches a target
// precision: how matchers whose costs are not on the same footing (a split-patch cost is lower
// than the full-patch cost of the same pair by construction, see patch_matcher.h) are compared
// fairly — at equal precision rather than at one fixed threshold.
//
//   std::vector<PatchMatch> mutual = SelectMutualBest(ComputeCandidateCosts(...));
//   std::vector<bool> correct = ...;            // e.g. within 1 px of the epipolar line
//   auto point = ThresholdForPrecision(mutual, correct, 0.9);
//   if (point) ApplyCostThreshold(mutual, point->max_cost);   // the matcher at 90 % precision
#pragma once

#include <optional>
#include <vector>

#include "frontend/matching/patch_matcher.h"

namespace comic::frontend {

// What a threshold T accepts: the matches with cost <= max_cost.
struct PrecisionPoint {
  double max_cost = 0.0;   // T
  int accepted = 0;        // matches with cost <= T
  int correct = 0;         // of which correct
  double precision = 0.0;  // correct / accepted (0 when nothing is accepted)
};

// The point of every distinct cost among `matches`, ascending (so each point accepts all ties at
// its cost). `correct[k]` says whether matches[k] is right. Throws comic::Error(kInvalidArgument)
// if the sizes differ.
std::vector<PrecisionPoint> PrecisionCurve(const std::vector<PatchMatch>& matches,
                                           const std::vector<bool>& correct);

// The largest threshold whose precision is at least `target_precision` (so the one accepting the
// most matches at that precision; precision need not fall monotonically with T), or nullopt if
// no threshold reaches it. Throws comic::Error(kInvalidArgument) for sizes that differ or a
// target outside [0, 1].
std::optional<PrecisionPoint> ThresholdForPrecision(const std::vector<PatchMatch>& matches,
                                                    const std::vector<bool>& correct,
                                                    double target_precision);

// The point of one threshold (all matches with cost <= max_cost).
PrecisionPoint PrecisionAt(const std::vector<PatchMatch>& matches, const std::vector<bool>& correct,
                           double max_cost);

}  // namespace comic::frontend
