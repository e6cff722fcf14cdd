#include "frontend/matching/combined_tracking.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <set>

#include "frontend/detector_factory.h"
#include "io/core/error.h"

namespace comic::frontend {
namespace {

// Frames of a textured scene translating by (3, 1) px per frame.
std::vector<cv::Mat> TranslatingFrames(int count) {
  const cv::Size size(200, 150);
  cv::Mat noise(size.height + 40, size.width + 40, CV_32F);
  cv::RNG rng(23);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Mat world;
  cv::normalize(noise, world, 10, 245, cv::NORM_MINMAX);
  world.convertTo(world, CV_8U);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    frames.push_back(world(cv::Rect(30 - 3 * i, 30 - i, size.width, size.height)).clone());
  }
  return frames;
}

TrackerOptions Options() {
  TrackerOptions options;
  options.max_features = 300;
  return options;
}

TEST(CombinedTracking, TracksHoldFeaturesOfBothDetectorsNeverMixedNorTwicePerFrame) {
  const std::vector<cv::Mat> frames = TranslatingFrames(5);
  const auto combined = MakeDetector("harris+hessian");
  ASSERT_EQ(combined->Name(), "harris+hessian");
  const TrackingResult result = TrackFramesWithDetector(frames, *combined, Options());
  const FeatureTracks& tracks = result.tracks;
  EXPECT_EQ(tracks.detector_name, "harris+hessian");
  EXPECT_NO_THROW(tracks.Check());  // strictly increasing frames: never two of one frame

  // The same frames tracked by each detector alone give the parts.
  std::vector<TrackingResult> parts;
  for (const char* name : {"harris", "hessian"}) {
    parts.push_back(TrackFrames(frames, *MakeDetector(name), Options()));
  }
  ASSERT_GT(parts[0].tracks.tracks.size(), 20u);
  ASSERT_GT(parts[1].tracks.tracks.size(), 20u);
  EXPECT_EQ(tracks.tracks.size(), parts[0].tracks.tracks.size() + parts[1].tracks.tracks.size());

  std::set<int> detectors_seen;
  for (const Track& track : tracks.tracks) {
    std::set<int> parts_of_track;
    std::set<int> frames_of_track;
    for (const TrackObservation& obs : track.observations) {
      const int first_hessian = FirstFeatureOfEachPart(parts, obs.frame)[1];
      parts_of_track.insert(obs.feature >= first_hessian ? 1 : 0);
      EXPECT_TRUE(frames_of_track.insert(obs.frame).second) << "two features of one frame";
    }
    EXPECT_EQ(parts_of_track.size(), 1u) << "a track mixes two detectors";
    detectors_seen.insert(*parts_of_track.begin());
  }
  EXPECT_EQ(detectors_seen, (std::set<int>{0, 1}));

  // Every feature is its own detector's: frame 2's features are harris's then hessian's.
  const FeatureSet& merged = tracks.features[2];
  ASSERT_EQ(merged.size(), parts[0].tracks.features[2].size() + parts[1].tracks.features[2].size());
  const Feature& first_hessian = merged[parts[0].tracks.features[2].size()];
  EXPECT_EQ(first_hessian.x, parts[1].tracks.features[2][0].x);
  EXPECT_EQ(first_hessian.scale, parts[1].tracks.features[2][0].scale);
}

TEST(CombinedTracking, SingleDetectorIsTrackedAsIsAndMergeChecksParts) {
  const std::vector<cv::Mat> frames = TranslatingFrames(3);
  const auto harris = MakeDetector("harris");
  const TrackingResult direct = TrackFrames(frames, *harris, Options());
  const TrackingResult through = TrackFramesWithDetector(frames, *harris, Options());
  ASSERT_EQ(direct.tracks.tracks.size(), through.tracks.tracks.size());
  for (size_t t = 0; t < direct.tracks.tracks.size(); ++t) {
    EXPECT_EQ(direct.tracks.tracks[t].observations.size(),
              through.tracks.tracks[t].observations.size());
  }
  std::vector<TrackingResult> mismatched = {
      direct, TrackFrames({frames[0], frames[1]}, *harris, Options())};
  EXPECT_THROW(MergeTrackingResults(mismatched, "x"), Error);
  EXPECT_THROW(MergeTrackingResults({}, "x"), Error);
}

TEST(CombinedTracking, IsDeterministic) {
  const std::vector<cv::Mat> frames = TranslatingFrames(4);
  const auto combined = MakeDetector("fast+hessian");
  const FeatureTracks a = TrackFramesWithDetector(frames, *combined, Options()).tracks;
  const FeatureTracks b = TrackFramesWithDetector(frames, *combined, Options()).tracks;
  ASSERT_EQ(a.tracks.size(), b.tracks.size());
  for (size_t t = 0; t < a.tracks.size(); ++t) {
    ASSERT_EQ(a.tracks[t].observations.size(), b.tracks[t].observations.size());
    for (size_t k = 0; k < a.tracks[t].observations.size(); ++k) {
      EXPECT_EQ(a.tracks[t].observations[k].feature, b.tracks[t].observations[k].feature);
    }
  }
}

}  // namespace
}  // namespace comic::frontend
