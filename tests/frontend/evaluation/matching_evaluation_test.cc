#include "frontend/evaluation/matching_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

constexpr RegionLabel B = RegionLabel::kBoundary;
constexpr RegionLabel I = RegionLabel::kInterior;
constexpr RegionLabel O = RegionLabel::kOutside;

Track MakeTrack(std::vector<TrackObservation> observations) { return Track{observations}; }

// Seven frames, hand-built tracks (frame, feature):
//   A: 0:0 1:0 2:0 3:0 4:0 5:2 6:0    through all frames
//   B: 0:1 1:1 2:1 3:1                ends after 3 frames
//   C: 0:2 1:2 2:2 3:2 4:2 5:3        exactly 5 frames on
//   D: 0:3 1:3 2:3 3:3 4:3 5:4 6:2    outside the region: never counted
//   E: 5:0 6:1
// Labels: frame 0: B B I O; frame 5: I B O O O; all others I.
struct Fixture {
  FeatureTracks tracks;
  std::vector<std::vector<RegionLabel>> labels;
};

Fixture MakeFixture() {
  Fixture fx;
  fx.tracks.features.resize(7, FeatureSet(4));
  fx.tracks.features[5].resize(5);
  fx.tracks.tracks = {
      MakeTrack({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 2}, {6, 0}}),
      MakeTrack({{0, 1}, {1, 1}, {2, 1}, {3, 1}}),
      MakeTrack({{0, 2}, {1, 2}, {2, 2}, {3, 2}, {4, 2}, {5, 3}}),
      MakeTrack({{0, 3}, {1, 3}, {2, 3}, {3, 3}, {4, 3}, {5, 4}, {6, 2}}),
      MakeTrack({{5, 0}, {6, 1}}),
  };
  fx.tracks.Check();
  for (size_t f = 0; f < 7; ++f) fx.labels.emplace_back(fx.tracks.features[f].size(), I);
  fx.labels[0] = {B, B, I, O};
  fx.labels[5] = {I, B, O, O, O};
  return fx;
}

TEST(MatchingEvaluation, ResMAndMScoreForNEqualsFiveByHand) {
  const Fixture fx = MakeFixture();
  const MatchingScores s = ComputeMatchingScores(fx.tracks, fx.labels, {5, 5});
  ASSERT_EQ(s.samples.size(), 1u);  // start frame 0 only (5 + 5 > 6)
  EXPECT_EQ(s.samples[0].start_frame, 0);
  // Boundary: features 0 (survives) and 1 (does not): ResM 1, N 2.
  EXPECT_DOUBLE_EQ(s.boundary.mean_res_m, 1.0);
  EXPECT_DOUBLE_EQ(s.boundary.mean_detections, 2.0);
  EXPECT_DOUBLE_EQ(s.boundary.mean_m_score, 0.5);
  // Non-boundary: feature 2 survives exactly 5 frames.
  EXPECT_DOUBLE_EQ(s.non_boundary.mean_res_m, 1.0);
  EXPECT_DOUBLE_EQ(s.non_boundary.mean_m_score, 1.0);
  // Overall: 2 of 3 (feature 3 is outside the region and left out).
  EXPECT_DOUBLE_EQ(s.overall.mean_res_m, 2.0);
  EXPECT_DOUBLE_EQ(s.overall.mean_m_score, 2.0 / 3.0);
}

TEST(MatchingEvaluation, ResMAndMScoreForNEqualsOneAveragedOverStartFrames) {
  const Fixture fx = MakeFixture();
  const MatchingScores s = ComputeMatchingScores(fx.tracks, fx.labels, {1, 5});
  ASSERT_EQ(s.samples.size(), 2u);  // start frames 0 and 5
  // Frame 0: boundary 2/2, interior 1/1, overall 3/3. Frame 5: boundary 0/1 (feature 1 is not
  // matched on), interior 1/1 (E), overall 1/2.
  EXPECT_DOUBLE_EQ(s.boundary.mean_m_score, (1.0 + 0.0) / 2);
  EXPECT_DOUBLE_EQ(s.boundary.mean_res_m, (2.0 + 0.0) / 2);
  EXPECT_DOUBLE_EQ(s.non_boundary.mean_m_score, 1.0);
  EXPECT_DOUBLE_EQ(s.overall.mean_m_score, (1.0 + 0.5) / 2);
  EXPECT_DOUBLE_EQ(s.overall.mean_res_m, (3.0 + 1.0) / 2);
  EXPECT_DOUBLE_EQ(s.overall.pooled_m_score, 4.0 / 5.0);
  EXPECT_EQ(s.overall.scored_frames, 2);
}

TEST(MatchingEvaluation, WithoutLabelsEveryFeatureIsOverall) {
  const Fixture fx = MakeFixture();
  const MatchingScores s = ComputeMatchingScores(fx.tracks, {}, {5, 5});
  EXPECT_DOUBLE_EQ(s.overall.mean_m_score, 3.0 / 4.0);  // A, C and D survive 5 frames
  EXPECT_TRUE(std::isnan(s.boundary.mean_m_score));
  EXPECT_EQ(s.boundary.scored_frames, 0);
}

TEST(MatchingEvaluation, TracksWithAGapDoNotCount) {
  FeatureTracks tracks;
  tracks.features.resize(3, FeatureSet(1));
  tracks.tracks = {MakeTrack({{0, 0}, {2, 0}})};
  const MatchingScores s = ComputeMatchingScores(tracks, {}, {1, 1});
  EXPECT_EQ(s.samples[0].residual[2], 0);
  EXPECT_EQ(s.samples[1].residual[2], 0);
}

TEST(MatchingEvaluation, BadInputGivesClearErrors) {
  const Fixture fx = MakeFixture();
  try {
    ComputeMatchingScores(fx.tracks, fx.labels, {7, 5});
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("n = 7 needs at least 8 frames, the sequence has 7"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(ComputeMatchingScores(fx.tracks, fx.labels, {0, 5}), Error);
  EXPECT_THROW(ComputeMatchingScores(fx.tracks, fx.labels, {1, 0}), Error);
  auto labels = fx.labels;
  labels[2].pop_back();
  EXPECT_THROW(ComputeMatchingScores(fx.tracks, labels, {1, 5}), Error);
  labels.pop_back();
  EXPECT_THROW(ComputeMatchingScores(fx.tracks, labels, {1, 5}), Error);
}

}  // namespace
}  // namespace comic::frontend
