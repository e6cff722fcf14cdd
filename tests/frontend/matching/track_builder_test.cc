#include "frontend/matching/track_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "frontend/matching/tracker.h"
#include "io/core/error.h"
#include "tests/frontend/track_test_helpers.h"

namespace comic::frontend {
namespace {

std::vector<FeatureSet> Frames(std::vector<int> sizes) {
  std::vector<FeatureSet> features;
  for (int n : sizes) features.emplace_back(n);
  return features;
}

// Checks frontend/matching/track.h's contract on `tracks` over `features`.
void ExpectValidTracks(const std::vector<FeatureSet>& features, const std::vector<Track>& tracks) {
  FeatureTracks all;
  all.features = features;
  all.tracks = tracks;
  EXPECT_NO_THROW(all.Check());
}

TEST(TrackBuilder, JoinsMatchesOfAnyFramePairIntoComponents) {
  const auto features = Frames({3, 3, 3, 3});
  // 0:0 - 1:1 - 2:2 consecutive; 0:1 - 2:0 across frame 1 (lost there), then 2:0 - 3:1;
  // 1:0 - 3:2 across frame 2.
  const std::vector<FramePairMatches> pairs = {{0, 1, {{0, 1, 5.f}}},
                                               {1, 2, {{1, 2, 5.f}}},
                                               {0, 2, {{1, 0, 5.f}}},
                                               {2, 3, {{0, 1, 5.f}}},
                                               {1, 3, {{0, 2, 5.f}}}};
  for (TrackConflictRule rule : {TrackConflictRule::kDrop, TrackConflictRule::kGreedy}) {
    TrackBuildSummary summary;
    const std::vector<Track> tracks = BuildTracks(features, pairs, rule, &summary);
    EXPECT_EQ(Describe(tracks),
              (std::vector<std::string>{"0:0 1:1 2:2", "0:1 2:0 3:1", "1:0 3:2"}));
    ExpectValidTracks(features, tracks);
    EXPECT_EQ(summary.num_matches, 5);
    EXPECT_EQ(summary.num_conflicting_components, 0);
    EXPECT_EQ(summary.num_refused_matches, 0);
  }
}

// a -> b -> c chained over frames 0, 1, 2 while a -> c' is matched directly (0 -> 2): the
// component {a, b, c, c'} holds two features of frame 2.
std::vector<FramePairMatches> ConflictingMatches(float direct_cost) {
  return {{0, 1, {{0, 0, 50.f}, {1, 1, 10.f}}},
          {1, 2, {{0, 0, 50.f}, {1, 1, 10.f}}},
          {0, 2, {{0, 2, direct_cost}}},
          {2, 3, {{2, 0, 10.f}}}};
}

TEST(TrackBuilder, DropRuleDropsAComponentHoldingAFrameTwice) {
  const auto features = Frames({2, 2, 3, 1});
  TrackBuildSummary summary;
  const std::vector<Track> tracks =
      BuildTracks(features, ConflictingMatches(1.f), TrackConflictRule::kDrop, &summary);
  // {0:0 1:0 2:0 2:2 3:0} holds frame 2 twice: gone, every one of its five features.
  EXPECT_EQ(Describe(tracks), (std::vector<std::string>{"0:1 1:1 2:1"}));
  ExpectValidTracks(features, tracks);
  EXPECT_EQ(summary.num_conflicting_components, 1);
  EXPECT_EQ(summary.num_dropped_features, 5);
  EXPECT_EQ(summary.num_refused_matches, 0);
}

TEST(TrackBuilder, GreedyRuleKeepsTheShortGapChainAndRefusesTheConflictingMatch) {
  const auto features = Frames({2, 2, 3, 1});
  // The direct match is cheaper than the chain's matches, but the nearer frames' matches go
  // first: the chain stays whole, the direct match is refused, and 2:2 keeps its own link to 3:0.
  TrackBuildSummary summary;
  const std::vector<Track> tracks =
      BuildTracks(features, ConflictingMatches(1.f), TrackConflictRule::kGreedy, &summary);
  EXPECT_EQ(Describe(tracks), (std::vector<std::string>{"0:0 1:0 2:0", "0:1 1:1 2:1", "2:2 3:0"}));
  ExpectValidTracks(features, tracks);
  EXPECT_EQ(summary.num_refused_matches, 1);
  EXPECT_EQ(summary.num_conflicting_components, 0);

  // Within one gap the cheaper match goes first. Gap 1 joins {0:0 1:0} and {2:0 3:1}; of the two
  // gap-2 matches, 1:0 - 3:0 (cost 1) joins 3:0 to the first; 0:0 - 2:0 (cost 3) would then put
  // 3:0 and 3:1 into one component: refused. (In the other order 1:0 - 3:0 would be refused.)
  const auto features2 = Frames({1, 1, 1, 2});
  const std::vector<FramePairMatches> pairs = {
      {0, 1, {{0, 0, 9.f}}}, {2, 3, {{0, 1, 9.f}}}, {0, 2, {{0, 0, 3.f}}}, {1, 3, {{0, 0, 1.f}}}};
  const std::vector<Track> tracks2 =
      BuildTracks(features2, pairs, TrackConflictRule::kGreedy, &summary);
  EXPECT_EQ(Describe(tracks2), (std::vector<std::string>{"0:0 1:0 3:0", "2:0 3:1"}));
  EXPECT_EQ(summary.num_refused_matches, 1);
  ExpectValidTracks(features2, tracks2);
}

TEST(TrackBuilder, GreedyByCostRuleMergesTheCheapestMatchFirstWhateverTheGap) {
  // The same conflict: by cost the direct 0 -> 2 match (cost 1) goes before the chain's matches
  // (10 and 50), so 0:0 1:0 2:0 is cut where it would join 2:2's component.
  const auto features = Frames({2, 2, 3, 1});
  TrackBuildSummary summary;
  const std::vector<Track> tracks =
      BuildTracks(features, ConflictingMatches(1.f), TrackConflictRule::kGreedyByCost, &summary);
  // Order: 0:0-2:2 (1), then the cost-10 matches 0:1-1:1, 1:1-2:1, 2:2-3:0, then the cost-50
  // 0:0-1:0 (joins 1:0 to {0:0 2:2 3:0}) and 1:0-2:0 (would put 2:0 beside 2:2: refused).
  EXPECT_EQ(Describe(tracks), (std::vector<std::string>{"0:0 1:0 2:2 3:0", "0:1 1:1 2:1"}));
  EXPECT_EQ(summary.num_refused_matches, 1);
  ExpectValidTracks(features, tracks);
  EXPECT_EQ(ParseTrackConflictRule("greedy-cost"), TrackConflictRule::kGreedyByCost);
  EXPECT_STREQ(TrackConflictRuleName(TrackConflictRule::kGreedyByCost), "greedy-cost");
}

TEST(TrackBuilder, ResultDoesNotDependOnTheOrderOfThePairs) {
  // Random matches over 6 frames within a window of 3, dense enough for many conflicts.
  std::mt19937 rng(7);
  const auto features = Frames({12, 12, 12, 12, 12, 12});
  std::vector<FramePairMatches> pairs;
  for (int j = 1; j < 6; ++j) {
    for (int i = std::max(0, j - 3); i < j; ++i) {
      std::vector<int> perm(12);
      for (int k = 0; k < 12; ++k) perm[k] = k;
      std::shuffle(perm.begin(), perm.end(), rng);
      FramePairMatches pair{i, j, {}};
      for (int k = 0; k < 8; ++k) {
        pair.matches.push_back({k, perm[k], static_cast<float>(rng() % 100)});
      }
      pairs.push_back(pair);
    }
  }
  for (TrackConflictRule rule :
       {TrackConflictRule::kDrop, TrackConflictRule::kGreedy, TrackConflictRule::kGreedyByCost}) {
    TrackBuildSummary summary;
    const std::vector<Track> tracks = BuildTracks(features, pairs, rule, &summary);
    ExpectValidTracks(features, tracks);
    EXPECT_GT(summary.num_conflicting_components + summary.num_refused_matches, 0)
        << "the random matches should conflict somewhere";
    std::vector<FramePairMatches> reversed(pairs.rbegin(), pairs.rend());
    for (FramePairMatches& pair : reversed) std::reverse(pair.matches.begin(), pair.matches.end());
    EXPECT_EQ(Describe(BuildTracks(features, reversed, rule)), Describe(tracks))
        << TrackConflictRuleName(rule);
  }
}

TEST(TrackBuilder, ConsecutiveMatchesGiveExactlyTheChains) {
  // Random one-to-one matches between consecutive frames only: no conflict can arise, and both
  // rules give the chains in the chains' order (first frame, then first feature).
  std::mt19937 rng(11);
  const auto features = Frames({30, 25, 30, 28, 30, 30});
  std::vector<std::vector<PatchMatch>> consecutive;
  std::vector<FramePairMatches> pairs;
  for (int i = 0; i + 1 < 6; ++i) {
    std::vector<int> perm(features[i + 1].size());
    for (size_t k = 0; k < perm.size(); ++k) perm[k] = static_cast<int>(k);
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<PatchMatch> matches;
    for (int k = 0; k < static_cast<int>(features[i].size()) && k < 20; ++k) {
      if (rng() % 4 == 0) continue;  // some features end their track here
      matches.push_back({k, perm[k], 1.f});
    }
    consecutive.push_back(matches);
    pairs.push_back({i, i + 1, matches});
  }
  const std::vector<std::string> chains =
      Describe(ChainConsecutiveMatches({30, 25, 30, 28, 30, 30}, consecutive));
  EXPECT_GT(chains.size(), 20u);
  for (TrackConflictRule rule : {TrackConflictRule::kDrop, TrackConflictRule::kGreedy}) {
    EXPECT_EQ(Describe(BuildTracks(features, pairs, rule)), chains);
  }
}

TEST(TrackBuilder, RejectsInvalidMatches) {
  const auto features = Frames({2, 2, 2});
  const auto rule = TrackConflictRule::kGreedy;
  EXPECT_THROW(BuildTracks(features, {{1, 1, {}}}, rule), Error);             // not increasing
  EXPECT_THROW(BuildTracks(features, {{2, 1, {}}}, rule), Error);             // decreasing
  EXPECT_THROW(BuildTracks(features, {{0, 3, {}}}, rule), Error);             // no frame 3
  EXPECT_THROW(BuildTracks(features, {{0, 2, {{0, 2, 1.f}}}}, rule), Error);  // no feature 2
  EXPECT_THROW(BuildTracks(features, {{0, 2, {{0, 1, 1.f}, {1, 1, 1.f}}}}, rule), Error);
  EXPECT_TRUE(BuildTracks({}, {}, rule).empty());
  EXPECT_THROW(ParseTrackConflictRule("vote"), Error);
  EXPECT_EQ(ParseTrackConflictRule("drop"), TrackConflictRule::kDrop);
  EXPECT_STREQ(TrackConflictRuleName(TrackConflictRule::kGreedy), "greedy");
}

}  // namespace
}  // namespace comic::frontend
