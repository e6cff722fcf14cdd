#include "frontend/matching/track_continuation.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

Feature At(float x, float y) {
  Feature f;
  f.x = x;
  f.y = y;
  return f;
}

cv::Mat Texture(uint64_t seed) {
  cv::Mat noise(200, 240, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Mat gray;
  noise.convertTo(gray, CV_8U, 60, 128);
  return gray;
}

cv::Mat Shifted(const cv::Mat& gray, double dx, double dy) {
  cv::Mat moved;
  cv::warpAffine(gray, moved, cv::Matx23d(1, 0, dx, 0, 1, dy), gray.size(), cv::INTER_LINEAR,
                 cv::BORDER_REFLECT);
  return moved;
}

PatchAlignment Trusted(float x, float y, float residual = 10.0f) {
  PatchAlignment a;
  a.converged = true;
  a.position = {x, y};
  a.residual = residual;
  a.correlation = 0.95f;
  return a;
}

TEST(TrackContinuation, AlignFeaturesFollowsAKnownShiftFromThePrediction) {
  const cv::Mat gray1 = Texture(1);
  const cv::Mat gray2 = Shifted(gray1, 12.0, -6.0);
  PatchAlignmentOptions options;
  const ImagePyramid p1(gray1, options.levels), p2(gray2, options.levels);
  const FeatureSet features = {At(80, 80), At(150, 120), At(120, 60)};
  SearchRegions predicted;
  predicted.centres = {{90, 75}, {160, 115}, {130, 55}};  // 2 px off the truth, as a prediction
  predicted.radii = {20, 20, 20};
  const std::vector<PatchAlignment> aligned =
      AlignFeatures(features, p1, p2, predicted, {}, options);
  ASSERT_EQ(aligned.size(), 3u);
  for (size_t i = 0; i < features.size(); ++i) {
    ASSERT_TRUE(aligned[i].converged) << i;
    EXPECT_NEAR(aligned[i].position.x, features[i].x + 12.0, 0.1) << i;
    EXPECT_NEAR(aligned[i].position.y, features[i].y - 6.0, 0.1) << i;
    EXPECT_TRUE(IsTrusted(aligned[i], TrackContinuationOptions())) << i;
  }
  // With a forward-backward check the same alignments pass.
  options.max_forward_backward_px = 0.5;
  const std::vector<PatchAlignment> checked =
      AlignFeatures(features, p1, p2, predicted, {}, options);
  for (size_t i = 0; i < features.size(); ++i) EXPECT_TRUE(checked[i].converged) << i;
}

TEST(TrackContinuation, AnUnrelatedFrameIsNotTrusted) {
  const cv::Mat gray1 = Texture(2), gray2 = Texture(3);
  PatchAlignmentOptions options;
  const ImagePyramid p1(gray1, options.levels), p2(gray2, options.levels);
  const FeatureSet features = {At(80, 80), At(150, 120), At(120, 60), At(60, 140)};
  const std::vector<PatchAlignment> aligned = AlignFeatures(features, p1, p2, {}, {}, options);
  for (size_t i = 0; i < features.size(); ++i) {
    EXPECT_FALSE(IsTrusted(aligned[i], TrackContinuationOptions())) << i;
  }
}

TEST(TrackContinuation, GuidedSearchUsesTrustedAlignmentsOnly) {
  const FeatureSet features = {At(10, 10), At(50, 50)};
  SearchRegions predicted;
  predicted.centres = {{12, 12}, {55, 55}};
  predicted.radii = {20, 30};
  PatchAlignment untrusted = Trusted(60, 60);
  untrusted.correlation = 0.1f;
  TrackContinuationOptions options;
  const SearchRegions search =
      GuidedSearchRegions(features, predicted, 20.0, {Trusted(13, 11), untrusted}, options);
  EXPECT_EQ(search.centres[0], cv::Point2f(13, 11));
  EXPECT_FLOAT_EQ(search.radii[0], static_cast<float>(options.aligned_radius));
  EXPECT_EQ(search.centres[1], cv::Point2f(55, 55));
  EXPECT_FLOAT_EQ(search.radii[1], 30.0f);
  // Without a prediction: own position and the default radius.
  const SearchRegions unpredicted =
      GuidedSearchRegions(features, {}, 25.0, {PatchAlignment(), untrusted}, options);
  EXPECT_EQ(unpredicted.centres[0], cv::Point2f(10, 10));
  EXPECT_FLOAT_EQ(unpredicted.radii[1], 25.0f);
  EXPECT_THROW(GuidedSearchRegions(features, predicted, 20.0, {Trusted(1, 1)}, options), Error);
}

TEST(TrackContinuation, ContinuesUnmatchedTrustedFeaturesUpToTheLimit) {
  const FeatureSet features1 = {At(10, 10), At(50, 50), At(90, 90), At(130, 130), At(170, 170)};
  const FeatureSet features2 = {At(12, 10)};
  const std::vector<PatchMatch> accepted = {{0, 0, 5.0f}};
  PatchAlignment untrusted = Trusted(92, 90);
  untrusted.residual = 1e4f;
  const std::vector<PatchAlignment> aligned = {Trusted(12, 10), Trusted(52, 51), untrusted,
                                               Trusted(132, 130), Trusted(172, 170)};
  const std::vector<int> runs1 = {0, 0, 0, 2, 1};
  TrackContinuationOptions options;
  options.max_continued_frames = 2;
  const std::vector<Continuation> continued =
      ContinueUnmatched(features1, runs1, features2, accepted, aligned, options);
  // 0 is matched, 2 untrusted, 3 at its limit: 1 and 4 continue, at their aligned positions.
  ASSERT_EQ(continued.size(), 2u);
  EXPECT_EQ(continued[0].index1, 1);
  EXPECT_EQ(continued[0].feature.Position(), cv::Point2f(52, 51));
  EXPECT_EQ(continued[1].index1, 4);
  EXPECT_EQ(continued[1].feature.Position(), cv::Point2f(172, 170));
  // max_continued_frames = 0: never.
  options.max_continued_frames = 0;
  EXPECT_TRUE(ContinueUnmatched(features1, runs1, features2, accepted, aligned, options).empty());
}

TEST(TrackContinuation, TwoTracksDoNotContinueOntoOnePoint) {
  const FeatureSet features1 = {At(10, 10), At(14, 10), At(40, 40), At(80, 80)};
  const FeatureSet features2 = {At(60, 60)};
  const std::vector<PatchMatch> accepted = {{3, 0, 5.0f}};
  // 0 and 1 align within 1 px of each other (the lower residual wins); 2 lands next to the
  // feature track 3 holds.
  const std::vector<PatchAlignment> aligned = {Trusted(20, 20, 50.0f), Trusted(20.5f, 20, 10.0f),
                                               Trusted(60.5f, 60, 1.0f), Trusted(60, 60)};
  TrackContinuationOptions options;
  options.max_continued_frames = 5;
  const std::vector<Continuation> continued =
      ContinueUnmatched(features1, {0, 0, 0, 0}, features2, accepted, aligned, options);
  ASSERT_EQ(continued.size(), 1u);
  EXPECT_EQ(continued[0].index1, 1);
}

TEST(TrackContinuation, ACurveMovesWithItsFeature) {
  Feature f = At(10, 10);
  f.curve = {{8, 10}, {10, 12}};
  TrackContinuationOptions options;
  options.max_continued_frames = 1;
  const std::vector<Continuation> continued =
      ContinueUnmatched({f}, {0}, {}, {}, {Trusted(13, 14)}, options);
  ASSERT_EQ(continued.size(), 1u);
  EXPECT_EQ(continued[0].feature.curve[0], cv::Point2f(11, 14));
  EXPECT_EQ(continued[0].feature.curve[1], cv::Point2f(13, 16));
}

TEST(TrackContinuation, PredictFromNeighboursTakesTheMedianOfTheNearest) {
  const std::vector<MotionSample> samples = {
      {{0, 0}, {1, 0}}, {{2, 0}, {3, 0}}, {{4, 0}, {2, 0}}, {{100, 100}, {50, 50}}};
  const std::vector<cv::Point2f> predicted =
      PredictFromNeighbours({{1, 0}, {300, 300}}, samples, 3, 10.0);
  EXPECT_EQ(predicted[0], cv::Point2f(3, 0));      // median of 1, 3, 2
  EXPECT_EQ(predicted[1], cv::Point2f(300, 300));  // no sample near: unchanged
}

TEST(TrackContinuation, OptionsAndSizesAreChecked) {
  TrackContinuationOptions options;
  options.aligned_radius = 0;
  EXPECT_THROW(options.Check(), Error);
  options = TrackContinuationOptions();
  options.max_continued_frames = -1;
  EXPECT_THROW(options.Check(), Error);
  options = TrackContinuationOptions();
  options.bridge_frames = -1;
  EXPECT_THROW(options.Check(), Error);
  options = TrackContinuationOptions();
  options.max_continued_frames = 1;
  EXPECT_THROW(ContinueUnmatched({At(1, 1)}, {}, {}, {}, {Trusted(1, 1)}, options), Error);
  EXPECT_THROW(ContinueUnmatched({At(1, 1)}, {0}, {}, {{0, 3, 1.0f}}, {Trusted(1, 1)}, options),
               Error);
}

}  // namespace
}  // namespace comic::frontend
