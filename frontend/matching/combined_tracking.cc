#include "frontend/matching/combined_tracking.h"

#include <algorithm>

#include "io/core/error.h"
#include "io/image/image_sequence.h"

namespace comic::frontend {

std::vector<int> FirstFeatureOfEachPart(const std::vector<TrackingResult>& parts, int frame) {
  std::vector<int> first;
  int offset = 0;
  for (const TrackingResult& part : parts) {
    first.push_back(offset);
    offset += static_cast<int>(part.tracks.features.at(frame).size());
  }
  return first;
}

TrackingResult MergeTrackingResults(const std::vector<TrackingResult>& parts,
                                    const std::string& detector_name) {
  COMIC_CHECK(!parts.empty(), kInvalidArgument, "merge tracking results: no parts");
  const FeatureTracks& first = parts.front().tracks;
  for (const TrackingResult& part : parts) {
    COMIC_CHECK(
        part.tracks.NumFrames() == first.NumFrames() && part.tracks.image_size == first.image_size,
        kInvalidArgument,
        "merge tracking results: the parts differ in frames or image size ("
            << part.tracks.NumFrames() << " vs " << first.NumFrames() << " frames)");
  }
  TrackingResult merged;
  merged.options = parts.front().options;
  merged.turned_pairs = parts.front().turned_pairs;
  FeatureTracks& tracks = merged.tracks;
  tracks.detector_name = detector_name;
  tracks.image_size = first.image_size;
  tracks.frame_names = first.frame_names;
  tracks.features.resize(first.NumFrames());
  std::vector<std::vector<int>> offsets(first.NumFrames());  // [frame][part]
  for (size_t frame = 0; frame < first.NumFrames(); ++frame) {
    offsets[frame] = FirstFeatureOfEachPart(parts, static_cast<int>(frame));
    for (const TrackingResult& part : parts) {
      const FeatureSet& features = part.tracks.features[frame];
      tracks.features[frame].insert(tracks.features[frame].end(), features.begin(), features.end());
    }
    if (std::all_of(parts.begin(), parts.end(),
                    [&](const TrackingResult& part) { return frame < part.continued.size(); })) {
      std::vector<uint8_t> flags;
      for (const TrackingResult& part : parts) {
        flags.insert(flags.end(), part.continued[frame].begin(), part.continued[frame].end());
      }
      merged.continued.push_back(std::move(flags));
    }
  }
  // Descriptors are merged when every part has them (one row per feature, in the same order).
  const bool descriptors = std::all_of(parts.begin(), parts.end(), [](const TrackingResult& part) {
    return part.tracks.HasDescriptors();
  });
  if (descriptors) {
    tracks.descriptors.resize(first.NumFrames());
    for (size_t frame = 0; frame < first.NumFrames(); ++frame) {
      std::vector<cv::Mat> rows;
      for (const TrackingResult& part : parts) {
        if (part.tracks.descriptors[frame].rows > 0) rows.push_back(part.tracks.descriptors[frame]);
      }
      if (rows.empty()) {
        tracks.descriptors[frame] = cv::Mat(0, 128, CV_8UC1);
      } else {
        cv::vconcat(rows, tracks.descriptors[frame]);
      }
    }
  }
  for (size_t p = 0; p < parts.size(); ++p) {
    for (Track track : parts[p].tracks.tracks) {
      for (TrackObservation& observation : track.observations) {
        observation.feature += offsets[observation.frame][p];
      }
      tracks.tracks.push_back(std::move(track));
    }
    const TrackBuildSummary& summary = parts[p].track_building;
    merged.track_building.num_matches += summary.num_matches;
    merged.track_building.num_conflicting_components += summary.num_conflicting_components;
    merged.track_building.num_dropped_features += summary.num_dropped_features;
    merged.track_building.num_refused_matches += summary.num_refused_matches;
  }
  tracks.Check();
  return merged;
}

TrackingResult TrackSequenceWithDetector(const io::ImageSequence& sequence,
                                         const Detector& detector, const TrackerOptions& options,
                                         const TrackingProgress& progress,
                                         const DetectionFilter& filter) {
  const auto* combined = dynamic_cast<const CombinedDetector*>(&detector);
  if (combined == nullptr) return TrackSequence(sequence, detector, options, progress, filter);
  std::vector<TrackingResult> parts;
  const size_t n = sequence.NumFrames();
  const size_t total = n * combined->NumComponents();
  for (size_t c = 0; c < combined->NumComponents(); ++c) {
    TrackingProgress part_progress;
    if (progress) {
      part_progress = [&progress, c, n, total](size_t done, size_t) {
        progress(c * n + done, total);
      };
    }
    parts.push_back(
        TrackSequence(sequence, combined->Component(c), options, part_progress, filter));
  }
  return MergeTrackingResults(parts, combined->Name());
}

TrackingResult TrackFramesWithDetector(const std::vector<cv::Mat>& grays, const Detector& detector,
                                       const TrackerOptions& options,
                                       const std::vector<std::string>& frame_names) {
  const auto* combined = dynamic_cast<const CombinedDetector*>(&detector);
  if (combined == nullptr) return TrackFrames(grays, detector, options, frame_names);
  std::vector<TrackingResult> parts;
  for (size_t c = 0; c < combined->NumComponents(); ++c) {
    parts.push_back(TrackFrames(grays, combined->Component(c), options, frame_names));
  }
  return MergeTrackingResults(parts, combined->Name());
}

}  // namespace comic::frontend
