// Depth maps as files (io/image/depth_map.h): 16-bit PNG in millimetres (0 = none, 65535 = at
// least 65.535 m) and PFM in float metres, both read back as written.
#include "io/image/depth_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>

#include "io/core/error.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

cv::Mat SampleDepth() {
  cv::Mat depth(7, 9, CV_32F);
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) depth.at<float>(y, x) = 0.5f + 1.37f * x + 3.11f * y;
  }
  depth.at<float>(0, 0) = 0.0f;    // no surface
  depth.at<float>(6, 8) = 120.0f;  // beyond what a 16-bit PNG holds
  return depth;
}

TEST(DepthMap, PfmRoundTripsExactlyAndRowsStayInOrder) {
  test::ScopedTempDir dir;
  const cv::Mat depth = SampleDepth();
  WriteDepthMap(dir.File("d.pfm"), depth);
  const cv::Mat back = ReadDepthMap(dir.File("d.pfm"));
  ASSERT_EQ(back.size(), depth.size());
  EXPECT_EQ(cv::norm(back, depth, cv::NORM_INF), 0.0);
}

TEST(DepthMap, PngHoldsMillimetresAndSaturates) {
  test::ScopedTempDir dir;
  const cv::Mat depth = SampleDepth();
  WriteDepthMap(dir.File("d.png"), depth);
  const cv::Mat stored = cv::imread(dir.File("d.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(stored.type(), CV_16UC1);
  EXPECT_EQ(stored.at<uint16_t>(1, 2),
            static_cast<uint16_t>(std::lround((0.5 + 2.74 + 3.11) * 1000)));
  const cv::Mat back = ReadDepthMap(dir.File("d.png"));
  EXPECT_EQ(back.at<float>(0, 0), 0.0f);
  EXPECT_EQ(back.at<float>(6, 8), std::numeric_limits<float>::infinity());
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      if ((x == 0 && y == 0) || (x == 8 && y == 6)) continue;
      EXPECT_NEAR(back.at<float>(y, x), depth.at<float>(y, x), 0.0005);
    }
  }
}

TEST(DepthMap, BadInputIsOneClearError) {
  test::ScopedTempDir dir;
  EXPECT_THROW(WriteDepthMap(dir.File("d.jpg"), SampleDepth()), Error);
  EXPECT_THROW(WriteDepthMap(dir.File("d.pfm"), cv::Mat(3, 3, CV_8UC1)), Error);
  {
    std::ofstream bad(dir.File("bad.pfm"), std::ios::binary);
    bad << "Pf\n4 4\n-1.0\n" << std::string(10, 'x');  // 10 bytes, not 64
  }
  try {
    ReadDepthMap(dir.File("bad.pfm"));
    FAIL() << "a truncated PFM was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("bad.pfm"), std::string::npos);
  }
  cv::imwrite(dir.File("eight.png"), cv::Mat(3, 3, CV_8UC1, cv::Scalar(7)));
  EXPECT_THROW(ReadDepthMap(dir.File("eight.png")), Error);
  try {
    ReadDepthMap(dir.File("missing.pfm"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kNotFound);
  }
}

}  // namespace
}  // namespace comic::io
