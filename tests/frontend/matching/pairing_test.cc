#include "frontend/matching/pairing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <random>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

// A smooth random world seen through a window moving `step` px per frame (a panning video).
std::vector<cv::Mat> PanningFrames(int count, int step, uint64_t seed) {
  const cv::Size size(160, 120);
  cv::Mat noise(size.height, size.width + count * step + 10, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 6.0);
  cv::Mat world;
  cv::normalize(noise, world, 20, 235, cv::NORM_MINMAX);
  world.convertTo(world, CV_8U);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    frames.push_back(world(cv::Rect(i * step, 0, size.width, size.height)).clone());
  }
  return frames;
}

std::vector<cv::Mat> Thumbnails(const std::vector<cv::Mat>& frames) {
  std::vector<cv::Mat> thumbnails;
  for (const cv::Mat& frame : frames) thumbnails.push_back(MakeThumbnail(frame, 32));
  return thumbnails;
}

TEST(Pairing, ParsesEveryFormAndNamesItBack) {
  EXPECT_EQ(ParsePairing("auto").mode, PairingMode::kAuto);
  EXPECT_EQ(ParsePairing("sequential").mode, PairingMode::kSequential);
  EXPECT_EQ(ParsePairing("exhaustive").mode, PairingMode::kExhaustive);
  const Pairing window = ParsePairing("window:8");
  EXPECT_EQ(window.mode, PairingMode::kWindow);
  EXPECT_EQ(window.window, 8);
  for (const char* name : {"auto", "sequential", "exhaustive", "window:1", "window:16"}) {
    EXPECT_EQ(PairingName(ParsePairing(name)), name);
  }
  for (const char* bad :
       {"foo", "", "window:", "window:0", "window:-3", "window:2x", "Auto", "window:1e3"}) {
    EXPECT_THROW(ParsePairing(bad), Error) << bad;
  }
  try {
    ParsePairing("foo");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'foo'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("window:K"), std::string::npos) << e.what();
  }
}

TEST(Pairing, ThumbnailIsNormalisedAndSimilarityIsCorrelation) {
  const std::vector<cv::Mat> frames = PanningFrames(2, 0, 3);
  const cv::Mat thumbnail = MakeThumbnail(frames[0], 32);
  EXPECT_EQ(thumbnail.rows, 32);
  EXPECT_EQ(thumbnail.cols, 43);  // 160 x 120 -> 42.7 wide
  EXPECT_NEAR(ThumbnailSimilarity(thumbnail, thumbnail), 1.0, 1e-9);
  EXPECT_NEAR(ThumbnailSimilarity(thumbnail, -thumbnail), -1.0, 1e-9);
  const cv::Mat flat = MakeThumbnail(cv::Mat(120, 160, CV_8U, cv::Scalar(90)), 32);
  EXPECT_EQ(cv::countNonZero(flat != 0), 0);
  EXPECT_THROW(ThumbnailSimilarity(thumbnail, MakeThumbnail(frames[0], 16)), Error);
}

TEST(Pairing, AutoPicksSequentialForAVideoAndExhaustiveForItsShuffledFrames) {
  const std::vector<cv::Mat> video = PanningFrames(20, 4, 11);
  const PairingChoice in_order = ChoosePairing(Thumbnails(video), ParsePairing("auto"));
  EXPECT_TRUE(in_order.measured);
  EXPECT_TRUE(in_order.looks_like_video) << in_order.reason;
  EXPECT_EQ(in_order.chosen.mode, PairingMode::kSequential) << in_order.reason;
  EXPECT_GT(in_order.gain, 0.6);

  std::vector<cv::Mat> shuffled = video;
  std::mt19937 rng(5);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  const PairingChoice set = ChoosePairing(Thumbnails(shuffled), ParsePairing("auto"));
  EXPECT_FALSE(set.looks_like_video) << set.reason;
  EXPECT_EQ(set.chosen.mode, PairingMode::kExhaustive) << set.reason;
  EXPECT_LT(set.gain, in_order.gain);

  // Beyond max_exhaustive_frames an image set is matched within a window.
  PairingChoiceOptions options;
  options.max_exhaustive_frames = 10;
  const PairingChoice large = ChoosePairing(Thumbnails(shuffled), ParsePairing("auto"), options);
  EXPECT_EQ(large.chosen.mode, PairingMode::kWindow);
  EXPECT_EQ(large.chosen.window, options.image_set_window);
}

// auto: a video by descriptors over a window of frames; an image set by the patch tracker's
// image-set set-up (descriptors alone made a wrong model of the temple ring, docs/matching.md).
TEST(Pairing, AutoMatchesAVideoByDescriptors) {
  PairingChoice video;
  video.measured = true;
  video.looks_like_video = true;
  video.chosen = {PairingMode::kSequential, 0};
  PairingChoice set = video;
  set.looks_like_video = false;
  set.chosen = {PairingMode::kWindow, 20};  // a large image set
  PairingChoice exhaustive;                 // requested by hand, not measured
  exhaustive.chosen = {PairingMode::kExhaustive, 0};
  PairingChoice window;  // a video with a window asked for
  window.requested = window.chosen = {PairingMode::kWindow, 5};
  EXPECT_TRUE(IsVideo(video));
  EXPECT_TRUE(IsVideo(window));
  EXPECT_FALSE(IsVideo(set));
  EXPECT_FALSE(IsVideo(exhaustive));
  EXPECT_TRUE(MatchesByDescriptors(FeatureMatcher::kAuto, video));
  EXPECT_TRUE(MatchesByDescriptors(FeatureMatcher::kAuto, window));
  EXPECT_FALSE(MatchesByDescriptors(FeatureMatcher::kAuto, set));
  EXPECT_FALSE(MatchesByDescriptors(FeatureMatcher::kAuto, exhaustive));
  EXPECT_TRUE(MatchesByDescriptors(FeatureMatcher::kDescriptors, video));
  EXPECT_FALSE(MatchesByDescriptors(FeatureMatcher::kPatches, exhaustive));
  for (FeatureMatcher m :
       {FeatureMatcher::kAuto, FeatureMatcher::kPatches, FeatureMatcher::kDescriptors}) {
    EXPECT_EQ(ParseFeatureMatcher(FeatureMatcherName(m)), m);
  }
  EXPECT_THROW(ParseFeatureMatcher("sift"), Error);

  TrackerOptions tracker;
  tracker.max_features = 1234;
  tracker.min_response = 0.5f;
  const ImageSetMatchingOptions all =
      ImageSetMatchingOptionsForPairing({PairingMode::kExhaustive, 0}, tracker, 3);
  EXPECT_EQ(all.window, 0);
  EXPECT_EQ(all.max_features, 1234);
  EXPECT_EQ(all.min_response, 0.5f);
  EXPECT_EQ(all.num_threads, 3);
  EXPECT_EQ(ImageSetMatchingOptionsForPairing({PairingMode::kWindow, 7}, tracker, 0).window, 7);
  const ImageSetMatchingOptions sequential =
      ImageSetMatchingOptionsForPairing({PairingMode::kSequential, 0}, tracker, 0);
  EXPECT_EQ(sequential.window, kSequentialDescriptorWindow);
  EXPECT_TRUE(sequential.quadratic_overlap);
  EXPECT_THROW(ImageSetMatchingOptionsForPairing({PairingMode::kAuto, 0}, tracker, 0), Error);
}

TEST(Pairing, RequestedPairingIsKeptAndShortInputsAreSequential) {
  const std::vector<cv::Mat> video = PanningFrames(6, 4, 2);
  const PairingChoice exhaustive = ChoosePairing(Thumbnails(video), ParsePairing("exhaustive"));
  EXPECT_EQ(exhaustive.chosen.mode, PairingMode::kExhaustive);
  EXPECT_FALSE(exhaustive.measured);
  const PairingChoice window = ChoosePairing({}, ParsePairing("window:3"));
  EXPECT_EQ(window.chosen.window, 3);
  const PairingChoice two = ChoosePairing(Thumbnails(PanningFrames(2, 4, 2)), Pairing{});
  EXPECT_EQ(two.chosen.mode, PairingMode::kSequential);
  EXPECT_FALSE(two.measured);
  EXPECT_THROW(ChoosePairing({}, Pairing{PairingMode::kWindow, 0}), Error);
  PairingChoiceOptions bad;
  bad.min_gain = 1.5;
  EXPECT_THROW(ChoosePairing({}, Pairing{}, bad), Error);
}

TEST(Pairing, TrackerOptionsForEachPairing) {
  TrackerOptions base;
  base.prediction = MotionPrediction::kConstantVelocity;
  const TrackerOptions sequential = TrackerOptionsForPairing(ParsePairing("sequential"), 16, base);
  EXPECT_EQ(sequential.match_window, 1);
  EXPECT_EQ(sequential.verify_min_gap, 0);
  EXPECT_EQ(sequential.prediction, MotionPrediction::kConstantVelocity);

  const TrackerOptions window = TrackerOptionsForPairing(ParsePairing("window:4"), 16, base);
  EXPECT_EQ(window.match_window, 4);
  EXPECT_EQ(window.verify_min_gap, 2);
  EXPECT_EQ(TrackerOptionsForPairing(ParsePairing("window:40"), 16, base).match_window, 15);

  const TrackerOptions all = TrackerOptionsForPairing(ParsePairing("exhaustive"), 16, base);
  EXPECT_EQ(all.match_window, 15);  // every pair of 16 frames
  EXPECT_EQ(all.verify_min_gap, 1);
  EXPECT_TRUE(all.match_turned_180);
  EXPECT_EQ(all.prediction, MotionPrediction::kCoarseToFine);
  EXPECT_EQ(all.matcher.max_cost, 800.0);
  EXPECT_NO_THROW(all.Check());
  EXPECT_THROW(TrackerOptionsForPairing(Pairing{}, 16, base), Error);
}

}  // namespace
}  // namespace comic::frontend
