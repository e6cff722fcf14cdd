#include "frontend/matching/track_side_change.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

// Smooth random texture of grey levels mean ± 25, a fixed seed.
cv::Mat Texture(cv::Size size, double mean, uint64_t seed) {
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, -1.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::Mat texture;
  noise.convertTo(texture, CV_8U, 25.0 / 0.35, mean);
  return texture;
}

// Frame k: a textured bright square [40, 90)² over a textured dark background; the square stays,
// the background moves `background_step` px per frame to the right (a background moving behind
// an object's corner).
cv::Mat Frame(int k, int background_step) {
  const cv::Mat background = Texture(cv::Size(260, 130), 60, 7);
  cv::Mat frame = background(cv::Rect(100 - k * background_step, 0, 130, 130)).clone();
  Texture(cv::Size(50, 50), 190, 11).copyTo(frame(cv::Rect(40, 40, 50, 50)));
  return frame;
}

// One track of `num_frames` observations of the square's top-left corner.
FeatureTracks CornerTrack(int num_frames) {
  FeatureTracks tracks;
  tracks.image_size = cv::Size(130, 130);
  Track track;
  for (int k = 0; k < num_frames; ++k) {
    Feature corner;
    corner.x = 40.0f;
    corner.y = 40.0f;
    tracks.features.push_back({corner});
    track.observations.push_back({k, 0});
  }
  tracks.tracks.push_back(track);
  return tracks;
}

TEST(TrackSideChange, TheObjectSideKeepsItsLookAndTheBackgroundSideDoesNot) {
  const FeatureTracks tracks = CornerTrack(5);
  const std::vector<SideChange> changes =
      MeasureTrackSideChanges(tracks, [](int k) { return Frame(k, 3); }, {});
  ASSERT_EQ(changes.size(), 1u);
  const SideChange& c = changes[0];
  ASSERT_TRUE(c.measured);
  EXPECT_EQ(c.num_compared, 4);
  EXPECT_EQ(c.object_side, PatchSide::kPlus);  // the corner points into the bright square
  EXPECT_LT(c.plus_mean, 0.05f);               // the square, the same pixels every frame
  EXPECT_GT(c.minus_mean, 0.5f);               // the background moved 3-12 px behind it
  EXPECT_GT(c.minus_last, 0.5f);
}

TEST(TrackSideChange, BothSidesKeepTheirLookWhenNothingMovesBehind) {
  const FeatureTracks tracks = CornerTrack(4);
  const std::vector<SideChange> changes =
      MeasureTrackSideChanges(tracks, [](int k) { return Frame(k, 0); }, {});
  ASSERT_TRUE(changes[0].measured);
  EXPECT_LT(changes[0].plus_mean, 0.05f);
  EXPECT_LT(changes[0].minus_mean, 0.05f);
}

TEST(TrackSideChange, ShortTracksAndFlatPatchesAreNotMeasured) {
  const std::vector<SideChange> short_track =
      MeasureTrackSideChanges(CornerTrack(2), [](int k) { return Frame(k, 3); }, {});
  EXPECT_FALSE(short_track[0].measured);
  const std::vector<SideChange> flat = MeasureTrackSideChanges(
      CornerTrack(4), [](int) { return cv::Mat(130, 130, CV_8UC1, cv::Scalar(90)); }, {});
  EXPECT_FALSE(flat[0].measured);
}

TEST(TrackSideChange, RefusesBadOptionsAndFramesOfTheWrongSize) {
  TrackSideChangeOptions options;
  options.min_track_length = 1;
  EXPECT_THROW(MeasureTrackSideChanges(
                   CornerTrack(3), [](int k) { return Frame(k, 0); }, options),
               Error);
  EXPECT_THROW(
      MeasureTrackSideChanges(CornerTrack(3), [](int) { return cv::Mat(64, 64, CV_8UC1); }, {}),
      Error);
}

}  // namespace
}  // namespace comic::frontend
