#include "io/datasets/region_annotations.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

std::string WriteText(const test::ScopedTempDir& dir, const std::string& name,
                      const std::string& text) {
  const std::string path = dir.File(name);
  WriteFileAtomically(path, text);
  return path;
}

TEST(RegionAnnotations, ReadsOtbBoxesAsOneBasedPolygons) {
  test::ScopedTempDir dir;
  const auto regions = ReadRegionFile(WriteText(dir, "gt.txt", "205\t151\t17\t50\n1,1,10,20\n\n"));
  EXPECT_EQ(regions.format, RegionFileFormat::kOtbBox);
  ASSERT_EQ(regions.polygons.size(), 2u);
  ASSERT_EQ(regions.polygons[0].size(), 4u);
  // Pixels 205..221 (1-based) = 204..220 (0-based): outer edges at 203.5 and 220.5.
  EXPECT_DOUBLE_EQ(regions.polygons[0][0].x, 203.5);
  EXPECT_DOUBLE_EQ(regions.polygons[0][0].y, 149.5);
  EXPECT_DOUBLE_EQ(regions.polygons[0][2].x, 220.5);
  EXPECT_DOUBLE_EQ(regions.polygons[0][2].y, 199.5);
  EXPECT_DOUBLE_EQ(regions.polygons[1][0].x, -0.5);
}

TEST(RegionAnnotations, ReadsVotPolygonsAndUnannotatedFrames) {
  test::ScopedTempDir dir;
  const auto regions =
      ReadRegionFile(WriteText(dir, "gt.txt", "11,21,31,21,31,41,11,41\r\n0\nnan,nan,nan,nan\n"));
  EXPECT_EQ(regions.format, RegionFileFormat::kVotPolygon);
  ASSERT_EQ(regions.polygons.size(), 3u);
  ASSERT_EQ(regions.polygons[0].size(), 4u);
  EXPECT_DOUBLE_EQ(regions.polygons[0][1].x, 30.0);
  EXPECT_DOUBLE_EQ(regions.polygons[0][1].y, 20.0);
  EXPECT_TRUE(regions.polygons[1].empty());
  EXPECT_TRUE(regions.polygons[2].empty());
}

TEST(RegionAnnotations, MalformedFilesGiveClearErrors) {
  test::ScopedTempDir dir;
  EXPECT_THROW(ReadRegionFile(dir.File("missing.txt")), Error);
  const auto expect_error = [&](const std::string& text, RegionFileFormat format,
                                const std::string& message) {
    try {
      ReadRegionFile(WriteText(dir, "bad.txt", text), format);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  expect_error("", RegionFileFormat::kAuto, "holds no region");
  expect_error("1 2 3 4\n1 2 x 4\n", RegionFileFormat::kAuto, "bad.txt:2: 'x' is not a number");
  expect_error("1 2 3\n", RegionFileFormat::kAuto, "neither an OTB box");
  expect_error("1 2 3 4\n1 2 3 4 5 6 7 8\n", RegionFileFormat::kAuto, "expected an OTB box");
  expect_error("1 2 3 4 5 6 7 8\n", RegionFileFormat::kOtbBox, "expected an OTB box");
  expect_error("1 2 -3 4\n", RegionFileFormat::kOtbBox, "negative width");
  expect_error("1,2,3,4,5,6,7\n", RegionFileFormat::kVotPolygon, "expected a VOT polygon");
}

TEST(RegionAnnotations, FormatNamesRoundTrip) {
  for (auto format :
       {RegionFileFormat::kAuto, RegionFileFormat::kVotPolygon, RegionFileFormat::kOtbBox}) {
    EXPECT_EQ(ParseRegionFileFormat(RegionFileFormatName(format)), format);
  }
  EXPECT_THROW(ParseRegionFileFormat("coco"), Error);
}

TEST(RegionAnnotations, RasterizesBoxesToExactlyTheirPixels) {
  test::ScopedTempDir dir;
  // OTB box: 1-based top-left pixel (11, 21), 20 x 20 pixels -> 0-based pixels x 10..29, y 20..39.
  const auto regions = ReadRegionFile(WriteText(dir, "gt.txt", "11 21 20 20\n"));
  const cv::Mat mask = RasterizeRegion(regions.polygons[0], {100, 80}, {100, 80});
  ASSERT_EQ(mask.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(mask), 400);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(10, 20, 20, 20))), 400);
  // Twice the size: exactly the 40 x 40 pixels covering the same area.
  const cv::Mat big = RasterizeRegion(regions.polygons[0], {100, 80}, {200, 160});
  EXPECT_EQ(cv::countNonZero(big), 1600);
  EXPECT_EQ(cv::countNonZero(big(cv::Rect(20, 40, 40, 40))), 1600);
  EXPECT_EQ(cv::countNonZero(RasterizeRegion({}, {100, 80}, {100, 80})), 0);
}

TEST(RegionAnnotations, RasterizesRotatedPolygonsByPixelCentres) {
  // A diamond with vertices on pixel centres: |x − 20| + |y − 20| < 10 (edges half-open).
  const RegionPolygon diamond = {{20, 10}, {30, 20}, {20, 30}, {10, 20}};
  const cv::Mat mask = RasterizeRegion(diamond, {40, 40}, {40, 40});
  EXPECT_EQ(mask.at<uint8_t>(20, 20), 255);
  EXPECT_EQ(mask.at<uint8_t>(12, 20), 255);
  EXPECT_EQ(mask.at<uint8_t>(14, 14), 0);  // |−6| + |−6| = 12
  // The continuous area is 200 px²; the centre count is within a perimeter's worth of it.
  EXPECT_NEAR(cv::countNonZero(mask), 200, 20);
}

TEST(RegionAnnotations, RasterizesPolygonsReachingFarOutsideTheImage) {
  // A vertex far beyond int's range (found by fuzz_regions: "1e10" in a region file) clips to the
  // image instead of overflowing: the triangle covers the whole right part of rows it crosses.
  const RegionPolygon huge = {{10, 0}, {1e10, 5}, {10, 10}};
  const cv::Mat mask = RasterizeRegion(huge, {40, 40}, {40, 40});
  EXPECT_EQ(mask.at<uint8_t>(5, 39), 255);
  EXPECT_EQ(mask.at<uint8_t>(5, 9), 0);
  EXPECT_EQ(mask.at<uint8_t>(20, 20), 0);
  const RegionPolygon left = {{-1e12, 0}, {5, 5}, {-1e12, 10}};
  EXPECT_EQ(RasterizeRegion(left, {40, 40}, {40, 40}).at<uint8_t>(5, 0), 255);
}

TEST(RegionAnnotations, ReadsTheSharedTrackingSequences) {
  COMIC_REQUIRE_SHARED_DATA();
  const std::string data = test::SharedDataDir();
  const auto car1 = ReadRegionFile(data + "/vot2015_car1/groundtruth.txt");
  EXPECT_EQ(car1.format, RegionFileFormat::kVotPolygon);
  EXPECT_EQ(car1.polygons.size(), 742u);
  const auto bag = ReadRegionFile(data + "/vot_bag/groundtruth.txt");
  EXPECT_EQ(bag.polygons.size(), 196u);
  const auto crossing = ReadRegionFile(data + "/otb_Crossing/groundtruth_rect.txt");
  EXPECT_EQ(crossing.format, RegionFileFormat::kOtbBox);
  ASSERT_EQ(crossing.polygons.size(), 120u);
  EXPECT_DOUBLE_EQ(crossing.polygons[0][0].x, 203.5);  // "205 151 17 50"
}

}  // namespace
}  // namespace comic::io
