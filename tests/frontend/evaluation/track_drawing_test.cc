#include "frontend/evaluation/track_drawing.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

TEST(TrackDrawing, ColoursTracksByLabelAndMarksUntrackedFeatures) {
  FeatureTracks tracks;
  tracks.features.resize(2, FeatureSet(2));
  tracks.features[0][0].x = 20, tracks.features[0][0].y = 20;
  tracks.features[1][0].x = 30, tracks.features[1][0].y = 20;  // tracked, boundary
  tracks.features[0][1].x = 60, tracks.features[0][1].y = 60;
  tracks.features[1][1].x = 70, tracks.features[1][1].y = 40;  // untracked
  tracks.tracks = {Track{{{0, 0}, {1, 0}}}};
  const cv::Mat background(80, 100, CV_8UC3, cv::Scalar(50, 50, 50));
  const cv::Mat drawn =
      DrawTracks(background, tracks, 1, {RegionLabel::kBoundary, RegionLabel::kInterior});
  EXPECT_EQ(drawn.at<cv::Vec3b>(20, 30), cv::Vec3b(0, 0, 255));  // the track's dot, red
  EXPECT_GT(drawn.at<cv::Vec3b>(20, 25)[2], 200);  // its path from (20, 20), anti-aliased
  EXPECT_LT(drawn.at<cv::Vec3b>(20, 25)[1], 60);
  EXPECT_EQ(drawn.at<cv::Vec3b>(40, 70), cv::Vec3b(160, 160, 160));    // grey cross
  EXPECT_EQ(drawn.at<cv::Vec3b>(70, 10), cv::Vec3b(50, 50, 50));       // untouched
  EXPECT_EQ(background.at<cv::Vec3b>(20, 30), cv::Vec3b(50, 50, 50));  // input not modified
  EXPECT_THROW(DrawTracks(background, tracks, 2), Error);
  EXPECT_THROW(DrawTracks(background, tracks, 1, {RegionLabel::kBoundary}), Error);
  EXPECT_THROW(DrawTracks(cv::Mat(80, 100, CV_8UC1), tracks, 1), Error);
}

}  // namespace
}  // namespace comic::frontend
