#include "io/report/bar_chart.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::io {
namespace {

// Pixels of exactly `colour` in a column range of the image.
int CountColour(const cv::Mat& image, const cv::Vec3b& colour, int x0, int x1) {
  int count = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = x0; x < x1; ++x) count += image.at<cv::Vec3b>(y, x) == colour ? 1 : 0;
  }
  return count;
}

TEST(BarChart, BarHeightsFollowTheValues) {
  BarChart chart;
  chart.title = "test";
  chart.groups = {"a", "b"};
  chart.series = {{"one", {10.0, 40.0}}, {"two", {20.0, std::nan("")}}};
  const cv::Mat image = DrawBarChart(chart, {600, 300});
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.size(), cv::Size(600, 300));
  const cv::Vec3b first(178, 114, 0), second(0, 159, 230);  // the palette's first two colours
  // Plot area x from 50 to 590: group "a" is the left half, "b" the right half.
  const int a_one = CountColour(image, first, 50, 320);
  const int b_one = CountColour(image, first, 320, 590);
  EXPECT_GT(a_one, 0);
  EXPECT_NEAR(static_cast<double>(b_one) / a_one, 4.0, 0.5);
  EXPECT_GT(CountColour(image, second, 50, 320), a_one);  // 20 > 10
  // NaN: no bar (only the legend swatch, which lies above the plot area).
  EXPECT_EQ(CountColour(image(cv::Rect(0, 70, 600, 230)), second, 320, 590), 0);
}

// Black pixels (the label; tick values are grey) in a band of the image.
int CountDark(const cv::Mat& image, int x0, int x1, int y0, int y1) {
  int count = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      count += p[0] < 60 && p[1] < 60 && p[2] < 60;  // black text, not the grey ticks
    }
  }
  return count;
}

TEST(BarChart, WritesTheYAxisLabelAlongTheAxis) {
  BarChart chart;
  chart.groups = {"a"};
  chart.series = {{"one", {5.0}}};
  const cv::Mat unlabelled = DrawBarChart(chart, {600, 300});
  chart.y_label = "M_score(5) (%)";
  const cv::Mat labelled = DrawBarChart(chart, {600, 300});
  // The label stands in the leftmost 22 pixels, over the plot's height; nothing is there without.
  EXPECT_EQ(CountDark(unlabelled, 0, 20, 70, 270), 0);
  EXPECT_GT(CountDark(labelled, 0, 20, 70, 270), 40);
  // Written bottom to top: taller than wide.
  int top = 300, bottom = 0;
  for (int y = 0; y < 300; ++y) {
    if (CountDark(labelled, 0, 20, y, y + 1) > 0) {
      top = std::min(top, y);
      bottom = std::max(bottom, y);
    }
  }
  EXPECT_GT(bottom - top, 60);
}

TEST(BarChart, BadChartsThrow) {
  BarChart chart;
  chart.groups = {"a", "b"};
  chart.series = {{"one", {1.0}}};
  EXPECT_THROW(DrawBarChart(chart), Error);
  chart.series = {{"one", {1.0, 2.0}}};
  EXPECT_THROW(DrawBarChart(chart, {100, 100}), Error);
  EXPECT_NO_THROW(DrawBarChart(chart));
}

}  // namespace
}  // namespace comic::io
