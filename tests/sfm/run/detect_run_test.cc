// RunDetect: the options reach the search that runs, max_features keeps the strongest, the
// result does not depend on the thread count, and bad options are refused before any work.
#include "sfm/run/detect_run.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

// A bright square and a darker triangle on grey: a handful of clear corners of both polarities.
cv::Mat Shapes() {
  cv::Mat image(120, 160, CV_8UC1, cv::Scalar(100));
  cv::rectangle(image, {30, 30}, {80, 80}, cv::Scalar(200), cv::FILLED);
  const std::vector<cv::Point> triangle = {{100, 90}, {150, 40}, {140, 100}};
  cv::fillConvexPoly(image, triangle, cv::Scalar(30));
  cv::GaussianBlur(image, image, {0, 0}, 1.0);
  return image;
}

bool SameFeatures(const frontend::FeatureSet& a, const frontend::FeatureSet& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].x != b[i].x || a[i].y != b[i].y || a[i].scale != b[i].scale ||
        a[i].response != b[i].response) {
      return false;
    }
  }
  return true;
}

TEST(DetectRun, BothSearchesFindTheCornersAndNameThemselves) {
  for (const char* name : {"comic", "comic-paper"}) {
    DetectRunOptions options;
    options.detector = name;
    const DetectRunResult result = RunDetect(options, Shapes());
    EXPECT_EQ(result.detector_name, name);
    EXPECT_GE(result.features.size(), 4u) << name;
  }
}

TEST(DetectRun, MaxFeaturesKeepsTheStrongestAndThreadsChangeNothing) {
  DetectRunOptions options;
  options.threads = 1;
  const frontend::FeatureSet all = RunDetect(options, Shapes()).features;
  ASSERT_GE(all.size(), 3u);
  options.threads = 2;
  EXPECT_TRUE(SameFeatures(RunDetect(options, Shapes()).features, all));
  options.max_features = 2;
  const frontend::FeatureSet strongest = RunDetect(options, Shapes()).features;
  EXPECT_TRUE(SameFeatures(strongest, frontend::FeatureSet(all.begin(), all.begin() + 2)));
}

TEST(DetectRun, TheSwitchesReachAlgorithmOne) {
  DetectRunOptions options;
  options.detector = "comic-paper";
  options.full_resolution_init = true;
  options.no_neighbour_seeds = true;
  options.every_path = true;
  const frontend::ComicDetectorOptions paper = options.ToDetectorOptions().comic_paper;
  EXPECT_FALSE(paper.coarse_initialisation);
  EXPECT_FALSE(paper.seed_neighbouring_corners);
  EXPECT_FALSE(paper.skip_duplicate_paths);
}

TEST(DetectRun, BadOptionsAreRefused) {
  DetectRunOptions options;
  options.max_features = -1;
  EXPECT_THROW(options.Check(), Error);
  options = DetectRunOptions();
  options.detector = "sift";
  EXPECT_THROW(options.Check(), Error);
  // A bad value of the search that does not run is an error too, not ignored.
  options = DetectRunOptions();
  options.block_size = -5;
  EXPECT_THROW(RunDetect(options, Shapes()), Error);
}

}  // namespace
}  // namespace comic::sfm
