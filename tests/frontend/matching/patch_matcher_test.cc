#include "frontend/matching/patch_matcher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "frontend/baselines/harris_detector.h"
#include "frontend/evaluation/threshold_equalisation.h"
#include "frontend/matching/level_line_sides.h"
#include "io/core/error.h"

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
       {MatchCost::kFullPatch, MatchCost::kSplitMinOfFourPairings, MatchCost::kSplitLikeSides,
        MatchCost::kCalibratedSides, MatchCost::kTrackSides}) {
    EXPECT_EQ(ParseMatchCost(MatchCostName(cost)), cost);
  }
  EXPECT_EQ(ParseMatchCost("calibrated"), MatchCost::kCalibratedSides);
  EXPECT_EQ(ParseMatchCost("track-sides"), MatchCost::kTrackSides);
  EXPECT_TRUE(IsCalibratedCost(MatchCost::kTrackSides));
  EXPECT_FALSE(IsCalibratedCost(MatchCost::kSplitLikeSides));
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

// ---- The calibrated side cost (issue 15) ----

TEST(CalibratedSideCost, IsTheIdentityOnTheFullPatchAndMonotoneInTheMean) {
  constexpr int kFull = kPatchSize * kPatchSize;
  for (double m : {0.0, 50.0, 400.0, 1600.0, 5000.0}) {
    EXPECT_DOUBLE_EQ(CalibratedSideCost(m, kFull, 28.0), m);
  }
  double previous = -1;
  for (double m = 0; m <= 4000; m += 25) {
    const double c = CalibratedSideCost(m, 132, 28.0);
    EXPECT_GE(c, previous) << m;
    previous = c;
  }
  // Below the noise level 2σ² a mean over fewer pixels is weaker evidence, so it costs more in
  // full-patch units; at 2σ² every pixel count gives about 2σ².
  EXPECT_GT(CalibratedSideCost(400, 132, 28.0), 400);
  EXPECT_GT(CalibratedSideCost(400, 132, 28.0), CalibratedSideCost(400, 264, 28.0));
  EXPECT_NEAR(CalibratedSideCost(2 * 28.0 * 28.0, 132, 28.0), 2 * 28.0 * 28.0, 0.01 * 1568);
  EXPECT_THROW(CalibratedSideCost(10, 0, 28.0), Error);
  EXPECT_THROW(CalibratedSideCost(10, 100, 0.0), Error);
}

// Two 23x23 images of independent Gaussian noise σ around 128 on the first `side_pixels` pixels
// (row-major), which are the object side (ic+, polarity kBright) of both features; the rest of
// the patches differ by 255, so neither the full patch nor another side can match.
struct NoisePair {
  cv::Mat image1, image2;
  Feature feature1, feature2;
};

NoisePair MakeNoisePair(int side_pixels, double sigma, cv::RNG& rng) {
  NoisePair pair;
  pair.image1.create(kPatchSize, kPatchSize, CV_8UC1);
  pair.image2.create(kPatchSize, kPatchSize, CV_8UC1);
  Feature f = At(kPatchRadius, kPatchRadius);
  f.polarity = Polarity::kBright;
  f.side_mask.assign(kPatchSize * kPatchSize, PatchSide::kMinus);
  for (int k = 0; k < kPatchSize * kPatchSize; ++k) {
    const bool side = k < side_pixels;
    if (side) f.side_mask[k] = PatchSide::kPlus;
    pair.image1.data[k] = side ? cv::saturate_cast<uint8_t>(128 + rng.gaussian(sigma)) : uint8_t{0};
    pair.image2.data[k] =
        side ? cv::saturate_cast<uint8_t>(128 + rng.gaussian(sigma)) : uint8_t{255};
  }
  pair.feature1 = f;
  pair.feature2 = f;
  return pair;
}

TEST(CalibratedSideCost, EqualNoiseOnSidesOfDifferentSizesPassesOneThresholdEquallyOften) {
  constexpr double kSigma = 20.0;
  constexpr int kTrials = 4000;
  PatchMatcherOptions options;
  options.side_noise_sigma = kSigma;
  options.min_side_fraction = 0.2;
  // The threshold: the 5 % quantile of the cost of pure noise over the whole patch.
  cv::RNG rng(15);
  std::vector<float> full_costs;
  for (int t = 0; t < kTrials; ++t) {
    const NoisePair p = MakeNoisePair(kPatchSize * kPatchSize, kSigma, rng);
    options.cost = MatchCost::kCalibratedSides;
    full_costs.push_back(PatchCost(p.image1, p.feature1, p.image2, p.feature2, options));
  }
  std::sort(full_costs.begin(), full_costs.end());
  const double threshold = full_costs[kTrials / 20];
  for (int side : {110, 180, 264, 400}) {
    int calibrated_pass = 0, split_pass = 0;
    for (int t = 0; t < kTrials; ++t) {
      const NoisePair p = MakeNoisePair(side, kSigma, rng);
      options.cost = MatchCost::kCalibratedSides;
      calibrated_pass +=
          PatchCost(p.image1, p.feature1, p.image2, p.feature2, options) <= threshold;
      options.cost = MatchCost::kSplitLikeSides;
      split_pass += PatchCost(p.image1, p.feature1, p.image2, p.feature2, options) <= threshold;
    }
    const double calibrated_rate = static_cast<double>(calibrated_pass) / kTrials;
    const double split_rate = static_cast<double>(split_pass) / kTrials;
    // Within a few percent of the full patch's 5 % whatever the side's size ...
    EXPECT_NEAR(calibrated_rate, 0.05, 0.02) << side << " pixels";
    // ... where the plain mean over the side (Algorithm 2's) passes far more often on small
    // sides (its spread grows as 1/√n).
    if (side <= 180) {
      EXPECT_GT(split_rate, 0.12) << side << " pixels";
    }
  }
}

// An object (bright textured quadrant x, y >= 32) in front of background `background` (textured),
// and a feature at its corner without a side mask (as a Harris point has none).
cv::Mat ObjectInFront(uint64_t object_seed, uint64_t background_seed, double background_mean) {
  cv::Mat image = Texture({64, 64}, background_seed, background_mean, 8);
  Texture({32, 32}, object_seed, 150, 12).copyTo(image(cv::Rect(32, 32, 32, 32)));
  return image;
}

TEST(CalibratedSideCost, AnObjectCornerMatchesOnItsObjectSideAndNotOnItsBackgroundSide) {
  const Feature corner = At(32, 32);
  PatchMatcherOptions options;  // T = 400
  const cv::Mat view1 = ObjectInFront(1, 2, 50);
  // The same object before a new dark background, and before a bright one (the object is then
  // the darker side: the polarity follows the object, not the brightness).
  for (double background : {80.0, 230.0}) {
    const cv::Mat view2 = ObjectInFront(1, 3, background);
    options.cost = MatchCost::kFullPatch;
    const float full = PatchCost(view1, corner, view2, corner, options);
    options.cost = MatchCost::kCalibratedSides;
    const float calibrated = PatchCost(view1, corner, view2, corner, options);
    EXPECT_GT(full, options.max_cost) << background;
    // The object side is pixel-identical: accepted at T, where the full patch is not. (Not 0: a
    // perfect side of ~110 px is only as strong as a full patch of a few hundred, see
    // CalibratedSideCost.)
    EXPECT_LT(calibrated, options.max_cost) << background;
    EXPECT_LT(calibrated, 0.6f * full) << background;
  }
  // A different object before the same background: the background side alone would match
  // (Algorithm 2's minimum over pairings takes it), the calibrated cost does not use it.
  const cv::Mat other = ObjectInFront(7, 2, 50);
  Feature masked1 = corner, masked2 = corner;
  masked1.side_mask = ComputeLevelLineSides(view1, corner).mask;
  masked2.side_mask = ComputeLevelLineSides(other, corner).mask;
  ASSERT_FALSE(masked1.side_mask.empty());
  ASSERT_FALSE(masked2.side_mask.empty());
  options.cost = MatchCost::kSplitMinOfFourPairings;
  const float split = PatchCost(view1, masked1, other, masked2, options);
  options.cost = MatchCost::kFullPatch;
  const float full = PatchCost(view1, corner, other, corner, options);
  options.cost = MatchCost::kCalibratedSides;
  const float calibrated = PatchCost(view1, corner, other, corner, options);
  EXPECT_LT(split, 1.0f);               // the background side is pixel-identical
  EXPECT_GT(calibrated, 0.99f * full);  // no cheaper than the full patch: the object side differs
  EXPECT_GT(calibrated, 20 * std::max(split, 1.0f));
}

TEST(CalibratedSideCost, FeaturesWithoutSidesCostTheFullPatch) {
  const cv::Mat a = Texture({64, 64}, 4), b = Texture({64, 64}, 5);
  const cv::Mat flat(64, 64, CV_8UC1, cv::Scalar(100));
  PatchMatcherOptions options;
  options.cost = MatchCost::kFullPatch;
  const float full = PatchCost(flat, At(32, 32), b, At(32, 32), options);
  options.cost = MatchCost::kCalibratedSides;
  EXPECT_EQ(PatchCost(flat, At(32, 32), b, At(32, 32), options), full);  // flat: no level line
  options.cost = MatchCost::kFullPatch;
  const float textured = PatchCost(a, At(30, 30), b, At(31, 33), options);
  options.cost = MatchCost::kCalibratedSides;
  EXPECT_LE(PatchCost(a, At(30, 30), b, At(31, 33), options), textured);  // never above full
  options.min_side_fraction = 1.5;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.side_noise_sigma = 0;
  EXPECT_THROW(options.Check(), Error);
}

TEST(CalibratedSideCost, PairNoiseSigmaIsHalfTheMedianFullPatchCostOfThePairsMatches) {
  auto matches = [](std::vector<float> costs) {
    std::vector<PatchMatch> out;
    for (size_t k = 0; k < costs.size(); ++k) out.push_back({static_cast<int>(k), 0, costs[k]});
    return out;
  };
  EXPECT_DOUBLE_EQ(PairNoiseSigma(matches({800, 100, 200}), 20), 10.0);  // 2σ² = 200
  EXPECT_DOUBLE_EQ(PairNoiseSigma(matches({300, 100, 800, 200}), 20), std::sqrt(150.0));
  EXPECT_DOUBLE_EQ(PairNoiseSigma({}, 20), 20.0);                  // no match: the fallback
  EXPECT_DOUBLE_EQ(PairNoiseSigma(matches({0, 0, 5}), 17), 17.0);  // identical images

  // side_noise_from_pair is the calibrated cost at that σ, bit for bit.
  const cv::Mat a = Texture({120, 100}, 8);
  cv::Mat b;
  cv::GaussianBlur(a, b, cv::Size(3, 3), 0.8);
  const HarrisDetector harris;
  const FeatureSet f1 = ApplyThreshold(harris.Detect(a), 1.0f);
  const FeatureSet f2 = ApplyThreshold(harris.Detect(b), 1.0f);
  PatchMatcherOptions full;
  const double sigma =
      PairNoiseSigma(SelectMutualBest(ComputeCandidateCosts(a, f1, b, f2, full)), 20.0);
  EXPECT_GT(sigma, 0.5);
  EXPECT_LT(sigma, 20.0);
  PatchMatcherOptions from_pair;
  from_pair.cost = MatchCost::kCalibratedSides;
  from_pair.side_noise_from_pair = true;
  PatchMatcherOptions fixed = from_pair;
  fixed.side_noise_from_pair = false;
  fixed.side_noise_sigma = sigma;
  const std::vector<PatchMatch> x = ComputeCandidateCosts(a, f1, b, f2, from_pair);
  const std::vector<PatchMatch> y = ComputeCandidateCosts(a, f1, b, f2, fixed);
  ASSERT_EQ(x.size(), y.size());
  ASSERT_GT(x.size(), 10u);
  for (size_t k = 0; k < x.size(); ++k) EXPECT_EQ(x[k].cost, y[k].cost);
}

TEST(CalibratedSideCost, ObjectSidesOfDifferentShapesAreComparedOverTheirUnion) {
  // Flat images: object 200 on background 40. Patch 1's object is the quadrant x, y >= 32;
  // patch 2's reaches 6 rows higher. Where both are object the values agree exactly, so a cost
  // over the shared pixels alone (Algorithm 2) is 0; over the union the 6 x 12 pixels that are
  // object in one patch and background in the other differ by 160.
  cv::Mat image1(64, 64, CV_8UC1, cv::Scalar(40)), image2(64, 64, CV_8UC1, cv::Scalar(40));
  image1(cv::Rect(32, 32, 32, 32)).setTo(200);
  image2(cv::Rect(32, 26, 32, 38)).setTo(200);
  auto masked = [](const cv::Mat& image) {
    Feature f = At(32, 32);
    f.polarity = Polarity::kBright;
    f.side_mask.resize(kPatchSize * kPatchSize);
    for (int v = 0; v < kPatchSize; ++v) {
      for (int u = 0; u < kPatchSize; ++u) {
        const bool object = image.at<uint8_t>(32 - kPatchRadius + v, 32 - kPatchRadius + u) == 200;
        f.side_mask[v * kPatchSize + u] = object ? PatchSide::kPlus : PatchSide::kMinus;
      }
    }
    return f;
  };
  const Feature f1 = masked(image1), f2 = masked(image2);
  PatchMatcherOptions options;
  options.cost = MatchCost::kSplitLikeSides;
  EXPECT_LT(PatchCost(image1, f1, image2, f2, options), 1.0f);
  options.cost = MatchCost::kFullPatch;
  const float full = PatchCost(image1, f1, image2, f2, options);
  EXPECT_NEAR(full, 72 * 160.0 * 160.0 / 529, 1.0);
  options.cost = MatchCost::kCalibratedSides;
  EXPECT_EQ(PatchCost(image1, f1, image2, f2, options), full);  // the side is no cheaper
  EXPECT_GT(full, options.max_cost);
}

}  // namespace
}  // namespace comic::frontend
