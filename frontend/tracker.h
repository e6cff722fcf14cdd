// Feature tracking over a video (paper §4–§5): detect on every frame, match frame i to frame i+1
// with the patch matcher, chain the accepted matches into tracks. The SfM consumes the tracks
// (FeatureTracks, frontend/track.h); the evaluation (matching_evaluation.h) scores them.
//
//   TrackerOptions options;                       // paper protocol: r = 20 px, T = 400, no
//   prediction options.min_response = cut.min_response;      // from threshold equalisation auto
//   detector = MakeDetector("harris"); TrackingResult result = TrackSequence(sequence, *detector,
//   options, [](size_t done, size_t n) {
//     std::cerr << "\rframe " << done << "/" << n;
//   });
//   const FeatureTracks& tracks = result.tracks;
//
// Or frame by frame, e.g. to feed one detection to several matchers:
//
//   Tracker tracker(options, "comic");
//   for (...) tracker.AddFrame(gray, SelectTrackableFeatures(detector.Detect(gray), gray.size(),
//                                                             options));
//   TrackingResult result = tracker.Result();
//
// Motion prediction (for real driving video, where near points move tens of pixels per frame;
// the paper's protocol uses none):
//   kConstantVelocity  a feature matched from frame i−1 is searched around x_i + (x_i − x_{i−1});
//                      a feature without a match is predicted by the median velocity of its
//                      nearest predicted neighbours (velocity_neighbours within
//                      velocity_neighbour_radius); a feature with neither is searched around its
//                      own position with unpredicted_radius.
//   kCoarseToFine      both frames are downscaled by coarse_factor, the detector's
//                      coarse_features strongest features are matched there within
//                      coarse_radius (full-resolution pixels) with the same cost and threshold,
//                      and each feature is searched around its position moved by the median
//                      displacement of its velocity_neighbours nearest coarse matches (within
//                      velocity_neighbour_radius; none found -> own position, unpredicted_radius).
// Either way the final search radius around a prediction is matcher.radius.
//
// Deterministic: the result depends only on the frames, the detector and the options.
#pragma once

#include <functional>
#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/detector.h"
#include "frontend/patch_matcher.h"
#include "frontend/track.h"

namespace comic::io {
class ImageSequence;
}

namespace comic::frontend {

enum class MotionPrediction { kNone, kConstantVelocity, kCoarseToFine };

// "none", "velocity", "coarse-to-fine".
const char* MotionPredictionName(MotionPrediction prediction);
// Throws comic::Error(kInvalidArgument) listing the valid names.
MotionPrediction ParseMotionPrediction(const std::string& name);

struct TrackerOptions {
  // Gate (radius r around the (predicted) position; paper §4: 20 px), cost mode, SSD threshold.
  PatchMatcherOptions matcher;
  // Detection threshold: features with a lower response are dropped on every frame (the cut-off
  // from threshold equalisation; the lowest float keeps every candidate).
  float min_response = -std::numeric_limits<float>::max();
  // Keep at most this many of the strongest features per frame after the cut-off (0 = all).
  int max_features = 0;
  // Motion prediction (see above).
  MotionPrediction prediction = MotionPrediction::kNone;
  // Search radius in pixels for features without any prediction (0 = matcher.radius).
  double unpredicted_radius = 0.0;
  // Neighbours whose median velocity / coarse displacement predicts a feature, and how far away
  // (pixels) they may be.
  int velocity_neighbours = 5;
  double velocity_neighbour_radius = 100.0;
  // kCoarseToFine: downscale factor of the coarse pass (>= 2), its search radius in
  // full-resolution pixels, and how many of the strongest coarse features it matches.
  int coarse_factor = 4;
  double coarse_radius = 80.0;
  int coarse_features = 500;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// Everything a tracking run produces.
struct TrackingResult {
  // Features per frame (after the cut-off, the patch-fit filter and max_features) and the tracks
  // chained from the accepted matches. Only tracks of two or more observations are listed.
  FeatureTracks tracks;
  // Per frame pair (i, i+1): every mutual-best match before the SSD threshold, so a caller can
  // re-threshold (TracksAtThreshold) without re-matching. Exact for MotionPrediction::kNone and
  // kCoarseToFine; with kConstantVelocity the search regions themselves depended on the
  // threshold used while tracking.
  std::vector<std::vector<PatchMatch>> mutual_matches;
  // Per frame pair: the matches accepted at matcher.max_cost (those the tracks are built from).
  std::vector<std::vector<PatchMatch>> accepted_matches;
};

// Called after each frame with (frames processed, total frames; 0 if unknown).
using TrackingProgress = std::function<void(size_t frames_done, size_t num_frames)>;

// The features of one detection the tracker can use: response >= options.min_response, patch
// inside an image of `image_size`, at most options.max_features strongest (input order kept).
FeatureSet SelectTrackableFeatures(const FeatureSet& detected, const cv::Size& image_size,
                                   const TrackerOptions& options);

// Tracks over frames added one at a time.
class Tracker {
 public:
  // `detector` is used only by kCoarseToFine (it may be null otherwise) and must outlive the
  // tracker; `detector_name` is recorded in the result.
  Tracker(const TrackerOptions& options, std::string detector_name,
          const Detector* detector = nullptr);

  // Adds the next frame (CV_8UC1, the size of the first) with its features (normally
  // SelectTrackableFeatures of its detection) and matches it to the previous frame. Throws
  // comic::Error(kInvalidArgument) for a wrong image type or size.
  void AddFrame(const cv::Mat& gray, FeatureSet features, const std::string& name = "");

  size_t NumFrames() const { return features_.size(); }

  // The tracks of the frames added so far.
  TrackingResult Result() const;

 private:
  SearchRegions PredictSearchRegions(const cv::Mat& gray) const;

  TrackerOptions options_;
  std::string detector_name_;
  const Detector* detector_;
  cv::Mat previous_gray_;
  std::vector<FeatureSet> features_;
  std::vector<std::string> names_;
  std::vector<std::vector<PatchMatch>> mutual_;
  std::vector<std::vector<PatchMatch>> accepted_;
};

// Detects on every frame of `sequence` (as opened, e.g. resized), tracks, and reports progress.
TrackingResult TrackSequence(const io::ImageSequence& sequence, const Detector& detector,
                             const TrackerOptions& options, const TrackingProgress& progress = {});

// The same over grey frames in memory (all CV_8UC1 of one size); `frame_names` may be empty.
TrackingResult TrackFrames(const std::vector<cv::Mat>& grays, const Detector& detector,
                           const TrackerOptions& options,
                           const std::vector<std::string>& frame_names = {},
                           const TrackingProgress& progress = {});

// Chains one-to-one frame-pair matches (pair_matches[i] from frame i to frame i+1) into tracks of
// two or more observations, ordered by first frame then first feature. Throws
// comic::Error(kInvalidArgument) for an index out of range or a feature matched twice.
std::vector<Track> ChainMatches(const std::vector<FeatureSet>& features,
                                const std::vector<std::vector<PatchMatch>>& pair_matches);

// The tracks `result` would have had at SSD threshold `max_cost` (see mutual_matches).
FeatureTracks TracksAtThreshold(const TrackingResult& result, double max_cost);

}  // namespace comic::frontend
