#include "frontend/evaluation/match_precision.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

const std::vector<PatchMatch> kMatches = {{0, 0, 10.f}, {1, 1, 20.f}, {2, 2, 20.f},
                                          {3, 3, 30.f}, {4, 4, 40.f}, {5, 5, 50.f}};
const std::vector<bool> kCorrect = {true, true, false, true, true, false};

TEST(MatchPrecision, CurveHasOnePointPerDistinctCost) {
  const auto curve = PrecisionCurve(kMatches, kCorrect);
  ASSERT_EQ(curve.size(), 5u);
  EXPECT_EQ(curve[1].max_cost, 20.0);
  EXPECT_EQ(curve[1].accepted, 3);  // both matches at 20 count
  EXPECT_EQ(curve[1].correct, 2);
  EXPECT_DOUBLE_EQ(curve[3].precision, 4.0 / 5.0);
  EXPECT_DOUBLE_EQ(curve[4].precision, 4.0 / 6.0);
}

TEST(MatchPrecision, ThresholdForPrecisionTakesTheLargestQualifyingThreshold) {
  // Precisions: 1, 2/3, 3/4, 4/5, 4/6. Target 0.75 -> T = 40 (0.8), not T = 10.
  auto point = ThresholdForPrecision(kMatches, kCorrect, 0.75);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->max_cost, 40.0);
  EXPECT_EQ(point->accepted, 5);
  point = ThresholdForPrecision(kMatches, kCorrect, 1.0);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->max_cost, 10.0);
  EXPECT_FALSE(ThresholdForPrecision(kMatches, std::vector<bool>(6, false), 0.5).has_value());
  EXPECT_FALSE(ThresholdForPrecision({}, {}, 0.5).has_value());
}

TEST(MatchPrecision, PrecisionAtOneThreshold) {
  const PrecisionPoint point = PrecisionAt(kMatches, kCorrect, 25.0);
  EXPECT_EQ(point.accepted, 3);
  EXPECT_EQ(point.correct, 2);
  EXPECT_EQ(PrecisionAt(kMatches, kCorrect, 5.0).precision, 0.0);
  EXPECT_THROW(PrecisionAt(kMatches, {true}, 5.0), Error);
  EXPECT_THROW(ThresholdForPrecision(kMatches, kCorrect, 1.5), Error);
}

}  // namespace
}  // namespace comic::frontend
