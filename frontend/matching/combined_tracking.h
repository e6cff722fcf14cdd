// Tracking with a combined detector ("comic+hessian", frontend/combined_detector.h): each
// component detector is tracked on its own with the same options, and the tracks are merged.
// So features of different detectors are never matched to each other, every feature keeps its
// own detector's side mask, and a track is a track of one detector (never two features of one
// frame, as every track).
//
//   TrackingResult result = TrackSequenceWithDetector(sequence, *MakeDetector("comic+hessian"),
//                                                     options);
//   // result.tracks.features[f]: comic's features of frame f, then hessian's
#pragma once

#include <string>
#include <vector>

#include "frontend/combined_detector.h"
#include "frontend/matching/tracker.h"

namespace comic::frontend {

// The merge of per-component tracking results (all over the same frames), in component order:
// per frame the features of part 0, then of part 1, ...; the tracks of each part with their
// feature indices moved accordingly; track-building counts summed; `options` and the turned
// pairs of part 0. The per-pair match lists (mutual_matches, ...) are left empty: they index
// one part's features (TracksAtThreshold does not apply to a merged result).
// Throws comic::Error(kInvalidArgument) if the parts differ in frames or image size.
TrackingResult MergeTrackingResults(const std::vector<TrackingResult>& parts,
                                    const std::string& detector_name);

// For frame `frame` of a merged result, the index of the first feature of each part
// (part_feature_counts[part][frame] summed over the earlier parts); what
// MergeTrackingResults used.
std::vector<int> FirstFeatureOfEachPart(const std::vector<TrackingResult>& parts, int frame);

// TrackSequence for any detector: a CombinedDetector's components are tracked one by one and
// merged (progress counts the frames of all components; `filter` applies to each component's
// detection); any other detector is tracked as is.
TrackingResult TrackSequenceWithDetector(const io::ImageSequence& sequence,
                                         const Detector& detector, const TrackerOptions& options,
                                         const TrackingProgress& progress = {},
                                         const DetectionFilter& filter = {});

// The same over grey frames in memory (as TrackFrames).
TrackingResult TrackFramesWithDetector(const std::vector<cv::Mat>& grays, const Detector& detector,
                                       const TrackerOptions& options,
                                       const std::vector<std::string>& frame_names = {});

}  // namespace comic::frontend
