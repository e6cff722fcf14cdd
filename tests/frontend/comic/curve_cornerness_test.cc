#include "frontend/comic/curve_cornerness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "frontend/comic/iso_curve.h"
#include "tests/frontend/synthetic_images.h"

namespace comic::frontend {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Samples 1 px apart along a polyline through `vertices` (arc length origin at vertex 0 + phase).
std::vector<cv::Point2f> Sampled(const std::vector<cv::Point2f>& vertices, double phase = 0.0) {
  int origin = 0;
  return ResamplePolyline(vertices, false, 1.0, phase, 0, 1000, &origin);
}

std::vector<cv::Point2f> Rotated(const std::vector<cv::Point2f>& points, double angle) {
  std::vector<cv::Point2f> out;
  const double c = std::cos(angle), s = std::sin(angle);
  for (const cv::Point2f& p : points) {
    out.emplace_back(static_cast<float>(c * p.x - s * p.y + 7.3),
                     static_cast<float>(s * p.x + c * p.y - 2.1));
  }
  return out;
}

TEST(CurveCornerness, BoxRadiusMatchesTheGaussianVariance) {
  for (double sigma : {2.0, 5.94, 12.0}) {
    const int r = BoxRadiusForGaussian(sigma);
    EXPECT_LE(std::abs(r * (r + 1.0) - sigma * sigma), sigma + 0.5) << sigma;
  }
}

TEST(CurveCornerness, StraightLineHasNoCornerness) {
  const auto line = Sampled({{0, 0}, {60 * std::cos(0.5f), 60 * std::sin(0.5f)}});
  const auto kappa = CurveCornerness(line, false, 6.0, 12);
  int valid = 0;
  for (double k : kappa) {
    if (k < 0) continue;
    ++valid;
    EXPECT_LT(k, 1e-6);
  }
  EXPECT_GT(valid, 20);
  EXPECT_TRUE(CornernessMaxima(kappa, false, 6, 0.03).empty());
}

TEST(CurveCornerness, RightAngleHasItsMaximumAtTheVertex) {
  const auto corner = Sampled({{40, 0}, {0, 0}, {0, 40}});
  const auto kappa = CurveCornerness(corner, false, 6.0, 12);
  const int vertex = 40;
  ASSERT_LT(cv::norm(corner[vertex]), 1e-4);
  const auto maxima = CornernessMaxima(kappa, false, 6, 0.03);
  ASSERT_EQ(maxima.size(), 1u);
  EXPECT_EQ(maxima[0], vertex);
  // Gaussian-weighted points on two long perpendicular arms: κ = 0.196 (Σ from the half-normal
  // moments); the three box passes approximate it.
  EXPECT_NEAR(kappa[vertex], 0.196, 0.02);
  // Ends without a complete segment are not evaluated.
  for (int i = 0; i < 12; ++i) EXPECT_EQ(kappa[i], -1.0);
}

// The cumulative-sum form against the three box passes: equal up to rounding wherever the
// windows are whole (every sample of a closed curve, 3r from an open one's ends), long curves
// (several blocks, far from the origin) included; near an open curve's ends it truncates the
// window once instead of after each pass, which moves κ a little but keeps its validity.
TEST(CurveCornerness, CumulativeFormEqualsTheBoxPasses) {
  CornernessWorkspace workspace;
  const double sigma = 8.4 / std::sqrt(2.0);
  const int r = BoxRadiusForGaussian(sigma);
  std::vector<std::vector<cv::Point2f>> curves;
  // A wiggly closed loop of 1500 samples far from the origin, a polygon, a short loop.
  std::vector<cv::Point2f> loop;
  for (int i = 0; i < 1500; ++i) {
    const double a = 2 * kPi * i / 1500;
    const double radius = 230 + 9 * std::sin(23 * a) + 4 * std::cos(61 * a);
    loop.emplace_back(static_cast<float>(900 + radius * std::cos(a)),
                      static_cast<float>(650 + radius * std::sin(a)));
  }
  curves.push_back(loop);
  curves.push_back(Sampled({{300, 20}, {340, 25}, {332, 70}, {290, 64}, {300, 20}}));
  curves.push_back(std::vector<cv::Point2f>(loop.begin(), loop.begin() + 700));
  for (size_t c = 0; c < curves.size(); ++c) {
    for (bool closed : {true, false}) {
      std::vector<double> expected, kappa;
      CurveCornerness(curves[c], closed, sigma, 12, &workspace, &expected);
      CurveCornernessCumulative(curves[c], closed, sigma, 12, &workspace, &kappa);
      const int n = static_cast<int>(expected.size());
      ASSERT_EQ(static_cast<int>(kappa.size()), n);
      for (int i = 0; i < n; ++i) {
        const bool whole = closed || (i >= 3 * r && i < n - 3 * r);
        EXPECT_EQ(kappa[i] < 0, expected[i] < 0) << c << " " << closed << " " << i;
        if (whole) {
          EXPECT_NEAR(kappa[i], expected[i], 1e-9) << c << " " << closed << " " << i;
        } else if (expected[i] >= 0) {
          EXPECT_NEAR(kappa[i], expected[i], 0.02) << c << " " << closed << " " << i;
        }
      }
    }
  }
}

TEST(CurveCornerness, CornernessIsRotationInvariant) {
  const auto corner = Sampled({{30, -10}, {0, 0}, {10, 35}});
  const auto a = CurveCornerness(corner, false, 6.0, 12);
  const auto b = CurveCornerness(Rotated(corner, 0.7), false, 6.0, 12);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-6);
}

TEST(CurveCornerness, SharperTurnsAreMoreCornerLike) {
  double previous = 0;
  for (double turn_degrees : {30.0, 60.0, 90.0, 120.0}) {
    const double t = turn_degrees * kPi / 180.0;
    const auto curve =
        Sampled({{-40, 0},
                 {0, 0},
                 {static_cast<float>(40 * std::cos(t)), static_cast<float>(40 * std::sin(t))}});
    const auto kappa = CurveCornerness(curve, false, 6.0, 12);
    EXPECT_GT(kappa[40], previous) << turn_degrees;
    previous = kappa[40];
  }
}

TEST(CurveCornerness, MaximaHonourThresholdSuppressionAndPlateaus) {
  std::vector<double> kappa = {-1, 0.01, 0.05, 0.1, 0.1, 0.1, 0.05, 0.02, 0.01, 0.04, 0.03, 0, -1};
  auto maxima = CornernessMaxima(kappa, false, 2, 0.03);
  ASSERT_EQ(maxima.size(), 2u);
  EXPECT_EQ(maxima[0], 3);  // first sample of the plateau
  EXPECT_EQ(maxima[1], 9);
  EXPECT_EQ(CornernessMaxima(kappa, false, 2, 0.06).size(), 1u);
  EXPECT_EQ(CornernessMaxima(kappa, false, 6, 0.03).size(), 1u);
  // Closed curves wrap around.
  std::vector<double> ring = {0.2, 0.1, 0.05, 0.1, 0.15};
  EXPECT_EQ(CornernessMaxima(ring, true, 2, 0.03), std::vector<int>{0});
}

TEST(CurveCornerness, RefinementFindsASharpVertexBetweenSamples) {
  for (double phase : {0.0, 0.3, 0.5, 0.8}) {
    const auto corner = Sampled({{40, 0}, {0, 0}, {0, 40}}, phase);
    const auto kappa = CurveCornerness(corner, false, 6.0, 12);
    const auto maxima = CornernessMaxima(kappa, false, 6, 0.03);
    ASSERT_EQ(maxima.size(), 1u);
    CurveCornerOptions options;
    const CurveCorner c = RefineCurveCorner(corner, false, kappa, maxima[0], options);
    // The apex lies on the resampled polyline, whose chord cuts a sharp corner by up to half a
    // sample diagonal (0.35 px).
    EXPECT_LT(cv::norm(c.apex), 0.4) << phase;
    EXPECT_LT(cv::norm(c.vertex), 0.05) << phase;  // the arms are exact lines
    EXPECT_NEAR(std::abs(c.turn_angle), kPi / 2, 0.02);
  }
}

TEST(CurveCornerness, ArmIntersectionRecoversTheVertexOfABlurredCorner) {
  const cv::Point2d vertex(30.37, 25.62);
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({80, 80}, 50),
                                             {test::MakeSquare(vertex, 30, 200)}, 1.0);
  const IsoCurveTracer tracer(image, cv::Rect(0, 0, 80, 80), 125.5);
  CurveEdge seed;
  ASSERT_TRUE(tracer.FindNearestCrossing(cv::Point2f(vertex), 3, &seed));
  IsoCurve curve;
  tracer.Trace(seed, 1000, &curve);
  ASSERT_TRUE(curve.closed);
  int origin = 0;
  const auto samples = ResamplePolyline(curve.points, true, 1.0, 0.0, 0, 0, &origin);
  const auto kappa = CurveCornerness(samples, true, 5.94, 12);
  int nearest = -1;
  for (int m : CornernessMaxima(kappa, true, 6, 0.03)) {
    if (nearest < 0 || cv::norm(cv::Point2d(samples[m]) - vertex) <
                           cv::norm(cv::Point2d(samples[nearest]) - vertex)) {
      nearest = m;
    }
  }
  ASSERT_GE(nearest, 0);
  const CurveCorner c = RefineCurveCorner(samples, true, kappa, nearest, CurveCornerOptions());
  // The rounded iso-curve's apex lies inside the corner (~0.8 px for σ = 1); the arms' lines
  // meet at the vertex.
  EXPECT_GT(cv::norm(cv::Point2d(c.apex) - vertex), 0.5);
  EXPECT_LT(cv::norm(cv::Point2d(c.vertex) - vertex), 0.1);
  // The interior of a bright square's corner is the bright side.
  EXPECT_EQ(c.polarity, Polarity::kBright);
  EXPECT_LT(c.turn_angle, 0);
}

TEST(CurveCornerness, TurningTowardsTheDarkLeftSideIsDarkPolarity) {
  // With y down, travelling east then north is a left turn.
  const auto corner = Sampled({{0, 40}, {40, 40}, {40, 0}});
  const auto kappa = CurveCornerness(corner, false, 6.0, 12);
  const CurveCorner c = RefineCurveCorner(corner, false, kappa, 40, CurveCornerOptions());
  EXPECT_EQ(c.polarity, Polarity::kDark);
  EXPECT_NEAR(c.turn_angle, kPi / 2, 0.02);
}

TEST(CurveCornerness, NoVertexCorrectionForNearlyStraightCurves) {
  const double t = 20.0 * kPi / 180.0;  // below the blend range
  const auto curve =
      Sampled({{-40, 0},
               {0, 0},
               {static_cast<float>(40 * std::cos(t)), static_cast<float>(40 * std::sin(t))}});
  const auto kappa = CurveCornerness(curve, false, 6.0, 12);
  const CurveCorner c = RefineCurveCorner(curve, false, kappa, 40, CurveCornerOptions());
  EXPECT_EQ(c.vertex, c.apex);
}

TEST(CurveCornerness, NoVertexCorrectionWhenTheArmsAreNotStraight) {
  // A right-angle corner at the origin whose arms bend away from each other, (t, -c t²) and
  // (-c t², t), as the arms of texture corners bend. Lines fitted to such arms meet far out on
  // the bisector, and where they meet depends on every wiggle of the arms, so the corner stays at
  // the apex. The same turn with straight arms is corrected (RefinementFindsASharpVertex...).
  constexpr double c = 0.03;
  std::vector<cv::Point2f> vertices;
  for (int i = 300; i >= 0; --i) {
    const double t = 0.1 * i;
    vertices.emplace_back(static_cast<float>(t), static_cast<float>(-c * t * t));
  }
  for (int i = 1; i <= 300; ++i) {
    const double t = 0.1 * i;
    vertices.emplace_back(static_cast<float>(-c * t * t), static_cast<float>(t));
  }
  const auto curve = Sampled(vertices);
  const auto kappa = CurveCornerness(curve, false, 5.94, 12);
  const auto maxima = CornernessMaxima(kappa, false, 6, 0.03);
  ASSERT_EQ(maxima.size(), 1u);
  const CurveCorner corner =
      RefineCurveCorner(curve, false, kappa, maxima[0], CurveCornerOptions());
  EXPECT_LT(cv::norm(corner.apex), 0.4);
  EXPECT_GT(corner.arm_rms, CurveCornerOptions().straight_arms_rms_end);
  EXPECT_EQ(corner.vertex, corner.apex);
  // Without the straightness gate the fitted lines would move it off the curve by more than the
  // 0.3 px the detector localises corners to.
  CurveCornerOptions ungated;
  ungated.straight_arms_rms_end = 1e6;
  const CurveCorner extrapolated = RefineCurveCorner(curve, false, kappa, maxima[0], ungated);
  EXPECT_GT(cv::norm(extrapolated.vertex - extrapolated.apex), 0.3);
}

TEST(CurveCornerness, ArmStraightnessIsReported) {
  const auto corner = Sampled({{40, 0}, {0, 0}, {0, 40}});
  const auto kappa = CurveCornerness(corner, false, 6.0, 12);
  const CurveCorner c = RefineCurveCorner(corner, false, kappa, 40, CurveCornerOptions());
  EXPECT_GE(c.arm_rms, 0.0);
  EXPECT_LT(c.arm_rms, 0.01);
}

}  // namespace
}  // namespace comic::frontend
