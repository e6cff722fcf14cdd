// Test helper: tracks as readable strings, so tests compare whole track lists at once.
#pragma once

#include <string>
#include <vector>

#include "frontend/track.h"

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

}  // namespace comic::frontend
