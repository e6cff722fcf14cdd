#include "frontend/comic/iso_curve_stability.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/core.hpp>
#include <random>

#include "frontend/comic/iso_curve.h"
#include "tests/frontend/synthetic_images.h"

namespace comic::frontend {
namespace {

// The cubic convolution written out in scalar form, in the order the sampler documents: weights
// in float, each row's sum from column 0 to 3, then the rows from 0 to 3.
float ReferenceCubic(const cv::Mat& gray, double x, double y) {
  auto weights = [](float t, float* w) {
    const float t2 = t * t, t3 = t2 * t;
    w[0] = -0.5f * t3 + t2 - 0.5f * t;
    w[1] = 1.5f * t3 - 2.5f * t2 + 1.0f;
    w[2] = -1.5f * t3 + 2.0f * t2 + 0.5f * t;
    w[3] = 0.5f * t3 - 0.5f * t2;
  };
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  float wx[4], wy[4];
  weights(static_cast<float>(x - x0), wx);
  weights(static_cast<float>(y - y0), wy);
  float sum = 0.0f;
  for (int j = 0; j < 4; ++j) {
    const uint8_t* row = gray.ptr<uint8_t>(std::clamp(y0 - 1 + j, 0, gray.rows - 1));
    float line = 0.0f;
    for (int i = 0; i < 4; ++i) line += wx[i] * row[std::clamp(x0 - 1 + i, 0, gray.cols - 1)];
    sum += wy[j] * line;
  }
  return sum;
}

TEST(IsoCurveStability, ProfileCubicIsTheScalarFormulaBitForBit) {
  // Random texture with full-range values (255s and 0s next to each other stress the products),
  // sampled inside, on the border band and outside the image.
  std::mt19937 random(7);
  cv::Mat gray(37, 41, CV_8UC1);
  for (int y = 0; y < gray.rows; ++y) {
    for (int x = 0; x < gray.cols; ++x)
      gray.at<uint8_t>(y, x) = random() % 4 == 0 ? 255 : random() % 256;
  }
  std::uniform_real_distribution<double> xs(-3.0, gray.cols + 2.0), ys(-3.0, gray.rows + 2.0);
  int differences = 0;
  for (int i = 0; i < 20000; ++i) {
    const double x = i < 100 ? 5 + i * 0.25 : xs(random);  // exact and quarter-pixel positions too
    const double y = i < 100 ? 7.0 : ys(random);
    const float expected = ReferenceCubic(gray, x, y);
    const float actual = InterpolateProfileCubic(gray, x, y);
    // Bits, not values: any reordering of the float operations would show here (+0 and -0 are
    // the same sample).
    if (std::memcmp(&expected, &actual, sizeof(float)) != 0 && !(expected == 0 && actual == 0)) {
      ++differences;
    }
  }
  EXPECT_EQ(differences, 0);
  // And it interpolates: exact at pixel centres.
  EXPECT_EQ(InterpolateProfileCubic(gray, 10.0, 12.0), gray.at<uint8_t>(12, 10));
}

// Bilinear interpolation with the coordinates clamped to the image, in scalar form: each row
// interpolated along x in float, then the two rows along y.
float ReferenceBilinear(const cv::Mat& gray, double x, double y) {
  x = std::clamp(x, 0.0, gray.cols - 1.0);
  y = std::clamp(y, 0.0, gray.rows - 1.0);
  const int x0 = std::min(static_cast<int>(x), std::max(0, gray.cols - 2));
  const int y0 = std::min(static_cast<int>(y), std::max(0, gray.rows - 2));
  const int x1 = std::min(x0 + 1, gray.cols - 1);
  const int y1 = std::min(y0 + 1, gray.rows - 1);
  const float tx = static_cast<float>(x - x0);
  const float ty = static_cast<float>(y - y0);
  auto at = [&](int yy, int xx) { return gray.at<uint8_t>(yy, xx); };
  const float top = at(y0, x0) + tx * (at(y0, x1) - at(y0, x0));
  const float bottom = at(y1, x0) + tx * (at(y1, x1) - at(y1, x0));
  return top + ty * (bottom - top);
}

TEST(IsoCurveStability, ProfileBilinearIsTheClampedFormulaBitForBit) {
  std::mt19937 random(11);
  for (const cv::Size size : {cv::Size(29, 23), cv::Size(1, 9), cv::Size(9, 1)}) {
    cv::Mat gray(size, CV_8UC1);
    for (int y = 0; y < gray.rows; ++y) {
      for (int x = 0; x < gray.cols; ++x) gray.at<uint8_t>(y, x) = random() % 256;
    }
    std::uniform_real_distribution<double> xs(-3.0, gray.cols + 2.0), ys(-3.0, gray.rows + 2.0);
    int differences = 0;
    for (int i = 0; i < 20000; ++i) {
      // Random points, and points just inside and on the last row and column.
      double x = xs(random), y = ys(random);
      if (i % 10 == 0) x = gray.cols - 1 - 1e-9 * (i % 3);
      if (i % 10 == 1) y = gray.rows - 1 - 1e-9 * (i % 3);
      const float expected = ReferenceBilinear(gray, x, y);
      const float actual = InterpolateProfileBilinear(gray, x, y);
      if (std::memcmp(&expected, &actual, sizeof(float)) != 0) ++differences;
    }
    EXPECT_EQ(differences, 0) << size;
    EXPECT_EQ(InterpolateProfileBilinear(gray, 0.0, 0.0), gray.at<uint8_t>(0, 0));
    EXPECT_EQ(InterpolateProfileBilinear(gray, gray.cols + 5.0, gray.rows + 5.0),
              gray.at<uint8_t>(gray.rows - 1, gray.cols - 1));
  }
}

TEST(IsoCurveStability, UpAndDownLevelsBoundABandOfTwoDeltaLevels) {
  EXPECT_EQ(UpLevel(100.5, 5), 105);
  EXPECT_EQ(DownLevel(100.5, 5), 95);  // band 96..105
  EXPECT_EQ(UpLevel(100.5, 2.5), 102);
  EXPECT_EQ(DownLevel(100.5, 2.5), 97);  // band 98..102
}

TEST(IsoCurveStability, UnweightedStabilityOfARampIsItsGradientOverTwoDelta) {
  cv::Mat block(10, 20, CV_8UC1);
  for (int x = 0; x < 20; ++x) block.col(x).setTo(5 * x);  // 5 grey levels per px
  ComponentTree tree;
  tree.Build(block, false);
  const int node = tree.AncestorAtLevel(tree.NodeOfPixel(tree.PixelIndex(0, 0)), 47);
  EXPECT_EQ(tree.Perimeter(node), 10);
  EXPECT_DOUBLE_EQ(ComponentStability(tree, node, 47, 2.5), 1.0);  // 5 / (2 * 2.5)
  EXPECT_DOUBLE_EQ(ComponentStability(tree, node, 47, 5.0), 0.5);  // 5 / (2 * 5)
}

TEST(IsoCurveStability, MaximallyStableComponentsOfAnEdgeLieOnItsSteepPart) {
  const test::Polygon right{{{20.3, -10}, {60, -10}, {60, 60}, {20.3, 60}}, 200};
  const cv::Mat block = test::RenderPolygons(test::FlatBackground({40, 30}, 50), {right}, 1.0);
  ComponentTree tree;
  tree.Build(block, false);
  const auto stable = FindMaximallyStableComponents(tree, 2.5, 25, 0.0);
  ASSERT_FALSE(stable.empty());
  bool on_edge = false;
  for (const StableComponent& c : stable) {
    EXPECT_EQ(tree.Perimeter(c.node), 30);  // the edge crosses all 30 rows
    on_edge |= c.level > 70 && c.level < 180;
  }
  EXPECT_TRUE(on_edge);
}

// The level-`threshold` curve through `near`, resampled at 1 px with the centre sample nearest to
// `near`; *centre receives its index.
std::vector<cv::Point2f> Reference(const cv::Mat& image, double threshold, cv::Point2f near,
                                   int* centre) {
  const IsoCurveTracer tracer(image, cv::Rect(0, 0, image.cols, image.rows), threshold);
  CurveEdge seed;
  EXPECT_TRUE(tracer.FindNearestCrossing(near, 3, &seed));
  IsoCurve curve;
  tracer.Trace(seed, 1000, &curve);
  const double s = ProjectOntoPolyline(curve.points, false, near);
  return ResamplePolyline(curve.points, false, 1.0, s, 20, 20, centre);
}

TEST(IsoCurveStability, WeightedStabilityPeaksInTheMiddleOfABlurredEdge) {
  const test::Polygon bright{{{30.4, -10}, {90, -10}, {90, 90}, {44.1, 90}}, 200};
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({80, 80}, 50), {bright}, 1.0);
  int centre = 0;
  const auto reference = Reference(image, 90.5, {37.0f, 40.0f}, &centre);
  StabilityProfile profile;
  ASSERT_TRUE(ComputeWeightedStabilityProfile(image, reference, centre, {}, &profile));
  EXPECT_NEAR(profile.middle_level + 0.5, 125.0, 2.0);
  StableLevel level;
  ASSERT_TRUE(SelectMaximallyStableLevel(profile, 90.0, 0.10, 0.25, &level));
  EXPECT_NEAR(level.threshold, 125.0, 3.0);
  EXPECT_EQ(level.level, static_cast<int>(std::ceil(level.threshold)) - 1);
  // ρ = mean displacement per 2δ levels: the edge's steepest gradient, 150 φ(0) / σ ≈ 57 grey
  // levels per px (σ ≈ 1.04 with the pixel's area), over 2δ = 10.
  EXPECT_NEAR(level.stability, 5.7, 0.6);
}

TEST(IsoCurveStability, AffineIntensityChangesKeepTheMiddleOfTheEdge) {
  const test::Polygon bright{{{30.4, -10}, {90, -10}, {90, 90}, {44.1, 90}}, 200};
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({80, 80}, 50), {bright}, 1.0);
  cv::Mat changed;
  image.convertTo(changed, CV_8U, 0.8, 20);
  int centre = 0;
  const auto reference = Reference(changed, 90.5, {37.0f, 40.0f}, &centre);
  StabilityProfile profile;
  ASSERT_TRUE(ComputeWeightedStabilityProfile(changed, reference, centre, {}, &profile));
  StableLevel level;
  ASSERT_TRUE(SelectMaximallyStableLevel(profile, 90.0, 0.10, 0.25, &level));
  EXPECT_NEAR(level.threshold, 0.8 * 125.0 + 20, 3.0);
}

TEST(IsoCurveStability, GaussianWeightsMakeInstabilityNearPCountMost) {
  // A sharp vertical edge with a soft stretch, either around p or 14 px away along the curve:
  // the paper's reason for weighting (§2.1, Fig. 3).
  const test::Polygon right{{{30.0, -10}, {90, -10}, {90, 90}, {30.0, 90}}, 200};
  const cv::Mat sharp = test::RenderPolygons(test::FlatBackground({60, 80}, 50), {right}, 0.7);
  const cv::Mat soft = test::RenderPolygons(test::FlatBackground({60, 80}, 50), {right}, 3.0);
  auto with_soft_rows = [&](int from, int to) {
    cv::Mat image = sharp.clone();
    soft.rowRange(from, to).copyTo(image.rowRange(from, to));
    return image;
  };
  auto rho_at_p = [](const cv::Mat& image) {
    int centre = 0;
    const auto reference = Reference(image, 125.5, {30.0f, 40.0f}, &centre);
    StabilityProfile profile;
    EXPECT_TRUE(ComputeWeightedStabilityProfile(image, reference, centre, {}, &profile));
    StableLevel level;
    EXPECT_TRUE(SelectMaximallyStableLevel(profile, 125.0, 0.10, 0.25, &level));
    return level.stability;
  };
  const double near = rho_at_p(with_soft_rows(36, 45));
  const double far = rho_at_p(with_soft_rows(50, 59));
  const double none = rho_at_p(sharp);
  EXPECT_LT(near, 0.7 * far);
  EXPECT_LT(far, none);
}

StabilityProfile SyntheticProfile(int first_level, std::vector<double> rho, double middle) {
  StabilityProfile profile;
  profile.first_level = first_level;
  profile.stability = std::move(rho);
  profile.middle_level = middle;
  return profile;
}

TEST(IsoCurveStability, SelectionTakesTheMiddleOfTheStableRunAndClimbsOverRipples) {
  // Levels 100..110; a plateau 102..108 with ripples (a dip of 2 %).
  const auto profile =
      SyntheticProfile(100, {1.0, 2.0, 4.0, 4.1, 4.05, 4.12, 4.04, 4.1, 3.9, 2.0, 1.0}, 105.3);
  StableLevel level;
  ASSERT_TRUE(SelectMaximallyStableLevel(profile, 103.0, 0.10, 0.25, &level));
  EXPECT_NEAR(level.threshold, 105.8, 1e-9);  // middle_level + 0.5, inside the run
  EXPECT_NEAR(level.stability, 4.12, 1e-9);   // the highest of the ripples
  EXPECT_EQ(level.level, 105);
  // The middle is clamped to the run.
  ASSERT_TRUE(SelectMaximallyStableLevel(SyntheticProfile(100, profile.stability, 120.0), 103.0,
                                         0.10, 0.25, &level));
  EXPECT_NEAR(level.threshold, 108.5, 1e-9);
}

TEST(IsoCurveStability, SelectionKeepsDistinctCurvesApart) {
  // Two peaks separated by a deep dip: two different curves. The one nearest in level wins.
  const std::vector<double> rho = {1.0, 3.0, 1.0, 0.5, 1.0, 5.0, 1.0};
  StableLevel level;
  ASSERT_TRUE(SelectMaximallyStableLevel(SyntheticProfile(50, rho, 0.0), 50.0, 0.10, 0.25, &level));
  EXPECT_EQ(level.level, 51);
  EXPECT_DOUBLE_EQ(level.stability, 3.0);
  ASSERT_TRUE(SelectMaximallyStableLevel(SyntheticProfile(50, rho, 0.0), 56.0, 0.10, 0.25, &level));
  EXPECT_EQ(level.level, 55);
  // A single-level run is refined by a parabola.
  ASSERT_TRUE(SelectMaximallyStableLevel(SyntheticProfile(0, {1.0, 3.0, 2.0}, 0.0), 1.0, 0.10, 0.25,
                                         &level));
  EXPECT_NEAR(level.threshold, 1.0 + 1.0 / 6.0 + 0.5, 1e-9);
  // No interior maximum: nothing selected.
  EXPECT_FALSE(SelectMaximallyStableLevel(SyntheticProfile(0, {1.0, 2.0, 3.0}, 0.0), 1.0, 0.10,
                                          0.25, &level));
}

TEST(IsoCurveStability, LazyEvaluationChoosesExactlyWhatTheFullProfileChooses) {
  // Textured scene: jagged ρ profiles with many maxima. The evaluator reads only the levels the
  // choice needs, and must agree bit for bit with the profile of every level.
  const cv::Mat image =
      test::RenderPolygons(test::TexturedBackground({120, 120}, 11, 20, 200, 5),
                           {test::MakeSquare({30.4, 35.2}, 50, 230),
                            test::MakeTriangle({20, 100}, {100, 90}, {70, 20}, 10)},
                           1.0);
  WeightedStabilityEvaluator evaluator;
  int compared = 0, evaluated = 0, levels = 0;
  for (int y = 20; y < 100; y += 7) {
    for (double threshold : {60.5, 110.5, 160.5}) {
      const IsoCurveTracer tracer(image, cv::Rect(0, 0, image.cols, image.rows), threshold);
      CurveEdge seed;
      if (!tracer.FindNearestCrossing(cv::Point2f(60.0f, static_cast<float>(y)), 20, &seed)) {
        continue;
      }
      IsoCurve curve;
      tracer.Trace(seed, 1000, &curve);
      int centre = 0;
      const auto reference = ResamplePolyline(
          curve.points, false, 1.0, ArcLengthAt(curve.points, curve.seed_index), 13, 13, &centre);
      StabilityProfile profile;
      const bool full = ComputeWeightedStabilityProfile(image, reference, centre, {}, &profile);
      ASSERT_EQ(full, evaluator.Prepare(image, reference, centre, {}));
      if (!full) continue;
      for (double previous : {threshold - 0.5, threshold - 12.0, threshold + 7.3}) {
        StableLevel a, b;
        const bool found = SelectMaximallyStableLevel(profile, previous, 0.10, 0.25, &a);
        ASSERT_EQ(found, SelectMaximallyStableLevel(&evaluator, previous, 0.10, 0.25, &b));
        if (!found) continue;
        EXPECT_EQ(a.threshold, b.threshold);
        EXPECT_EQ(a.level, b.level);
        EXPECT_EQ(a.stability, b.stability);
        ++compared;
      }
      evaluated += evaluator.NumEvaluated();
      levels += evaluator.NumLevels();
      for (int l = 0; l < profile.NumLevels(); ++l) {
        EXPECT_EQ(evaluator.Stability(l), profile.stability[l]);
        EXPECT_EQ(evaluator.CentreOffset(l), profile.centre_offset[l]);
      }
    }
  }
  EXPECT_GT(compared, 20);
  EXPECT_LT(evaluated, levels);
}

TEST(IsoCurveStability, SingleLevelStabilityIsTheProfilesValueBitForBit) {
  // The direct search's path (PrepareWithoutMiddleLevel, then one SingleLevelStability per
  // evaluator) computes only one level's three thresholds: it must give the full profile's ρ_w of
  // every level exactly, on jagged textured profiles, for δ = 5 and 3 and a fractional δ (which
  // falls back to the windowed evaluation).
  const cv::Mat image =
      test::RenderPolygons(test::TexturedBackground({120, 120}, 11, 20, 200, 5),
                           {test::MakeSquare({30.4, 35.2}, 50, 230),
                            test::MakeTriangle({20, 100}, {100, 90}, {70, 20}, 10)},
                           1.0);
  WeightedStabilityEvaluator evaluator;
  int compared = 0;
  for (double delta : {5.0, 3.0, 2.5}) {
    WeightedStabilityOptions options;
    options.delta = delta;
    for (int y = 20; y < 100; y += 7) {
      for (double threshold : {60.5, 110.5, 160.5}) {
        const IsoCurveTracer tracer(image, cv::Rect(0, 0, image.cols, image.rows), threshold);
        CurveEdge seed;
        if (!tracer.FindNearestCrossing(cv::Point2f(60.0f, static_cast<float>(y)), 20, &seed)) {
          continue;
        }
        IsoCurve curve;
        tracer.Trace(seed, 1000, &curve);
        int centre = 0;
        const auto reference = ResamplePolyline(
            curve.points, false, 1.0, ArcLengthAt(curve.points, curve.seed_index), 13, 13, &centre);
        StabilityProfile profile;
        const bool full =
            ComputeWeightedStabilityProfile(image, reference, centre, options, &profile);
        ASSERT_EQ(full, evaluator.PrepareWithoutMiddleLevel(image, reference, centre, options));
        if (!full) continue;
        ASSERT_EQ(evaluator.first_level(), profile.first_level);
        ASSERT_EQ(evaluator.NumLevels(), profile.NumLevels());
        for (int l = 0; l < profile.NumLevels(); ++l) {
          // A fresh evaluator per level, as the direct search uses it: nothing memoised.
          ASSERT_TRUE(evaluator.PrepareWithoutMiddleLevel(image, reference, centre, options));
          EXPECT_EQ(evaluator.SingleLevelStability(l), profile.stability[l]);
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 200);
}

}  // namespace
}  // namespace comic::frontend
