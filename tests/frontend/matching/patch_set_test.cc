#include "frontend/matching/patch_set.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "frontend/baselines/harris_detector.h"
#include "frontend/evaluation/threshold_equalisation.h"
#include "frontend/matching/level_line_sides.h"
#include "frontend/matching/patch_matcher.h"
#include "io/core/error.h"

namespace comic::frontend {
namespace {

Feature At(float x, float y) {
  Feature f;
  f.x = x;
  f.y = y;
  return f;
}

// Bright and dark rectangles on a textured background: corners with level-line sides, edges
// without an object side, and texture.
cv::Mat Scene(uint64_t seed, int shift) {
  cv::Mat noise(160, 200, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Mat gray;
  noise.convertTo(gray, CV_8U, 25, 110);
  gray(cv::Rect(40 + shift, 30, 50, 40)).setTo(220);
  gray(cv::Rect(110 + shift, 80, 45, 50)).setTo(20);
  return gray;
}

TEST(PatchSet, HoldsThePatchTheSidesAndTheObjectSideOfEveryFeature) {
  cv::Mat gray(100, 100, CV_8UC1, cv::Scalar(40));
  gray(cv::Rect(30, 30, 40, 40)).setTo(200);
  Feature with_mask = At(60, 60);
  with_mask.side_mask.assign(kPatchPixels, PatchSide::kMinus);
  with_mask.side_mask[7] = PatchSide::kPlus;
  with_mask.polarity = Polarity::kDark;
  const FeatureSet features = {At(30, 30), At(5, 50), with_mask, At(50, 50)};

  const PatchSet level_lines(gray, features, PatchSides::kLevelLines);
  ASSERT_EQ(level_lines.size(), 4u);
  EXPECT_EQ(level_lines.sides(), PatchSides::kLevelLines);
  // The square's corner: its level line, the square (ic+) as the object.
  const LevelLineSides corner = ComputeLevelLineSides(gray, features[0]);
  EXPECT_TRUE(level_lines[0].valid);
  EXPECT_TRUE(level_lines[0].has_sides);
  EXPECT_EQ(level_lines[0].object_side, PatchSide::kPlus);
  for (int k = 0; k < kPatchPixels; ++k) {
    const int u = k % kPatchSize - kPatchRadius, v = k / kPatchSize - kPatchRadius;
    EXPECT_EQ(level_lines.Values(0)[k], gray.at<uint8_t>(30 + v, 30 + u));
    EXPECT_EQ(level_lines[0].values[k], gray.at<uint8_t>(30 + v, 30 + u));
    EXPECT_EQ(level_lines.SideWords(0, PatchSide::kPlus)[k],
              corner.mask[k] == PatchSide::kPlus ? -1 : 0);
    EXPECT_EQ(level_lines.SideWords(0, PatchSide::kMinus)[k],
              corner.mask[k] == PatchSide::kMinus ? -1 : 0);
  }
  // Off the image: not matched.
  EXPECT_FALSE(level_lines[1].valid);
  // The detector's own mask and polarity are kept.
  EXPECT_TRUE(level_lines[2].has_sides);
  EXPECT_EQ(level_lines[2].object_side, PatchSide::kMinus);
  EXPECT_EQ(level_lines.SideWords(2, PatchSide::kPlus)[7], -1);
  EXPECT_EQ(level_lines.SideWords(2, PatchSide::kPlus)[8], 0);
  // Inside the flat square: no level line, no sides, zero side words.
  EXPECT_TRUE(level_lines[3].valid);
  EXPECT_FALSE(level_lines[3].has_sides);
  for (int k = 0; k < kPatchPixels; ++k) {
    EXPECT_EQ(level_lines.SideWords(3, PatchSide::kPlus)[k], 0);
    EXPECT_EQ(level_lines.SideWords(3, PatchSide::kMinus)[k], 0);
  }

  // kDetector: only the detector's own masks; kNone: grey values only.
  const PatchSet detector(gray, features, PatchSides::kDetector);
  EXPECT_FALSE(detector[0].has_sides);
  EXPECT_TRUE(detector[2].has_sides);
  EXPECT_EQ(detector[2].sides[7], PatchSide::kPlus);
  const PatchSet none(gray, features, PatchSides::kNone);
  EXPECT_FALSE(none[2].has_sides);
  EXPECT_EQ(none[0].values, level_lines[0].values);
}

TEST(PatchSet, PreparedPatchesGiveExactlyTheCostsOfTheImagesForEveryCost) {
  const cv::Mat gray1 = Scene(3, 0), gray2 = Scene(3, 4);
  const HarrisDetector harris;
  const FeatureSet f1 = ApplyThreshold(harris.Detect(gray1), 1.0f);
  const FeatureSet f2 = ApplyThreshold(harris.Detect(gray2), 1.0f);
  ASSERT_GE(f1.size(), 20u);
  for (MatchCost cost : {MatchCost::kFullPatch, MatchCost::kSplitMinOfFourPairings,
                         MatchCost::kSplitLikeSides, MatchCost::kCalibratedSides}) {
    PatchMatcherOptions options;
    options.cost = cost;
    const std::vector<PatchMatch> direct = ComputeCandidateCosts(gray1, f1, gray2, f2, options);
    const PatchSet p1 = PreparePatches(gray1, f1, options);
    const PatchSet p2 = PreparePatches(gray2, f2, options);
    const std::vector<PatchMatch> prepared = ComputeCandidateCosts(f1, p1, f2, p2, options);
    ASSERT_EQ(direct.size(), prepared.size()) << MatchCostName(cost);
    for (size_t k = 0; k < direct.size(); ++k) {
      EXPECT_EQ(direct[k].index1, prepared[k].index1);
      EXPECT_EQ(direct[k].index2, prepared[k].index2);
      EXPECT_EQ(direct[k].cost, prepared[k].cost);  // bit for bit
      EXPECT_EQ(direct[k].cost,
                PatchCost(gray1, f1[direct[k].index1], gray2, f2[direct[k].index2], options));
    }
    EXPECT_EQ(MatchFeatures(f1, p1, f2, p2, options).size(),
              MatchFeatures(gray1, f1, gray2, f2, options).size());
  }
}

TEST(PatchSet, APatchWhoseSidesAreDroppedCostsTheFullPatch) {
  // A bright corner in front of a background that changes: the calibrated cost uses the object
  // side; once the sides of one feature are dropped, its pairs cost the full patch.
  cv::Mat gray1(100, 100, CV_8UC1, cv::Scalar(40));
  gray1(cv::Rect(30, 30, 40, 40)).setTo(200);
  cv::Mat gray2 = gray1.clone();
  gray2(cv::Rect(0, 0, 30, 100)).setTo(120);
  const FeatureSet f = {At(30, 30)};
  PatchMatcherOptions calibrated;
  calibrated.cost = MatchCost::kCalibratedSides;
  PatchMatcherOptions full;
  PatchSet p1 = PreparePatches(gray1, f, calibrated);
  const PatchSet p2 = PreparePatches(gray2, f, calibrated);
  const float full_cost = ComputeCandidateCosts(f, p1, f, p2, full).at(0).cost;
  EXPECT_LT(ComputeCandidateCosts(f, p1, f, p2, calibrated).at(0).cost, full_cost);
  p1.DropSides(0);
  EXPECT_FALSE(p1[0].has_sides);
  EXPECT_EQ(ComputeCandidateCosts(f, p1, f, p2, calibrated).at(0).cost, full_cost);
  EXPECT_THROW(p1.DropSides(1), Error);
}

TEST(PatchSet, TheMatcherRefusesPatchesWithoutTheSidesItsCostNeedsOrOfAnotherCount) {
  const cv::Mat gray = Scene(5, 0);
  const FeatureSet f = {At(60, 50), At(100, 100)};
  PatchMatcherOptions calibrated;
  calibrated.cost = MatchCost::kCalibratedSides;
  const PatchSet plain(gray, f, PatchSides::kNone);
  const PatchSet sides = PreparePatches(gray, f, calibrated);
  EXPECT_THROW(ComputeCandidateCosts(f, plain, f, sides, calibrated), Error);
  EXPECT_THROW(ComputeCandidateCosts(f, sides, f, plain, calibrated), Error);
  EXPECT_NO_THROW(ComputeCandidateCosts(f, sides, f, sides, calibrated));
  // The full patch reads any set's grey values.
  EXPECT_NO_THROW(ComputeCandidateCosts(f, sides, f, plain, PatchMatcherOptions()));
  const FeatureSet one = {f[0]};
  EXPECT_THROW(ComputeCandidateCosts(one, sides, f, sides, calibrated), Error);
  EXPECT_THROW(PatchSet(cv::Mat(), f, PatchSides::kNone), Error);
  EXPECT_EQ(SidesFor(MatchCost::kFullPatch), PatchSides::kNone);
  EXPECT_EQ(SidesFor(MatchCost::kSplitLikeSides), PatchSides::kDetector);
  EXPECT_EQ(SidesFor(MatchCost::kCalibratedSides), PatchSides::kLevelLines);
}

}  // namespace
}  // namespace comic::frontend
