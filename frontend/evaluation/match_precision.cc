#include "frontend/evaluation/match_precision.h"

#include <algorithm>
#include <numeric>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

void CheckSizes(const std::vector<PatchMatch>& matches, const std::vector<bool>& correct) {
  COMIC_CHECK(
      matches.size() == correct.size(), kInvalidArgument,
      "precision: " << correct.size() << " correctness flags for " << matches.size() << " matches");
}

}  // namespace

std::vector<PrecisionPoint> PrecisionCurve(const std::vector<PatchMatch>& matches,
                                           const std::vector<bool>& correct) {
  CheckSizes(matches, correct);
  std::vector<size_t> order(matches.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return matches[a].cost < matches[b].cost; });
  std::vector<PrecisionPoint> curve;
  int accepted = 0;
  int right = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    ++accepted;
    right += correct[order[k]] ? 1 : 0;
    const bool last_of_tie =
        k + 1 == order.size() || matches[order[k + 1]].cost != matches[order[k]].cost;
    if (!last_of_tie) continue;
    PrecisionPoint point;
    point.max_cost = matches[order[k]].cost;
    point.accepted = accepted;
    point.correct = right;
    point.precision = static_cast<double>(right) / accepted;
    curve.push_back(point);
  }
  return curve;
}

std::optional<PrecisionPoint> ThresholdForPrecision(const std::vector<PatchMatch>& matches,
                                                    const std::vector<bool>& correct,
                                                    double target_precision) {
  COMIC_CHECK(target_precision >= 0 && target_precision <= 1, kInvalidArgument,
              "precision: target must be in [0, 1], got " << target_precision);
  const std::vector<PrecisionPoint> curve = PrecisionCurve(matches, correct);
  for (auto it = curve.rbegin(); it != curve.rend(); ++it) {
    if (it->precision >= target_precision) return *it;
  }
  return std::nullopt;
}

PrecisionPoint PrecisionAt(const std::vector<PatchMatch>& matches, const std::vector<bool>& correct,
                           double max_cost) {
  CheckSizes(matches, correct);
  PrecisionPoint point;
  point.max_cost = max_cost;
  for (size_t k = 0; k < matches.size(); ++k) {
    if (matches[k].cost > max_cost) continue;
    ++point.accepted;
    point.correct += correct[k] ? 1 : 0;
  }
  point.precision = point.accepted > 0 ? static_cast<double>(point.correct) / point.accepted : 0.0;
  return point;
}

}  // namespace comic::frontend
