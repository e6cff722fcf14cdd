#include "frontend/evaluation/track_survival.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "frontend/baselines/harris_detector.h"
#include "io/core/error.h"

namespace comic::frontend {
namespace {

cv::Mat Texture(cv::Size size, uint64_t seed) {
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Mat out;
  noise.convertTo(out, CV_8U, 60, 128);
  return out;
}

// A textured scene translating by `step` per frame.
std::vector<cv::Mat> TranslatingFrames(int count, cv::Point step) {
  const cv::Size size(200, 150);
  const int margin = 60;
  const cv::Mat world = Texture({size.width + 2 * margin, size.height + 2 * margin}, 9);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    frames.push_back(
        world(cv::Rect(margin - i * step.x, margin - i * step.y, size.width, size.height)).clone());
  }
  return frames;
}

TEST(TrackSurvival, StartFramesLeaveTheHorizon) {
  EXPECT_EQ(SurvivalStartFrames(150, 10, 10),
            (std::vector<int>{0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130}));
  EXPECT_EQ(SurvivalStartFrames(5, 10, 10), (std::vector<int>{0}));
  EXPECT_TRUE(SurvivalStartFrames(0, 10, 10).empty());
  EXPECT_THROW(SurvivalStartFrames(10, 0, 1), Error);
}

TEST(TrackSurvival, SummaryCountsSharesAndLengths) {
  const SurvivalSummary s = SummariseSurvival({0, 1, 5, 10, 4});
  EXPECT_EQ(s.num_features, 5);
  EXPECT_DOUBLE_EQ(s.share_followed[0], 0.8);
  EXPECT_DOUBLE_EQ(s.share_followed[1], 0.4);
  EXPECT_DOUBLE_EQ(s.share_followed[2], 0.2);
  EXPECT_DOUBLE_EQ(s.mean_frames_followed, 4.0);
  // Followed features: lengths 2, 6, 11, 5.
  EXPECT_DOUBLE_EQ(s.mean_track_length, 6.0);
  EXPECT_EQ(SummariseSurvival({}).num_features, 0);
}

TEST(TrackSurvival, LkFollowsAKnownShift) {
  const std::vector<cv::Mat> frames = TranslatingFrames(2, {4, -3});
  const std::vector<cv::Point2f> points = {{60, 60}, {100, 80}, {140, 70}};
  const LkFlow flow = TrackPointsLk(frames[0], frames[1], points, LkReferenceOptions());
  for (size_t i = 0; i < points.size(); ++i) {
    ASSERT_TRUE(flow.valid[i]) << i;
    EXPECT_NEAR(flow.positions[i].x, points[i].x + 4, 0.1) << i;
    EXPECT_NEAR(flow.positions[i].y, points[i].y - 3, 0.1) << i;
  }
  // A point taken out of the image is not followed.
  const LkFlow out = TrackPointsLk(frames[0], frames[1], {{197, 70}}, LkReferenceOptions());
  EXPECT_FALSE(out.valid[0]);
  EXPECT_TRUE(out.outside[0]);
  EXPECT_THROW(TrackPointsLk(frames[0], cv::Mat(10, 10, CV_8UC1), points, LkReferenceOptions()),
               Error);
}

TEST(TrackSurvival, OursAndLkOnATranslatingScene) {
  const std::vector<cv::Mat> frames = TranslatingFrames(6, {2, 1});
  const HarrisDetector harris;
  TrackerOptions options;
  options.min_response = 1.0f;
  const TrackingResult result = TrackFrames(frames, harris, options);
  const std::vector<int> starts = SurvivalStartFrames(6, 10, 5);
  ASSERT_EQ(starts, (std::vector<int>{0}));
  const std::vector<int> ours = FramesFollowedFrom(result, starts);
  const std::vector<int> lk = LkFramesFollowedFrom(frames, result, starts, LkReferenceOptions());
  ASSERT_EQ(ours.size(), result.tracks.features[0].size());
  ASSERT_EQ(lk.size(), ours.size());
  for (int n : ours) EXPECT_LE(n, 5);
  // An exact translation of texture: most features are followed to the end by both.
  EXPECT_GT(SummariseSurvival(ours).share_followed[1], 0.7);
  EXPECT_GT(SummariseSurvival(lk).share_followed[1], 0.7);
  // MeanTrackLength is report.json's: observations per track.
  size_t observations = 0;
  for (const Track& t : result.tracks.tracks) observations += t.Length();
  EXPECT_DOUBLE_EQ(MeanTrackLength(result.tracks),
                   static_cast<double>(observations) / result.tracks.tracks.size());
  EXPECT_THROW(LkFramesFollowedFrom({frames[0]}, result, starts, LkReferenceOptions()), Error);
}

TEST(TrackSurvival, LossSplitAccountsForEveryFeature) {
  const std::vector<cv::Mat> frames = TranslatingFrames(3, {3, 0});
  const HarrisDetector harris;
  TrackerOptions options;
  options.min_response = 1.0f;
  const TrackingResult result = TrackFrames(frames, harris, options);
  const LossSplit split = SplitLosses(result, 0, frames[0], frames[1], harris.Detect(frames[1]),
                                      LkReferenceOptions(), LossSplitOptions());
  EXPECT_EQ(split.num_features, static_cast<int>(result.tracks.features[0].size()));
  int total = 0;
  for (const auto& c : split.counts) total += c[0] + c[1];
  EXPECT_EQ(total, split.num_features);
  const int continued = split.counts[static_cast<int>(FeatureFate::kContinued)][0] +
                        split.counts[static_cast<int>(FeatureFate::kContinued)][1];
  EXPECT_GT(continued, split.num_features / 2);
  EXPECT_THROW(
      SplitLosses(result, 2, frames[2], frames[2], {}, LkReferenceOptions(), LossSplitOptions()),
      Error);
}

}  // namespace
}  // namespace comic::frontend
