#include "frontend/comic/iso_curve.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "tests/frontend/synthetic_images.h"

namespace comic::frontend {
namespace {

std::set<std::pair<int, int>> EdgeKeys(const IsoCurve& curve, int width) {
  std::set<std::pair<int, int>> keys;
  for (const CurveEdge& e : curve.edges) {
    keys.insert({e.inside.y * width + e.inside.x, e.outside.y * width + e.outside.x});
  }
  return keys;
}

TEST(IsoCurve, StraightEdgeIsTracedBetweenPixelCentresWithDarkSideOnTheLeft) {
  cv::Mat image(30, 40, CV_8UC1, cv::Scalar(50));
  image.colRange(21, 40).setTo(200);
  image.col(20).setTo(125);
  const IsoCurveTracer tracer(image, cv::Rect(0, 0, 40, 30), 100.5);
  CurveEdge seed;
  ASSERT_TRUE(tracer.FindNearestCrossing({19.5f, 15.0f}, 2, &seed));
  IsoCurve curve;
  tracer.Trace(seed, 1000, &curve);
  EXPECT_FALSE(curve.closed);
  ASSERT_EQ(curve.points.size(), 30u);  // one crossing per row
  const float expected_x = 19.0f + (100.5f - 50.0f) / 75.0f;
  for (const cv::Point2f& p : curve.points) EXPECT_NEAR(p.x, expected_x, 1e-5);
  // Dark on the left of travel: with the dark side to the west, the curve runs north (up).
  EXPECT_FLOAT_EQ(curve.points.front().y, 29.0f);
  EXPECT_FLOAT_EQ(curve.points.back().y, 0.0f);
  EXPECT_EQ(curve.points[curve.seed_index], tracer.Crossing(seed));
}

TEST(IsoCurve, BlurredEdgeIsLocatedWithSubPixelAccuracy) {
  for (double edge_x : {30.0, 30.37, 30.5, 30.81}) {
    const test::Polygon right{{{edge_x, -10}, {100, -10}, {100, 100}, {edge_x, 100}}, 200};
    const cv::Mat image =
        test::RenderPolygons(test::FlatBackground({60, 40}, 50), {right}, /*blur_sigma=*/1.0);
    const IsoCurveTracer tracer(image, cv::Rect(0, 0, 60, 40), 125.5);
    CurveEdge seed;
    ASSERT_TRUE(tracer.FindNearestCrossing({30.0f, 20.0f}, 3, &seed));
    IsoCurve curve;
    tracer.Trace(seed, 1000, &curve);
    for (size_t i = 5; i + 5 < curve.points.size(); ++i) {
      EXPECT_NEAR(curve.points[i].x, edge_x, 0.05) << "edge at " << edge_x;
    }
  }
}

TEST(IsoCurve, ClosedCurveAroundASquareIsTheSameFromEverySeed) {
  cv::Mat image(20, 20, CV_8UC1, cv::Scalar(40));
  image(cv::Rect(5, 6, 8, 7)).setTo(220);
  const IsoCurveTracer tracer(image, cv::Rect(0, 0, 20, 20), 130.5);
  CurveEdge seed;
  ASSERT_TRUE(tracer.FindNearestCrossing({4.5f, 8.0f}, 1, &seed));
  IsoCurve curve;
  tracer.Trace(seed, 1000, &curve);
  EXPECT_TRUE(curve.closed);
  EXPECT_EQ(curve.edges.size(), 2u * (8 + 7));  // one crossing per boundary pixel pair
  for (const CurveEdge& e : curve.edges) EXPECT_TRUE(tracer.IsCrossing(e));
  for (size_t start = 1; start < curve.edges.size(); start += 5) {
    IsoCurve again;
    tracer.Trace(curve.edges[start], 1000, &again);
    EXPECT_TRUE(again.closed);
    EXPECT_EQ(EdgeKeys(again, 20), EdgeKeys(curve, 20));
  }
  // Dark (outside the bright square) on the left: the curve goes clockwise on screen, i.e. with
  // y down its signed area (shoelace) is positive.
  double area = 0;
  for (size_t i = 0; i < curve.points.size(); ++i) {
    const cv::Point2f& a = curve.points[i];
    const cv::Point2f& b = curve.points[(i + 1) % curve.points.size()];
    area += a.x * b.y - b.x * a.y;
  }
  EXPECT_GT(area, 0);
}

TEST(IsoCurve, PointsInterpolateLinearlyAndFractionalThresholdsKeepTheEdges) {
  cv::Mat image;
  test::TexturedBackground({40, 40}, 7, 0, 255, 10).convertTo(image, CV_8U);
  const IsoCurveTracer tracer(image, cv::Rect(0, 0, 40, 40), 120.5);
  const IsoCurveTracer shifted(image, cv::Rect(0, 0, 40, 40), 120.9);
  CurveEdge seed;
  ASSERT_TRUE(tracer.FindNearestCrossing({20.0f, 20.0f}, 20, &seed));
  IsoCurve curve, curve_shifted;
  tracer.Trace(seed, 5000, &curve);
  shifted.Trace(seed, 5000, &curve_shifted);
  ASSERT_GT(curve.points.size(), 20u);
  ASSERT_EQ(curve_shifted.edges.size(), curve.edges.size());
  for (size_t i = 0; i < curve.edges.size(); ++i) {
    const CurveEdge& e = curve.edges[i];
    EXPECT_EQ(curve_shifted.edges[i], e);
    const double v_in = image.at<uint8_t>(e.inside);
    const double v_out = image.at<uint8_t>(e.outside);
    const double t = (120.5 - v_in) / (v_out - v_in);
    EXPECT_NEAR(curve.points[i].x, e.inside.x + t * (e.outside.x - e.inside.x), 1e-4);
    EXPECT_NEAR(curve.points[i].y, e.inside.y + t * (e.outside.y - e.inside.y), 1e-4);
    // A higher threshold moves each crossing towards the outside pixel.
    const cv::Point2f step = curve_shifted.points[i] - curve.points[i];
    EXPECT_GE(step.dot(cv::Point2f(e.outside - e.inside)), 0.0f);
  }
}

TEST(IsoCurve, SaddlesAreResolvedAlikeForBothPolarities) {
  // Diagonal pairs: the mean of each 2x2 cell decides whether the dark pixels are joined.
  cv::Mat image(12, 12, CV_8UC1, cv::Scalar(200));
  image.at<uint8_t>(5, 5) = 10;
  image.at<uint8_t>(6, 6) = 10;
  image.at<uint8_t>(5, 6) = 150;
  image.at<uint8_t>(6, 5) = 150;
  const cv::Mat inverted = 255 - image;
  for (double threshold : {60.5, 120.5, 160.5}) {
    const IsoCurveTracer tracer(image, cv::Rect(0, 0, 12, 12), threshold);
    const IsoCurveTracer inverse(inverted, cv::Rect(0, 0, 12, 12), 255.0 - threshold);
    CurveEdge seed, inverse_seed;
    ASSERT_TRUE(tracer.FindNearestCrossing({5.0f, 4.5f}, 1, &seed));
    ASSERT_TRUE(inverse.FindNearestCrossing({5.0f, 4.5f}, 1, &inverse_seed));
    IsoCurve curve, inverse_curve;
    tracer.Trace(seed, 1000, &curve);
    inverse.Trace(inverse_seed, 1000, &inverse_curve);
    auto sorted = [](std::vector<cv::Point2f> p) {
      std::sort(p.begin(), p.end(), [](const cv::Point2f& a, const cv::Point2f& b) {
        return a.x != b.x ? a.x < b.x : a.y < b.y;
      });
      return p;
    };
    const auto a = sorted(curve.points), b = sorted(inverse_curve.points);
    ASSERT_EQ(a.size(), b.size()) << threshold;
    for (size_t i = 0; i < a.size(); ++i) EXPECT_LT(cv::norm(a[i] - b[i]), 1e-4);
    // At 60.5 the cell mean (80) is above the threshold: the two dark pixels are separate curves.
    if (threshold == 60.5) {
      EXPECT_EQ(curve.points.size(), 4u);
    }
    // At 160.5 the 150 pixels are dark too: one curve around all four.
    if (threshold == 160.5) {
      EXPECT_EQ(curve.points.size(), 8u);
    }
  }
}

TEST(IsoCurve, TraceStopsAtTheDomainBorder) {
  cv::Mat image(30, 30, CV_8UC1, cv::Scalar(50));
  image.colRange(15, 30).setTo(200);
  const IsoCurveTracer tracer(image, cv::Rect(5, 10, 20, 8), 125.5);
  CurveEdge seed;
  ASSERT_TRUE(tracer.FindNearestCrossing({14.5f, 12.0f}, 1, &seed));
  IsoCurve curve;
  tracer.Trace(seed, 1000, &curve);
  EXPECT_FALSE(curve.closed);
  EXPECT_EQ(curve.points.size(), 8u);
  for (const cv::Point2f& p : curve.points) {
    EXPECT_GE(p.y, 10.0f);
    EXPECT_LE(p.y, 17.0f);
  }
}

TEST(IsoCurve, ResamplingIsUniformAlongTheArcLength) {
  const std::vector<cv::Point2f> line = {{0, 0}, {3, 4}, {3, 10}};  // length 5 + 6
  EXPECT_DOUBLE_EQ(PolylineLength(line, false), 11.0);
  int origin = -1;
  const auto samples = ResamplePolyline(line, false, 1.0, 5.0, 100, 100, &origin);
  ASSERT_EQ(samples.size(), 12u);  // arc lengths 0..11
  EXPECT_EQ(origin, 5);
  EXPECT_LT(cv::norm(samples[origin] - cv::Point2f(3, 4)), 1e-5);
  for (size_t i = 1; i < samples.size(); ++i) {
    if (i == 5 || i == 6) continue;  // the chords around the bend are shorter
    EXPECT_NEAR(cv::norm(samples[i] - samples[i - 1]), 1.0, 1e-5);
  }
  const auto limited = ResamplePolyline(line, false, 1.0, 5.0, 2, 3, &origin);
  EXPECT_EQ(limited.size(), 6u);
  EXPECT_EQ(origin, 2);

  const std::vector<cv::Point2f> square = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const auto loop = ResamplePolyline(square, true, 1.0, 0.0, 0, 0, &origin);
  EXPECT_EQ(loop.size(), 40u);
  EXPECT_NEAR(ProjectOntoPolyline(square, true, {5.0f, -2.0f}), 5.0, 1e-9);
  EXPECT_NEAR(ProjectOntoPolyline(square, true, {-1.0f, 5.0f}), 35.0, 1e-9);
  EXPECT_NEAR(ArcLengthAt(square, 2), 20.0, 1e-9);
}

TEST(IsoCurve, ArcLengthsComputedOnceGiveTheSameLengthsAndSamples) {
  // An irregular polyline (lengths not exact in binary), open and closed: the precomputed arc
  // lengths must be the ones ArcLengthAt and PolylineLength give, and resampling with them the
  // same samples, bit for bit (the detector relies on it to compute the lengths once).
  std::vector<cv::Point2f> points;
  for (int i = 0; i < 40; ++i) {
    const double angle = 0.37 * i;
    points.emplace_back(static_cast<float>(20 + (9 + 0.3 * i) * std::cos(angle)),
                        static_cast<float>(20 + (7 + 0.1 * i) * std::sin(angle)));
  }
  for (bool closed : {false, true}) {
    std::vector<double> cumulative;
    PolylineArcLengths(points, closed, &cumulative);
    ASSERT_EQ(cumulative.size(), points.size() + 1);
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
      EXPECT_EQ(cumulative[i], ArcLengthAt(points, i)) << i;
    }
    EXPECT_EQ(cumulative.back(), PolylineLength(points, closed));
    EXPECT_GT(cumulative.back(), cumulative[points.size() - 1] + (closed ? 1.0 : -1.0));
    for (double origin : {0.0, 17.3, cumulative[11]}) {
      int origin_a = -1, origin_b = -2;
      const auto a = ResamplePolyline(points, closed, 1.0, origin, 30, 30, &origin_a);
      const auto b = ResamplePolyline(points, cumulative, closed, 1.0, origin, 30, 30, &origin_b);
      ASSERT_EQ(a.size(), b.size());
      ASSERT_FALSE(a.empty());
      EXPECT_EQ(origin_a, origin_b);
      for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].x, b[i].x) << i;
        EXPECT_EQ(a[i].y, b[i].y) << i;
      }
    }
  }
  std::vector<double> empty_lengths = {5.0};
  PolylineArcLengths({}, true, &empty_lengths);
  EXPECT_EQ(empty_lengths, std::vector<double>{0.0});
}

}  // namespace
}  // namespace comic::frontend
