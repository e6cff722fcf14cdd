#include "frontend/matching/patch_matcher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "frontend/baselines/harris_detector.h"
#include "frontend/evaluation/threshold_equalisation.h"
#include "io/error.h"

namespace comic::frontend {
namespace {

// Smooth random texture with grey values spread around `mean`, reproducible by `seed`.
cv::Mat Texture(cv::Size size, uint64_t seed, double mean = 128, double amplitude = 60) {
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Scalar m, s;
  cv::meanStdDev(noise, m, s);
  cv::Mat out;
  noise.convertTo(out, CV_8U, amplitude / s[0], mean - amplitude * m[0] / s[0]);
  return out;
}

Feature At(float x, float y) {
  Feature f;
  f.x = x;
  f.y = y;
  return f;
}

TEST(PatchMatcher, FindsTheTrueShiftOfATranslatedTexturedImage) {
  const cv::Mat big = Texture({260, 220}, 1);
  const int dx = 7, dy = -4;
  const cv::Mat frame1 = big(cv::Rect(20, 20, 200, 160)).clone();
  // Content at (x, y) in frame 1 is at (x + dx, y + dy) in frame 2.
  const cv::Mat frame2 = big(cv::Rect(20 - dx, 20 - dy, 200, 160)).clone();
  const HarrisDetector harris;
  const FeatureSet f1 = ApplyThreshold(harris.Detect(frame1), 1.0f);
  const FeatureSet f2 = ApplyThreshold(harris.Detect(frame2), 1.0f);
  const std::vector<PatchMatch> matches = MatchFeatures(frame1, f1, frame2, f2, {});
  int correct = 0;
  for (const PatchMatch& m : matches) {
    const double ex = f2[m.index2].x - f1[m.index1].x - dx;
    const double ey = f2[m.index2].y - f1[m.index1].y - dy;
    if (std::hypot(ex, ey) < 1.0) {
      ++correct;
      EXPECT_LT(m.cost, 1.0f);  // identical pixels
    }
  }
  ASSERT_GE(matches.size(), 40u);
  EXPECT_GE(correct, static_cast<int>(0.95 * matches.size()))
      << correct << " of " << matches.size();
  // One-to-one.
  std::vector<int> used(f2.size(), 0);
  for (const PatchMatch& m : matches) EXPECT_EQ(++used[m.index2], 1);
}

// Frames of the paper's central case: a textured square object moving by (6, 3) against a
// background that is replaced between the frames. Features sit on the object's four corners and
// carry side masks (ic+ = object, ic− = background) as CoMIC's iso-curve would give them.
struct ChangingBackground {
  cv::Mat frame1, frame2;
  FeatureSet features1, features2;
};

ChangingBackground MakeChangingBackground() {
  const cv::Size size(160, 160);
  const cv::Mat object_texture = Texture({50, 50}, 11, 170, 40);
  ChangingBackground scene;
  const cv::Point shift(6, 3);
  for (int frame = 0; frame < 2; ++frame) {
    cv::Mat image = Texture(size, frame == 0 ? 21 : 22, 90, 40);  // a new background each frame
    const cv::Point origin = cv::Point(50, 50) + (frame == 0 ? cv::Point() : shift);
    const cv::Rect object(origin, object_texture.size());
    object_texture.copyTo(image(object));
    FeatureSet features;
    for (const cv::Point& corner :
         {object.tl(), cv::Point(object.br().x - 1, object.y),
          cv::Point(object.x, object.br().y - 1), object.br() - cv::Point(1, 1)}) {
      Feature f = At(static_cast<float>(corner.x), static_cast<float>(corner.y));
      f.side_mask.resize(kPatchSize * kPatchSize);
      for (int v = -kPatchRadius; v <= kPatchRadius; ++v) {
        for (int u = -kPatchRadius; u <= kPatchRadius; ++u) {
          f.side_mask[(v + kPatchRadius) * kPatchSize + (u + kPatchRadius)] =
              object.contains(corner + cv::Point(u, v)) ? PatchSide::kPlus : PatchSide::kMinus;
        }
      }
      features.push_back(std::move(f));
    }
    (frame == 0 ? scene.frame1 : scene.frame2) = image;
    (frame == 0 ? scene.features1 : scene.features2) = std::move(features);
  }
  return scene;
}

TEST(PatchMatcher, SplitMatcherSurvivesAChangingBackgroundWhereTheFullPatchFails) {
  const ChangingBackground scene = MakeChangingBackground();
  PatchMatcherOptions options;  // r = 20 px, T = 400
  for (MatchCost cost : {MatchCost::kSplitMinOfFourPairings, MatchCost::kSplitLikeSides}) {
    options.cost = cost;
    const auto matches =
        MatchFeatures(scene.frame1, scene.features1, scene.frame2, scene.features2, options);
    ASSERT_EQ(matches.size(), 4u) << MatchCostName(cost);
    for (const PatchMatch& m : matches) {
      EXPECT_EQ(m.index1, m.index2) << MatchCostName(cost);
      EXPECT_LT(m.cost, 1.0f);  // the object side is pixel-identical
    }
  }
  // The same features without side information: the full patch sees the new background.
  options.cost = MatchCost::kFullPatch;
  EXPECT_TRUE(
      MatchFeatures(scene.frame1, scene.features1, scene.frame2, scene.features2, options).empty());
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_GT(
        PatchCost(scene.frame1, scene.features1[i], scene.frame2, scene.features2[i], options),
        options.max_cost);
  }
  // A split mode on features without side masks is the full patch.
  FeatureSet plain1 = scene.features1, plain2 = scene.features2;
  for (Feature& f : plain1) f.side_mask.clear();
  for (Feature& f : plain2) f.side_mask.clear();
  options.cost = MatchCost::kSplitMinOfFourPairings;
  EXPECT_TRUE(MatchFeatures(scene.frame1, plain1, scene.frame2, plain2, options).empty());
}

TEST(PatchMatcher, SplitCostIsTheMinimumOverPairingsWithEnoughOverlap) {
  // Patch 1: left half 100, right half 200; patch 2: left 100, right 0. Sides: left = ic+.
  cv::Mat image1(40, 40, CV_8UC1, cv::Scalar(200)), image2(40, 40, CV_8UC1, cv::Scalar(0));
  image1(cv::Rect(0, 0, 20, 40)).setTo(100);
  image2(cv::Rect(0, 0, 20, 40)).setTo(100);
  Feature f = At(20, 20);  // window columns 9..31: 11 columns left of x = 20, 12 from it on
  f.side_mask.resize(kPatchSize * kPatchSize);
  for (int v = 0; v < kPatchSize; ++v) {
    for (int u = 0; u < kPatchSize; ++u) {
      f.side_mask[v * kPatchSize + u] = u < kPatchRadius ? PatchSide::kPlus : PatchSide::kMinus;
    }
  }
  PatchMatcherOptions options;
  options.cost = MatchCost::kSplitMinOfFourPairings;
  EXPECT_FLOAT_EQ(PatchCost(image1, f, image2, f, options), 0.0f);  // (ic+, ic+)
  options.cost = MatchCost::kFullPatch;
  EXPECT_FLOAT_EQ(PatchCost(image1, f, image2, f, options),
                  200.0f * 200.0f * (12 * 23) / (23 * 23));
  // Too little overlap: no pairing counts, no cost.
  options.cost = MatchCost::kSplitLikeSides;
  options.min_side_overlap = 12 * 23 + 1;
  EXPECT_TRUE(std::isinf(PatchCost(image1, f, image2, f, options)));
}

TEST(PatchMatcher, RadiusGateAroundThePredictedPosition) {
  const cv::Mat image = Texture({200, 120}, 5);
  const FeatureSet f1 = {At(40, 60)};
  const FeatureSet f2 = {At(40, 60), At(90, 60)};
  PatchMatcherOptions options;
  options.max_cost = std::numeric_limits<double>::infinity();
  auto candidates = ComputeCandidateCosts(image, f1, image, f2, options);
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_EQ(candidates[0].index2, 0);
  candidates = ComputeCandidateCosts(image, f1, image, f2, options,
                                     SearchRegions{{cv::Point2f(85, 62)}, {}});
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_EQ(candidates[0].index2, 1);
  // A per-feature radius wide enough for both.
  candidates = ComputeCandidateCosts(image, f1, image, f2, options, SearchRegions{{}, {60.0f}});
  EXPECT_EQ(candidates.size(), 2u);
  EXPECT_THROW(
      ComputeCandidateCosts(image, f1, image, f2, options, SearchRegions{{{0, 0}, {1, 1}}, {}}),
      Error);
  EXPECT_THROW(ComputeCandidateCosts(image, f1, image, f2, options, SearchRegions{{}, {1, 2}}),
               Error);
}

TEST(PatchMatcher, RectifiedStereoGateFollowsTheRowAndDisparityRange) {
  const cv::Mat left = Texture({200, 120}, 9);
  const FeatureSet f1 = {At(100, 60)};
  // Right-image candidates: d = 10 on the row, d = 10 two rows off, d = -5, d = 40.
  const FeatureSet f2 = {At(90, 60), At(90, 62), At(105, 60), At(60, 60.5f)};
  PatchMatcherOptions options;
  options.gate = CandidateGate::kRectifiedStereo;
  options.min_disparity = 0;
  options.max_disparity = 50;
  options.row_tolerance = 1;
  auto candidates = ComputeCandidateCosts(left, f1, left, f2, options);
  std::vector<int> found;
  for (const auto& c : candidates) found.push_back(c.index2);
  EXPECT_EQ(found, (std::vector<int>{0, 3}));
  options.max_disparity = 20;
  candidates = ComputeCandidateCosts(left, f1, left, f2, options);
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_EQ(candidates[0].index2, 0);
}

TEST(PatchMatcher, MutualBestIsOneToOneWithDeterministicTies) {
  const std::vector<PatchMatch> candidates = {{0, 0, 5.0f}, {0, 1, 1.0f}, {1, 1, 2.0f},
                                              {1, 2, 3.0f}, {2, 2, 3.0f}, {3, 3, 9.0f}};
  // 0 -> 1 (1.0) mutual; 1 -> 1 is beaten by 0 for column 1, so 1's best (1) is not mutual;
  // column 2: rows 1 and 2 tie at 3.0 -> row 1 wins, but row 1's best is column 1 -> no match;
  // row 2's best is column 2, column 2's best is row 1 -> no match; 3 <-> 3 mutual.
  const auto mutual = SelectMutualBest(candidates);
  ASSERT_EQ(mutual.size(), 2u);
  EXPECT_EQ(mutual[0].index1, 0);
  EXPECT_EQ(mutual[0].index2, 1);
  EXPECT_EQ(mutual[1].index1, 3);
  const auto accepted = ApplyCostThreshold(mutual, 5.0);
  ASSERT_EQ(accepted.size(), 1u);
  EXPECT_EQ(accepted[0].index1, 0);
  EXPECT_EQ(ApplyCostThreshold(mutual, 9.0).size(), 2u);  // cost <= T is accepted
}

TEST(PatchMatcher, NamesOptionsAndBadInput) {
  for (MatchCost cost :
       {MatchCost::kFullPatch, MatchCost::kSplitMinOfFourPairings, MatchCost::kSplitLikeSides}) {
    EXPECT_EQ(ParseMatchCost(MatchCostName(cost)), cost);
  }
  EXPECT_THROW(ParseMatchCost("ncc"), Error);
  PatchMatcherOptions options;
  options.radius = 0;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.min_side_overlap = 0;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.max_disparity = -1;
  EXPECT_THROW(options.Check(), Error);
  const cv::Mat image(50, 50, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(MatchFeatures(cv::Mat(50, 50, CV_8UC3), {}, image, {}, {}), Error);
  // Features whose patch does not fit are never matched.
  EXPECT_TRUE(ComputeCandidateCosts(image, {At(3, 3)}, image, {At(3, 3)}, {}).empty());
}

}  // namespace
}  // namespace comic::frontend
