// Keyframes from tracks: a slow stretch keeps every max_frame_gap-th frame, a fast stretch one
// per min_median_motion_px of image motion, and tracks that end force a keyframe.
#include "sfm/keyframe_selection.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

// `points` tracks seen in every frame; frame f moves them all by speed(f) pixels along x.
frontend::FeatureTracks MovingTracks(int frames, int points, double (*speed)(int)) {
  frontend::FeatureTracks tracks;
  tracks.image_size = cv::Size(640, 480);
  tracks.features.resize(frames);
  tracks.tracks.resize(points);
  double offset = 0.0;
  for (int f = 0; f < frames; ++f) {
    if (f > 0) offset += speed(f);
    for (int p = 0; p < points; ++p) {
      frontend::Feature feature;
      feature.x = static_cast<float>(10 + 5 * p + offset);
      feature.y = static_cast<float>(100 + p);
      tracks.features[f].push_back(feature);
      tracks.tracks[p].observations.push_back({f, p});
    }
  }
  tracks.Check();
  return tracks;
}

double SlowThenFast(int frame) { return frame < 50 ? 0.5 : 6.0; }

TEST(KeyframeSelection, SlowStretchByGapFastStretchByMotion) {
  const frontend::FeatureTracks tracks = MovingTracks(100, 40, SlowThenFast);
  KeyframeOptions options;  // 12 px, gap 10
  const std::vector<KeyframeDecision> d = SelectKeyframes(tracks, options);
  ASSERT_EQ(d.size(), 100u);
  EXPECT_TRUE(d[0].keyframe);
  EXPECT_EQ(d[0].reason, KeyframeReason::kFirst);
  int slow = 0;
  int fast = 0;
  for (int f = 1; f < 100; ++f) {
    if (!d[f].keyframe) {
      EXPECT_LT(d[f].median_motion_px, options.min_median_motion_px) << f;
      continue;
    }
    if (f < 50) {
      ++slow;
      EXPECT_EQ(d[f].reason, KeyframeReason::kFrameGap) << f;
      EXPECT_EQ(f - d[f].last_keyframe, options.max_frame_gap) << f;
    } else if (f > 52 && f < 99) {
      ++fast;
      EXPECT_EQ(d[f].reason, KeyframeReason::kMotion) << f;
      EXPECT_EQ(f - d[f].last_keyframe, 2) << f;  // 6 px a frame, 12 px needed
    }
  }
  EXPECT_EQ(slow, 4);  // 10, 20, 30, 40
  EXPECT_GE(fast, 20);
  EXPECT_TRUE(d[99].keyframe);
}

TEST(KeyframeSelection, EndingTracksForceAKeyframe) {
  frontend::FeatureTracks tracks = MovingTracks(8, 20, [](int) { return 0.1; });
  // From frame 4 on, half of the tracks are gone.
  for (int p = 0; p < 10; ++p) tracks.tracks[p].observations.resize(4);
  KeyframeOptions options;
  const std::vector<KeyframeDecision> d = SelectKeyframes(tracks, options);
  for (int f = 1; f < 4; ++f) EXPECT_FALSE(d[f].keyframe) << f;
  EXPECT_TRUE(d[4].keyframe);
  EXPECT_EQ(d[4].reason, KeyframeReason::kSharedTracks);
  EXPECT_DOUBLE_EQ(d[4].shared_fraction, 0.5);
  // Frame 5 compares with frame 4, which sees only the surviving tracks.
  EXPECT_FALSE(d[5].keyframe);
  EXPECT_DOUBLE_EQ(d[5].shared_fraction, 1.0);
  EXPECT_EQ(d[7].reason, KeyframeReason::kLast);
}

TEST(KeyframeSelection, RejectsBadOptions) {
  const frontend::FeatureTracks tracks = MovingTracks(3, 5, [](int) { return 1.0; });
  KeyframeOptions options;
  options.min_shared_fraction = 1.5;
  EXPECT_THROW(SelectKeyframes(tracks, options), Error);
  options = KeyframeOptions();
  options.max_frame_gap = 0;
  EXPECT_THROW(SelectKeyframes(tracks, options), Error);
  EXPECT_STREQ(KeyframeReasonName(KeyframeReason::kMotion), "motion");
}

}  // namespace
}  // namespace comic::sfm
