#include "frontend/baselines/response_peaks.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

TEST(ResponsePeaks, FindsLocalMaximaWithSubPixelOffsets) {
  cv::Mat map(20, 20, CV_32F, cv::Scalar(0));
  // A parabola peak between x = 8 and 9: values 3, 4, 3.5 -> vertex at 0.5·(3 − 3.5)/(3 − 8 + 3.5)
  // = 1/6 px right of 8.
  map.at<float>(10, 7) = 3.0f;
  map.at<float>(10, 8) = 4.0f;
  map.at<float>(10, 9) = 3.5f;
  map.at<float>(4, 15) = 2.0f;  // a second, weaker peak
  const FeatureSet peaks = FindResponsePeaks(map, {}, 1.5f);
  ASSERT_EQ(peaks.size(), 2u);
  EXPECT_FLOAT_EQ(peaks[0].response, 4.0f);
  EXPECT_NEAR(peaks[0].x, 8.0f + 1.0f / 6.0f, 1e-5);
  EXPECT_FLOAT_EQ(peaks[0].y, 10.0f);
  EXPECT_FLOAT_EQ(peaks[0].scale, 1.5f);
  EXPECT_FLOAT_EQ(peaks[1].x, 15.0f);
  ResponsePeakOptions options;
  options.min_value = 2.5f;
  EXPECT_EQ(FindResponsePeaks(map, options, 1.0f).size(), 1u);
}

TEST(ResponsePeaks, PlateausGiveOnePeakAndBordersNone) {
  cv::Mat map(20, 20, CV_32F, cv::Scalar(0));
  map(cv::Rect(8, 8, 2, 2)).setTo(5.0f);  // a 2x2 plateau
  map.at<float>(1, 10) = 9.0f;            // inside the 3-pixel border
  ResponsePeakOptions options;
  options.subpixel = false;
  const FeatureSet peaks = FindResponsePeaks(map, options, 1.0f);
  ASSERT_EQ(peaks.size(), 1u);
  EXPECT_FLOAT_EQ(peaks[0].x, 8.0f);  // the first plateau pixel in raster order
  EXPECT_FLOAT_EQ(peaks[0].y, 8.0f);
  options.border = 1;
  EXPECT_EQ(FindResponsePeaks(map, options, 1.0f).size(), 2u);
  options.nms_radius = 0;
  EXPECT_THROW(FindResponsePeaks(map, options, 1.0f), Error);
  EXPECT_THROW(FindResponsePeaks(cv::Mat(5, 5, CV_8UC1), {}, 1.0f), Error);
}

}  // namespace
}  // namespace comic::frontend
