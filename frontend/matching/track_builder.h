// Feature tracks from pairwise matches between any two frames (OpenMVG's track builder,
// tracks/tracks.hpp): every (frame, feature) is a node, every match joins two nodes, and the
// connected components (union-find) are the tracks. The tracker builds its tracks with it, from
// matches between consecutive frames and, with TrackerOptions::match_window > 1, farther ones; for
// matches between consecutive frames only the components are exactly the chains of those matches.
//
//   std::vector<FramePairMatches> pairs = {{0, 1, matches01}, {1, 2, matches12}, {0, 2, ...}};
//   TrackBuildSummary summary;
//   std::vector<Track> tracks = BuildTracks(features, pairs, TrackConflictRule::kGreedy, &summary);
//
// Conflicts. Once frames other than consecutive ones are matched, a component can hold two
// features of one frame (a -> b -> c chained while a -> c' matched directly, c != c'): at least one
// of those matches is wrong, and such a component is not a track (frontend/matching/track.h: one
// feature per frame). Two rules:
//   kDrop    OpenMVG's: the whole component is dropped; its features belong to no track.
//   kGreedy  matches are merged in a fixed order — the smallest frame gap first (a match between
//            nearer frames is more reliable: less change of viewpoint, a tighter prediction), then
//            the lowest cost, then frame and feature indices — and a match that would join two
//            components sharing a frame is refused. Every component then is a track; a wrong
//            long-gap match cannot break up a chain of short-gap ones, it is simply left out.
//   kGreedyByCost  as kGreedy, merged by the lowest cost first (then frame and feature indices):
//            for image sets matched by descriptors (cost = descriptor angle), where the frame
//            index says nothing about how near two views are.
// Both are deterministic: the result depends on the matches only, not on their order in `pairs`.
#pragma once

#include <string>
#include <vector>

#include "frontend/feature.h"
#include "frontend/matching/patch_matcher.h"
#include "frontend/matching/track.h"

namespace comic::frontend {

// The matches between two frames, frame1 < frame2; index1 indexes frame1's features, index2
// frame2's, one-to-one.
struct FramePairMatches {
  int frame1 = -1;
  int frame2 = -1;
  std::vector<PatchMatch> matches;

  int Gap() const { return frame2 - frame1; }
};

enum class TrackConflictRule { kDrop, kGreedy, kGreedyByCost };

// "drop", "greedy", "greedy-cost".
const char* TrackConflictRuleName(TrackConflictRule rule);
// Throws comic::Error(kInvalidArgument) listing the valid names.
TrackConflictRule ParseTrackConflictRule(const std::string& name);

// What the track building met.
struct TrackBuildSummary {
  int num_matches = 0;                 // matches given
  int num_conflicting_components = 0;  // kDrop: components dropped for holding a frame twice
  int num_dropped_features = 0;        // kDrop: features of those components
  int num_refused_matches = 0;         // kGreedy: matches refused to keep the components tracks
};

// Tracks of two or more observations from the matches of `pairs` (see above), observations in
// increasing frame order, tracks ordered by first frame then first feature.
// Only the sizes of `features` are used. Throws comic::Error(kInvalidArgument) for a pair whose
// frames are out of range or not increasing, an index out of range, or a feature matched twice
// within one pair.
std::vector<Track> BuildTracks(const std::vector<FeatureSet>& features,
                               const std::vector<FramePairMatches>& pairs, TrackConflictRule rule,
                               TrackBuildSummary* summary = nullptr);

}  // namespace comic::frontend
