#include "io/datasets/middlebury.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "io/core/error.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;

// A synthetic rectified pair: a bright square at disparity 6 over a textured background at
// disparity 2, stored with scale 4 like the 2003 pairs.
MiddleburyPairPaths WriteSyntheticPair(const ScopedTempDir& dir, cv::Size size = {60, 40}) {
  cv::Mat left(size, CV_8UC3), right(size, CV_8UC3);
  cv::randu(left, 0, 255);
  cv::randu(right, 0, 255);
  cv::Mat disparity(size, CV_8UC1, cv::Scalar(2 * 4));
  disparity(cv::Rect(20, 10, 15, 15)).setTo(6 * 4);
  disparity.col(0).setTo(0);  // unknown
  cv::Mat disc(size, CV_8UC1, cv::Scalar(128));
  disc(cv::Rect(18, 8, 19, 19)).setTo(255);
  cv::imwrite(dir.File("left.png"), left);
  cv::imwrite(dir.File("right.png"), right);
  cv::imwrite(dir.File("disp.png"), disparity);
  cv::imwrite(dir.File("nonocc.png"), cv::Mat(size, CV_8UC1, cv::Scalar(255)));
  cv::imwrite(dir.File("disc.png"), disc);
  MiddleburyPairPaths paths;
  paths.left = dir.File("left.png");
  paths.right = dir.File("right.png");
  paths.disparity = dir.File("disp.png");
  paths.disparity_scale = 4.0;
  paths.nonocc = dir.File("nonocc.png");
  paths.disc = dir.File("disc.png");
  return paths;
}

TEST(Middlebury, ScaleIsHonouredAtOriginalSize) {
  ScopedTempDir dir;
  const MiddleburyPair pair = LoadMiddleburyPair(WriteSyntheticPair(dir));
  EXPECT_FLOAT_EQ(pair.disparity.at<float>(5, 5), 2.0f);
  EXPECT_FLOAT_EQ(pair.disparity.at<float>(15, 25), 6.0f);
  EXPECT_FLOAT_EQ(pair.disparity.at<float>(15, 0), 0.0f);
  EXPECT_DOUBLE_EQ(pair.MaxDisparity(), 6.0);
  EXPECT_EQ(pair.disc.at<uint8_t>(10, 20), 255);
  EXPECT_EQ(pair.left_gray.type(), CV_8UC1);
}

TEST(Middlebury, ResizingScalesDisparitiesAndKeepsMasksBinary) {
  ScopedTempDir dir;
  const MiddleburyPair pair = LoadMiddleburyPair(WriteSyntheticPair(dir), 100);  // x2.5
  ASSERT_EQ(pair.left_gray.size(), cv::Size(150, 100));
  ASSERT_EQ(pair.disparity.size(), cv::Size(150, 100));
  EXPECT_DOUBLE_EQ(pair.resize_factor, 2.5);
  EXPECT_FLOAT_EQ(pair.disparity.at<float>(10, 10), 5.0f);
  EXPECT_FLOAT_EQ(pair.disparity.at<float>(40, 65), 15.0f);
  std::set<int> disc_values;
  for (int y = 0; y < pair.disc.rows; ++y) {
    for (int x = 0; x < pair.disc.cols; ++x) disc_values.insert(pair.disc.at<uint8_t>(y, x));
  }
  EXPECT_EQ(disc_values, (std::set<int>{128, 255}));  // nearest-neighbour: no blended values
}

template <typename Fn>
void ExpectError(Fn fn, ErrorKind kind, const std::string& text) {
  try {
    fn();
    FAIL() << "expected error: " << text;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), kind) << e.what();
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(Middlebury, BadInputs) {
  ScopedTempDir dir;
  MiddleburyPairPaths paths = WriteSyntheticPair(dir);
  MiddleburyPairPaths bad = paths;
  bad.disparity_scale = 0;
  ExpectError([&] { LoadMiddleburyPair(bad); }, ErrorKind::kInvalidArgument, "scale must be > 0");
  cv::imwrite(dir.File("small.png"), cv::Mat(30, 30, CV_8UC3, cv::Scalar::all(1)));
  bad = paths;
  bad.right = dir.File("small.png");
  ExpectError([&] { LoadMiddleburyPair(bad); }, ErrorKind::kInvalidData, "right image is 30x30");
  bad = paths;
  bad.disparity = dir.File("small.png");
  ExpectError([&] { LoadMiddleburyPair(bad); }, ErrorKind::kInvalidData, "disparity map is 30x30");
  bad = paths;
  bad.disc = dir.File("missing_disc.png");
  ExpectError([&] { LoadMiddleburyPair(bad); }, ErrorKind::kNotFound, "missing_disc.png");
  ExpectError([&] { LoadMiddleburyFolder(dir.path()); }, ErrorKind::kNotFound,
              "no Middlebury pair found");
}

TEST(Middlebury, RealPairsMatchTheirGroundTruth) {
  COMIC_REQUIRE_SHARED_DATA();
  for (const char* name :
       {"middlebury2001_tsukuba", "middlebury2003_cones", "middlebury2003_teddy"}) {
    const MiddleburyPair pair =
        LoadMiddleburyFolder(comic::test::SharedDataDir() + "/" + name, 700);
    ASSERT_EQ(pair.left_gray.rows, 700) << name;
    // The disparity sends left pixels to similar right pixels (SOURCE.md's check): the mean
    // absolute grey difference over non-occluded known pixels is far lower than at zero shift.
    double diff_gt = 0, diff_zero = 0;
    int count = 0;
    for (int y = 0; y < pair.left_gray.rows; y += 3) {
      for (int x = 0; x < pair.left_gray.cols; x += 3) {
        const float d = pair.disparity.at<float>(y, x);
        const int xr = static_cast<int>(std::lround(x - d));
        if (d <= 0 || pair.nonocc.at<uint8_t>(y, x) != 255 || xr < 0) continue;
        diff_gt += std::abs(pair.left_gray.at<uint8_t>(y, x) - pair.right_gray.at<uint8_t>(y, xr));
        diff_zero += std::abs(pair.left_gray.at<uint8_t>(y, x) - pair.right_gray.at<uint8_t>(y, x));
        ++count;
      }
    }
    ASSERT_GT(count, 1000) << name;
    EXPECT_LT(diff_gt / count, 0.4 * diff_zero / count) << name;
    // Working-size disparity ranges (SOURCE.md maxima x resize factor): Tsukuba 14 px x 933/384,
    // Cones 55 px x 840/450, Teddy 52.75 px x 840/450.
    const std::string n = name;
    const double expected = n == "middlebury2001_tsukuba" ? 14 * 933.0 / 384.0
                            : n == "middlebury2003_cones" ? 55 * 840.0 / 450.0
                                                          : 52.75 * 840.0 / 450.0;
    EXPECT_NEAR(pair.MaxDisparity(), expected, 1e-3) << name;
  }
}

}  // namespace
}  // namespace comic::io
