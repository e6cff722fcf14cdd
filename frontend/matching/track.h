// Feature tracks: chains of features, at most one per frame, that the tracker builds from
// frame-to-frame matches and the SfM consumes. The SfM depends only on these types, never on
// which detector made the features.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

struct TrackObservation {
  int frame = -1;    // index into FeatureTracks::features
  int feature = -1;  // index into FeatureTracks::features[frame]
};

struct Track {
  // Observations with strictly increasing frame indices (a track never holds two features of
  // one frame).
  std::vector<TrackObservation> observations;

  size_t Length() const { return observations.size(); }
  int FirstFrame() const { return observations.empty() ? -1 : observations.front().frame; }
  int LastFrame() const { return observations.empty() ? -1 : observations.back().frame; }
  // The index of the track's feature in `frame` (into FeatureTracks::features[frame]), or -1
  // where the track has none; a binary search, since observations are sorted by frame.
  int FeatureInFrame(int frame) const;
};

// Everything a tracker produces for one sequence.
struct FeatureTracks {
  std::string detector_name;             // which detector made the features
  cv::Size image_size;                   // size of the frames the features live in
  std::vector<std::string> frame_names;  // one per frame (file names), may be empty
  std::vector<FeatureSet> features;      // per frame
  std::vector<Track> tracks;
  // Per frame, when they were computed (descriptor matching of an image set, or added for an
  // export; frontend/description/sift_descriptor.h): features[f].size() rows x 128 columns,
  // CV_8UC1, row i describing features[f][i]. Empty (no frames at all) when none were computed.
  std::vector<cv::Mat> descriptors;

  size_t NumFrames() const { return features.size(); }
  const Feature& FeatureOf(const TrackObservation& obs) const {
    return features[obs.frame][obs.feature];
  }
  bool HasDescriptors() const { return !descriptors.empty(); }

  // Throws comic::Error(kInvalidData) if an observation indexes a missing frame or feature, a
  // track's frames are not strictly increasing, a feature belongs to two tracks, frame_names is
  // non-empty and of the wrong length, or descriptors are non-empty and not one CV_8UC1 matrix of
  // 128 columns and a row per feature for every frame.
  void Check() const;
};

}  // namespace comic::frontend
