#include "frontend/matching/track.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

FeatureTracks ThreeFrames() {
  FeatureTracks tracks;
  tracks.features.resize(3);
  for (auto& frame : tracks.features) frame.resize(4);
  tracks.tracks.push_back({{{0, 0}, {1, 2}, {2, 1}}});
  tracks.tracks.push_back({{{1, 0}, {2, 3}}});
  return tracks;
}

TEST(FeatureTracks, ValidTracksPass) {
  const FeatureTracks tracks = ThreeFrames();
  EXPECT_NO_THROW(tracks.Check());
  EXPECT_EQ(tracks.tracks[0].Length(), 3u);
  EXPECT_EQ(tracks.tracks[0].FirstFrame(), 0);
  EXPECT_EQ(tracks.tracks[1].LastFrame(), 2);
}

TEST(FeatureTracks, ATracksFeatureInAFrameIsFoundOrMinusOne) {
  const FeatureTracks tracks = ThreeFrames();
  EXPECT_EQ(tracks.tracks[0].FeatureInFrame(0), 0);
  EXPECT_EQ(tracks.tracks[0].FeatureInFrame(1), 2);
  EXPECT_EQ(tracks.tracks[0].FeatureInFrame(2), 1);
  EXPECT_EQ(tracks.tracks[1].FeatureInFrame(0), -1);  // before the track starts
  EXPECT_EQ(tracks.tracks[1].FeatureInFrame(3), -1);  // after it ends
  Track with_gap{{{0, 1}, {2, 0}}};
  EXPECT_EQ(with_gap.FeatureInFrame(1), -1);  // a frame the track skips
  EXPECT_EQ(with_gap.FeatureInFrame(2), 0);
  EXPECT_EQ(Track{}.FeatureInFrame(0), -1);
}

TEST(FeatureTracks, TwoFeaturesOfOneFrameInATrackAreRejected) {
  FeatureTracks tracks = ThreeFrames();
  tracks.tracks[0].observations.push_back({2, 2});  // frame 2 again
  EXPECT_THROW(tracks.Check(), Error);
}

TEST(FeatureTracks, FeatureSharedByTwoTracksIsRejected) {
  FeatureTracks tracks = ThreeFrames();
  tracks.tracks[1].observations[1] = {2, 1};  // already in track 0
  EXPECT_THROW(tracks.Check(), Error);
}

TEST(FeatureTracks, OutOfRangeIndicesAreRejected) {
  FeatureTracks tracks = ThreeFrames();
  tracks.tracks[1].observations[1] = {3, 0};
  EXPECT_THROW(tracks.Check(), Error);
  tracks = ThreeFrames();
  tracks.tracks[1].observations[1] = {2, 4};
  EXPECT_THROW(tracks.Check(), Error);
  tracks = ThreeFrames();
  tracks.frame_names = {"a", "b"};
  EXPECT_THROW(tracks.Check(), Error);
}

TEST(FeatureTracks, DescriptorsAreOneRowOf128BytesPerFeatureOfEveryFrame) {
  FeatureTracks tracks = ThreeFrames();
  EXPECT_FALSE(tracks.HasDescriptors());
  tracks.descriptors.assign(3, cv::Mat(4, 128, CV_8UC1, cv::Scalar(1)));
  EXPECT_TRUE(tracks.HasDescriptors());
  EXPECT_NO_THROW(tracks.Check());
  tracks.descriptors.pop_back();  // a frame without
  EXPECT_THROW(tracks.Check(), Error);
  tracks.descriptors.push_back(cv::Mat(3, 128, CV_8UC1));  // a row short
  EXPECT_THROW(tracks.Check(), Error);
  tracks.descriptors.back() = cv::Mat(4, 64, CV_8UC1);
  EXPECT_THROW(tracks.Check(), Error);
  tracks.descriptors.back() = cv::Mat(4, 128, CV_32F);
  EXPECT_THROW(tracks.Check(), Error);
  tracks.features[2].clear();  // a frame without features: no rows, any empty matrix
  tracks.tracks.clear();
  tracks.descriptors.back() = cv::Mat();
  EXPECT_NO_THROW(tracks.Check());
}

}  // namespace
}  // namespace comic::frontend
