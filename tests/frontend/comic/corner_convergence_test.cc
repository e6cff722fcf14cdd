#include "frontend/comic/corner_convergence.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "frontend/comic/iso_curve.h"
#include "tests/frontend/synthetic_images.h"

namespace comic::frontend {
namespace {

// A reference curve for a start: 30 px of the level-`threshold` curve on either side of the
// point nearest to `near`.
std::vector<cv::Point2f> CurveThrough(const cv::Mat& image, double threshold, cv::Point2f near) {
  const IsoCurveTracer tracer(image, cv::Rect(0, 0, image.cols, image.rows), threshold);
  CurveEdge seed;
  EXPECT_TRUE(tracer.FindNearestCrossing(near, 3, &seed));
  IsoCurve curve;
  tracer.Trace(seed, 1000, &curve);
  const double s = ProjectOntoPolyline(curve.points, curve.closed, near);
  int origin = 0;
  if (!curve.closed) return ResamplePolyline(curve.points, false, 1.0, s, 30, 30, &origin);
  std::vector<cv::Point2f> loop = ResamplePolyline(curve.points, true, 1.0, s - 30, 0, 0, &origin);
  loop.resize(std::min<size_t>(loop.size(), 61));
  return loop;
}

class CornerConvergence : public ::testing::Test {
 protected:
  CornerConvergence()
      : vertex_(40.37, 35.81),
        image_(test::RenderPolygons(test::FlatBackground({100, 100}, 50),
                                    {test::MakeSquare(vertex_, 40, 200)}, 1.0)) {
    options_.sigma = 8.4 / std::sqrt(2.0);
  }
  cv::Point2d vertex_;
  cv::Mat image_;
  ConvergenceOptions options_;
};

TEST_F(CornerConvergence, ConvergesFromAnOffStartAndAnOffLevelToTheVertex) {
  // Start 2 px off, on the curve at level 80, near the foot of the blurred edge.
  const cv::Point2f start(static_cast<float>(vertex_.x + 1.5), static_cast<float>(vertex_.y - 1.3));
  const auto reference = CurveThrough(image_, 80.5, start);
  ConvergedCorner corner;
  ASSERT_TRUE(ConvergeCorner(image_, start, reference, 80.0, options_, &corner));
  EXPECT_LT(cv::norm(cv::Point2d(corner.position) - vertex_), 0.3);
  EXPECT_NEAR(corner.threshold, 125.0, 6.0);  // the middle of the edge
  EXPECT_EQ(corner.level, static_cast<int>(std::ceil(corner.threshold)) - 1);
  EXPECT_GT(corner.iterations, 1);
  EXPECT_EQ(corner.polarity, Polarity::kBright);
  EXPECT_NEAR(corner.cornerness, 0.17, 0.03);
  EXPECT_GT(corner.stability, 3.0);
  ASSERT_EQ(corner.segment.size(), 2u * options_.half_length + 1);
  EXPECT_LT(cv::norm(cv::Point2d(corner.segment[options_.half_length]) - cv::Point2d(corner.apex)),
            1.0);
}

TEST_F(CornerConvergence, ACornerThatHasNotSettledIsDropped) {
  const cv::Point2f start(static_cast<float>(vertex_.x + 2.5), static_cast<float>(vertex_.y - 2.0));
  const auto reference = CurveThrough(image_, 70.5, start);
  ConvergedCorner corner;
  options_.max_iterations = 1;  // the first move (> 1 px) is the last
  EXPECT_FALSE(ConvergeCorner(image_, start, reference, 70.0, options_, &corner));
  options_.max_iterations = 5;
  EXPECT_TRUE(ConvergeCorner(image_, start, reference, 70.0, options_, &corner));
}

TEST_F(CornerConvergence, NoCornerOnAStraightEdge) {
  const cv::Point2f start(static_cast<float>(vertex_.x + 20), static_cast<float>(vertex_.y));
  const auto reference = CurveThrough(image_, 125.5, start);
  ConvergedCorner corner;
  EXPECT_FALSE(ConvergeCorner(image_, start, reference, 125.0, options_, &corner));
}

TEST_F(CornerConvergence, ReportsTheOtherCornersOnTheCurve) {
  // A bar whose two end corners are 18 px apart on one curve: distinct at scale s, merged at the
  // initialisation scale 2s.
  const test::Polygon bar{{{30.2, 40.6}, {48.2, 40.6}, {48.2, 85.6}, {30.2, 85.6}}, 200};
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({100, 100}, 50), {bar}, 1.0);
  const cv::Point2f start(30.5f, 41.0f);
  ConvergedCorner corner;
  ASSERT_TRUE(
      ConvergeCorner(image, start, CurveThrough(image, 125.5, start), 125.0, options_, &corner));
  bool found_neighbour = false;
  for (const cv::Point2f& p : corner.other_corners) {
    found_neighbour |= cv::norm(p - cv::Point2f(48.2f, 40.6f)) < 2.0;
  }
  EXPECT_LT(cv::norm(corner.position - cv::Point2f(30.2f, 40.6f)), 0.3);
  EXPECT_TRUE(found_neighbour);
}

}  // namespace
}  // namespace comic::frontend
