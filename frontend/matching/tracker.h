// Feature tracking over a video (paper §4–§5): detect on every frame, match frame i to frame i+1
// with the patch matcher, chain the accepted matches into tracks. Optionally (match_window K > 1)
// each frame is also matched to the K − 1 frames after the next, so that a feature lost in one
// frame (occluded, missed by the detector, or across a wide step of a sparse image set) is linked
// again; the tracks are then the connected components of all the matches
// (frontend/matching/track_builder.h). The SfM consumes the tracks (FeatureTracks,
// frontend/matching/track.h); the evaluation (matching_evaluation.h) scores them.
//
//   TrackerOptions options;                          // paper protocol: r = 20 px, T = 400,
//   options.min_response = cut.min_response;         // no prediction, consecutive frames
//   auto detector = MakeDetector("harris");          // (threshold equalisation gives the cut)
//   TrackingResult result = TrackSequence(sequence, *detector, options,
//                                         [](size_t done, size_t n) {
//                                           std::cerr << "\rframe " << done << "/" << n;
//                                         });
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
// Frames farther apart (match_window > 1; frame i to frame j = i + g, g >= 2): the nearer frames
// are matched first, so a feature of i matched to some frame m between them whose match in m is
// matched to j (two hops) is searched around that feature of j, and these two-hop displacements
// predict the other features of i by the median of their nearest ones (as above). With
// kCoarseToFine the coarse pass between i and j adds its displacements to those. This works for
// video, where the hops follow any motion (forward motion included) without assuming it is
// constant, and for sparse sets, where a hop across a wide step is missing: the features then
// fall back to the coarse pass or to their own position with unpredicted_radius. kNone never
// predicts, at any gap.
//
// Each frame's patches (and, for the calibrated costs, its level-line sides) are prepared once
// (PatchSet) and kept while a later frame may still be matched to it. With
// matcher.cost = kTrackSides the tracker remembers, per feature, whether its match from the frame
// before was won by its object side or by its full patch, and compares the latter by the full
// patch only when matching on (patch_matcher.h).
//
// Deterministic: the result depends only on the frames, the detector and the options.
#pragma once

#include <functional>
#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "frontend/detector.h"
#include "frontend/feature_masks.h"
#include "frontend/matching/match_verification.h"
#include "frontend/matching/patch_alignment.h"
#include "frontend/matching/patch_matcher.h"
#include "frontend/matching/track.h"
#include "frontend/matching/track_builder.h"
#include "frontend/matching/track_continuation.h"

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
  // Features whose kPatchSize window has a smaller minimum gradient eigenvalue
  // (WindowMinEigenvalue, grey levels² per pixel²) are not tracked, before the max_features cut:
  // a flat window, or one holding a single straight edge, matches anything nearby equally well
  // ("good features to track", Shi & Tomasi 1994). 0 = every feature.
  double min_window_eigenvalue = 0.0;
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
  // Each frame is matched to the next match_window frames (1 = the next frame only: the paper's
  // protocol, and the tracks are chains of consecutive matches).
  int match_window = 1;
  // match_window > 1: what to do with a connected component of matches holding two features of
  // one frame (frontend/matching/track_builder.h). Irrelevant for match_window = 1 (no conflict can
  // arise).
  TrackConflictRule conflict_rule = TrackConflictRule::kGreedy;
  // Frame pairs at least this many frames apart have their accepted matches verified
  // geometrically (VerifyMatches with `verification`): 0 = no pair, 1 = every pair, 2 = the
  // pairs beyond the next frame only.
  int verify_min_gap = 0;
  MatchVerificationOptions verification;
  // Verified pairs are also matched with the later frame turned by 180° in its plane, and the
  // hypothesis with more verified matches is kept (needs verify_min_gap > 0, and a prediction
  // that finds the offset of the turned frame: kCoarseToFine, or a wide radius). Gantry rigs such
  // as the Middlebury multi-view rings store the views of one latitude sign upside down; a
  // translational patch matcher cannot link those to the others. Doubles the matching time of
  // the verified pairs.
  bool match_turned_180 = false;
  // Guided search and continuation (track_continuation.h): each feature of frame i is aligned
  // into frame i+1 from its predicted position by pyramidal patch alignment; detections are
  // searched near a trusted alignment only, and with continuation.max_continued_frames > 0 a
  // track whose feature is not re-detected continues at the aligned position for that many
  // frames. Off in the paper's protocol; on for the SfM (sfm::SequenceReconstructionOptions).
  bool align_patches = false;
  TrackContinuationOptions continuation;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// Everything a tracking run produces.
struct TrackingResult {
  // Features per frame (after the cut-off, the patch-fit filter and max_features) and the tracks
  // built from the accepted matches (BuildTracks). Only tracks of two or more observations are
  // listed.
  FeatureTracks tracks;
  // Per frame pair (i, i+1): every mutual-best match before the SSD threshold (and before any
  // verification), so a caller can re-threshold (TracksAtThreshold) without re-matching. Exact
  // for MotionPrediction::kNone, and for kCoarseToFine with match_window = 1; with
  // kConstantVelocity (or the two-hop predictions of match_window > 1) the search regions
  // themselves depended on the matches accepted while tracking.
  std::vector<std::vector<PatchMatch>> mutual_matches;
  // Per frame pair (i, i+1): the matches accepted at matcher.max_cost.
  std::vector<std::vector<PatchMatch>> accepted_matches;
  // Per frame pair (i, i+1): where each feature of frame i was searched in frame i+1 (empty
  // regions: at its own position within matcher.radius), for the diagnosis of lost tracks.
  std::vector<SearchRegions> search_regions;
  // Per frame, per feature: 1 if the feature is a continuation (not a detection: its track's
  // feature of the frame before, moved to where its patch aligned; align_patches), else 0.
  // Continued features follow a frame's detected ones.
  std::vector<std::vector<uint8_t>> continued;
  // align_patches, per frame pair (i, i+1): each feature of frame i aligned into frame i+1.
  std::vector<std::vector<PatchAlignment>> alignments;
  // match_window > 1: the same for the pairs (i, j), 2 <= j − i <= match_window, ordered by j then
  // by the gap. Empty for match_window = 1.
  std::vector<FramePairMatches> window_mutual_matches;
  std::vector<FramePairMatches> window_accepted_matches;
  // The options the tracks were built with (TracksAtThreshold re-applies them), and what building
  // the tracks from all the accepted matches met.
  TrackerOptions options;
  TrackBuildSummary track_building;
  // match_turned_180: the frame pairs (i, j) whose matches are those of frame j turned by 180°.
  std::vector<std::pair<int, int>> turned_pairs;
};

// Called after each frame with (frames processed, total frames; 0 if unknown).
using TrackingProgress = std::function<void(size_t frames_done, size_t num_frames)>;

// The features of one detection the tracker can use: response >= options.min_response, patch
// inside the image, window eigenvalue >= options.min_window_eigenvalue, at most
// options.max_features strongest (input order kept).
FeatureSet SelectTrackableFeatures(const FeatureSet& detected, const cv::Mat& gray,
                                   const TrackerOptions& options);
// The same knowing only the image size: throws comic::Error(kInvalidArgument) if
// options.min_window_eigenvalue > 0 (the test needs the image).
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
  // SelectTrackableFeatures of its detection) and matches it to the previous match_window frames,
  // the nearest first. Throws
  // comic::Error(kInvalidArgument) for a wrong image type or size.
  void AddFrame(const cv::Mat& gray, FeatureSet features, const std::string& name = "");

  size_t NumFrames() const { return features_.size(); }

  // The tracks of the frames added so far.
  TrackingResult Result() const;

 private:
  // A frame downscaled for the coarse pass, with its strongest features (kCoarseToFine only).
  struct CoarseFrame {
    cv::Mat gray;
    FeatureSet features;
    PatchSet patches;  // the features' patches, prepared once for every pair the frame is in
  };
  CoarseFrame MakeCoarseFrame(const cv::Mat& gray) const;
  // A frame turned by 180° in its plane (match_turned_180), with its features and coarse frame.
  struct TurnedFrame {
    cv::Mat gray;
    FeatureSet features;
    PatchSet patches;
    CoarseFrame coarse;
  };
  TurnedFrame TurnFrame180(const cv::Mat& gray, const FeatureSet& features,
                           const CoarseFrame& coarse) const;
  // The accepted matches of frame1 to frame2 (an added frame, within the window).
  const std::vector<PatchMatch>& AcceptedMatches(int frame1, int frame2) const;
  // Where to search the new frame (the next to be added: gray2, features2, coarse2, all turned
  // by 180° if `turned`) for each feature of frame1, given the accepted matches to the new frame
  // from the nearer frames (accepted_to_frame2[g − 1]: from the frame g before it).
  SearchRegions PredictSearchRegions(int frame1, const cv::Mat& gray2, const FeatureSet& features2,
                                     const CoarseFrame& coarse2,
                                     const std::vector<std::vector<PatchMatch>>& accepted_to_frame2,
                                     bool turned) const;

  // Appends the continuations of the tracks of frame − 1 that found no detection in `frame` to
  // its features, patches and matches from frame − 1 (align_patches).
  void AddContinuations(const cv::Mat& gray, const std::vector<PatchAlignment>& aligned,
                        FeatureSet* features, PatchSet* patches, std::vector<PatchMatch>* mutual,
                        std::vector<PatchMatch>* accepted, std::vector<int>* runs) const;
  // Records the links into the frame being added (its matches from every earlier frame of the
  // window: `accepted_to_frame`[g − 1] from the frame g before) as the next observation of the
  // earlier features.
  void RecordLinks(const std::vector<std::vector<PatchMatch>>& accepted_to_frame);
  // Re-association after a gap (continuation.bridge_frames): links the tracks that ended two or
  // more frames before the frame being added to it, as detections or new continued features
  // appended to `features`, `patches` and `runs`; returns the links by frame pair.
  std::vector<FramePairMatches> AddBridges(const cv::Mat& gray, const ImagePyramid& pyramid,
                                           FeatureSet* features, PatchSet* patches,
                                           std::vector<int>* runs);

  TrackerOptions options_;
  std::string detector_name_;
  const Detector* detector_;
  cv::Size image_size_;
  // Per frame; patches (and coarse frames) are kept only while a later frame may still be matched
  // to them.
  std::vector<PatchSet> patches_;
  std::vector<CoarseFrame> coarse_;
  std::vector<FeatureSet> features_;
  std::vector<std::string> names_;
  // [j][g − 1]: matches of frame j − g to frame j (empty for frame 0).
  std::vector<std::vector<std::vector<PatchMatch>>> mutual_;
  std::vector<std::vector<std::vector<PatchMatch>>> accepted_;
  std::vector<SearchRegions> search_regions_;  // [j]: frame j − 1 to frame j (empty for j = 0)
  // align_patches: the last frame's pyramid, and per frame and feature the number of consecutive
  // frames its track has been continued without a detection (0 for a detection).
  std::vector<ImagePyramid> pyramids_;  // kept while a later frame may be aligned to them
  std::vector<std::vector<int>> continued_runs_;
  // Per frame and feature: the (frame, feature) of its track's next observation, (-1, -1) if
  // none yet.
  std::vector<std::vector<std::pair<int, int>>> next_link_;
  // [j]: the gap links into frame j (re-association after a gap).
  std::vector<std::vector<FramePairMatches>> bridges_;
  std::vector<std::vector<PatchAlignment>> alignments_;  // [j]: frame j − 1's into frame j
  std::vector<std::pair<int, int>> turned_pairs_;
};

// Detects on every frame of `sequence` (as opened, e.g. resized), tracks, and reports progress.
// `filter` (frontend/feature_masks.h), when set, is applied to each frame's detection before the
// features are selected (e.g. masks of moving objects).
TrackingResult TrackSequence(const io::ImageSequence& sequence, const Detector& detector,
                             const TrackerOptions& options, const TrackingProgress& progress = {},
                             const DetectionFilter& filter = {});

// The same over grey frames in memory (all CV_8UC1 of one size); `frame_names` may be empty.
TrackingResult TrackFrames(const std::vector<cv::Mat>& grays, const Detector& detector,
                           const TrackerOptions& options,
                           const std::vector<std::string>& frame_names = {},
                           const TrackingProgress& progress = {});

// The tracks `result` would have had at SSD threshold `max_cost` (see mutual_matches), verified
// and built as result.options say.
FeatureTracks TracksAtThreshold(const TrackingResult& result, double max_cost);

}  // namespace comic::frontend
