#include "frontend/comic/initial_corners.h"

#include <gtest/gtest.h>

#include "tests/frontend/synthetic_images.h"

namespace comic::frontend {
namespace {

TEST(InitialCorners, BlockOriginsCoverTheImageWithTheLastBlockFlush) {
  EXPECT_EQ(BlockOrigins(100, 50, 25), (std::vector<int>{0, 25, 50}));
  EXPECT_EQ(BlockOrigins(110, 50, 25), (std::vector<int>{0, 25, 50, 60}));
  EXPECT_EQ(BlockOrigins(50, 50, 25), (std::vector<int>{0}));
  EXPECT_TRUE(BlockOrigins(49, 50, 25).empty());
}

TEST(InitialCorners, OwnedRangesPartitionTheImageAroundBlockCentres) {
  for (int size : {100, 110, 137}) {
    const std::vector<int> origins = BlockOrigins(size, 50, 25);
    int expected_begin = 0;
    for (int i = 0; i < static_cast<int>(origins.size()); ++i) {
      const auto [begin, end] = OwnedRange(origins, 50, i, size);
      EXPECT_EQ(begin, expected_begin) << size << " block " << i;
      EXPECT_GT(end, begin);
      // Interior blocks own their central part, with at least a quarter block of context.
      if (i > 0) {
        EXPECT_GE(begin - origins[i], 50 / 4 - 1);
      }
      if (i + 1 < static_cast<int>(origins.size())) {
        EXPECT_GE(origins[i] + 50 - end, 50 / 4 - 1);
      }
      expected_begin = end;
    }
    EXPECT_EQ(expected_begin, size);
  }
}

class InitialCornersInABlock : public ::testing::Test {
 protected:
  std::vector<InitialCorner> Detect(const cv::Mat& image, bool upper) {
    InitialCornerOptions options;
    options.half_length = 12;
    options.sigma = 6.0;
    std::vector<InitialCorner> corners;
    const cv::Rect block(0, 0, image.cols, image.rows);
    detector_.DetectInBlock(image, block, block, upper, options, &corners);
    return corners;
  }
  InitialCornerDetector detector_;
};

TEST_F(InitialCornersInABlock, FindsTheCornerOfABrightSquareWithItsPolarity) {
  const cv::Point2d vertex(20.3, 18.6);
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({50, 50}, 60),
                                             {test::MakeSquare(vertex, 40, 190)}, 1.0);
  for (bool upper : {false, true}) {
    const auto corners = Detect(image, upper);
    ASSERT_FALSE(corners.empty()) << upper;
    double best = 1e9;
    for (const InitialCorner& c : corners) {
      const double d = cv::norm(cv::Point2d(c.position) - vertex);
      if (d < best) {
        best = d;
        EXPECT_EQ(c.polarity, Polarity::kBright);
        EXPECT_GT(c.level, 60);
        EXPECT_LT(c.level, 190);
        // The curve around the corner, dark side on the left, with the corner inside it.
        ASSERT_GT(c.curve.size(), 20u);
        EXPECT_LT(cv::norm(c.curve[c.corner_index] - c.position), 1.0);
      }
    }
    // The apex at the initialisation scale: inside the corner, within a couple of pixels.
    EXPECT_LT(best, 3.0) << upper;
  }
}

TEST_F(InitialCornersInABlock, DarkSquareCornerHasDarkPolarity) {
  const cv::Point2d vertex(20.3, 18.6);
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({50, 50}, 190),
                                             {test::MakeSquare(vertex, 40, 60)}, 1.0);
  const auto corners = Detect(image, false);
  ASSERT_FALSE(corners.empty());
  for (const InitialCorner& c : corners) {
    if (cv::norm(cv::Point2d(c.position) - vertex) < 3.0) {
      EXPECT_EQ(c.polarity, Polarity::kDark);
    }
  }
}

TEST_F(InitialCornersInABlock, FlatBlocksAndStraightEdgesHaveNoCorners) {
  EXPECT_TRUE(Detect(cv::Mat(50, 50, CV_8UC1, cv::Scalar(77)), false).empty());
  const test::Polygon half{{{-10, -10}, {30.2, -10}, {20.7, 60}, {-10, 60}}, 200};
  const cv::Mat edge = test::RenderPolygons(test::FlatBackground({50, 50}, 50), {half}, 1.0);
  EXPECT_TRUE(Detect(edge, false).empty());
  EXPECT_TRUE(Detect(edge, true).empty());
}

TEST_F(InitialCornersInABlock, OnlyCornersInTheOwnedPartAreReported) {
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({50, 50}, 60),
                                             {test::MakeSquare({10.3, 10.6}, 30, 190)}, 1.0);
  InitialCornerOptions options;
  options.half_length = 12;
  options.sigma = 6.0;
  std::vector<InitialCorner> all, owned;
  detector_.DetectInBlock(image, cv::Rect(0, 0, 50, 50), cv::Rect(0, 0, 50, 50), false, options,
                          &all);
  detector_.DetectInBlock(image, cv::Rect(0, 0, 50, 50), cv::Rect(0, 0, 25, 50), false, options,
                          &owned);
  EXPECT_GT(all.size(), owned.size());
  ASSERT_FALSE(owned.empty());
  for (const InitialCorner& c : owned) EXPECT_LT(c.position.x, 25.0f);
}

}  // namespace
}  // namespace comic::frontend
