// Test helpers for tracks: readable strings, and an independent reference for the tracks of
// consecutive-frame matches (what BuildTracks must give when only frames i and i + 1 are matched).
#pragma once

#include <string>
#include <vector>

#include "frontend/matching/patch_matcher.h"
#include "frontend/matching/track.h"

namespace comic::frontend {

// One "frame:feature frame:feature ..." string per track, in the tracks' order.
inline std::vector<std::string> Describe(const std::vector<Track>& tracks) {
  std::vector<std::string> out;
  for (const Track& track : tracks) {
    std::string s;
    for (const TrackObservation& obs : track.observations) {
      s += (s.empty() ? "" : " ") + std::to_string(obs.frame) + ":" + std::to_string(obs.feature);
    }
    out.push_back(s);
  }
  return out;
}

// The chains of one-to-one matches pair_matches[f] (frame f to f + 1; valid indices assumed),
// followed feature by feature: tracks of two or more observations, ordered by first frame then
// first feature.
inline std::vector<Track> ChainConsecutiveMatches(
    const std::vector<int>& num_features,
    const std::vector<std::vector<PatchMatch>>& pair_matches) {
  std::vector<std::vector<int>> next(num_features.size());
  std::vector<std::vector<bool>> has_previous(num_features.size());
  for (size_t f = 0; f < num_features.size(); ++f) {
    next[f].assign(num_features[f], -1);
    has_previous[f].assign(num_features[f], false);
  }
  for (size_t f = 0; f < pair_matches.size(); ++f) {
    for (const PatchMatch& m : pair_matches[f]) {
      next[f][m.index1] = m.index2;
      has_previous[f + 1][m.index2] = true;
    }
  }
  std::vector<Track> tracks;
  for (int f = 0; f < static_cast<int>(num_features.size()); ++f) {
    for (int i = 0; i < num_features[f]; ++i) {
      if (has_previous[f][i] || next[f][i] < 0) continue;
      Track track;
      for (int frame = f, feature = i; feature >= 0; ++frame) {
        track.observations.push_back({frame, feature});
        feature = frame + 1 < static_cast<int>(num_features.size()) ? next[frame][feature] : -1;
      }
      tracks.push_back(std::move(track));
    }
  }
  return tracks;
}

}  // namespace comic::frontend
