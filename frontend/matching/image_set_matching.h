// Feature tracks of an image set by descriptor matching, as COLMAP's exhaustive matcher: detect on
// every frame, describe every feature (frontend/description/sift_descriptor.h), match the
// descriptors of every frame pair (descriptor_matcher.h: nearest neighbour, ratio test, cross
// check), keep the matches a fundamental matrix explains (match_verification.h), match the
// verified pairs again along their epipolar lines (guided matching, optional), and build the tracks
// from the verified pairs (track_builder.h, conflicts resolved by the lowest descriptor angle).
// Unlike the patch tracker (tracker.h, which stays for video) nothing here assumes the views are
// near each other: views taken far apart, turned in their plane or in any order match as long as
// they overlap.
//
//   ImageSetMatchingOptions options;                 // all pairs, COLMAP's thresholds
//   auto detector = MakeDetector("harris");
//   ImageSetMatching result = MatchImageSet(sequence, *detector, options, progress);
//   // result.tracks (with result.tracks.descriptors), result.summary
//
// Cost: description is linear in the features; matching is quadratic in the frames and in the
// features per frame (a 2000 x 2000 pair is 0.5 G multiply-adds); pairs run on num_threads
// threads. Deterministic: every frame and every pair is computed independently and the results
// are collected in frame and pair order, so the output is the same for any thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "frontend/description/sift_descriptor.h"
#include "frontend/detector.h"
#include "frontend/feature_masks.h"
#include "frontend/matching/descriptor_matcher.h"
#include "frontend/matching/match_verification.h"
#include "frontend/matching/track.h"
#include "frontend/matching/track_builder.h"

namespace comic::io {
class ImageSequence;
}

namespace comic::frontend {

struct ImageSetMatchingOptions {
  // Features per frame: response >= min_response, at most max_features strongest (0 = all).
  float min_response = -std::numeric_limits<float>::max();
  int max_features = 2000;
  // Frame pairs: every pair (0), or each frame with the next `window` frames.
  int window = 0;
  // With a window, each frame is also matched with the frames 2^k after it (k >= 0, as far as
  // the sequence goes): COLMAP's sequential matcher's quadratic overlap. A video whose tracks
  // break for a few frames (blur, a passing occluder) is still linked across the break, and the
  // pairs grow as n log n rather than n².
  bool quadratic_overlap = false;
  // Unset: DescriptorOptionsFor(the detector's name), the options measured for its features.
  std::optional<DescriptorOptions> descriptor;
  DescriptorMatchOptions matching;
  // Geometric verification of every pair; COLMAP's SiftMatchingOptions defaults: 4 px, at
  // least 15 inliers, RANSAC budget for a 25 % inlier ratio.
  MatchVerificationOptions verification;
  // A verified pair is matched again along its epipolar lines (MatchDescriptorsAlongEpipolarLines
  // within guided_max_error_px: COLMAP's guided_matching) and keeps the larger of the two match
  // sets, for pairs where look-alikes made the first ratio test reject true matches. Off, as in
  // COLMAP, until it is measured (docs/descriptors.md gives the results without it).
  bool guided_matching = false;
  // The ratio test along the lines: fewer look-alikes compete there than in the whole image, so
  // it may be looser than matching.max_ratio.
  double guided_max_ratio = 0.9;
  // The band around the lines (pixels; the verification's max_error_px allows more).
  double guided_max_error_px = 2.0;
  // Conflicting matches (a component holding two features of one frame).
  TrackConflictRule conflict_rule = TrackConflictRule::kGreedyByCost;
  // Threads for description and matching (0: one per core). The result does not depend on it.
  int num_threads = 0;

  ImageSetMatchingOptions();
  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// What matching met and what it cost (CPU seconds of the threads that did the work, summed).
struct ImageSetMatchingSummary {
  int num_frames = 0;
  int64_t num_features = 0;
  int num_pairs = 0;           // frame pairs matched
  int num_verified_pairs = 0;  // pairs that kept verified matches
  int64_t num_raw_matches = 0;
  int64_t num_verified_matches = 0;
  double detection_cpu_s = 0.0;
  double description_cpu_s = 0.0;
  double matching_cpu_s = 0.0;
  double verification_cpu_s = 0.0;
  double track_building_cpu_s = 0.0;
};

struct ImageSetMatching {
  FeatureTracks tracks;  // with descriptors
  TrackBuildSummary track_building;
  // The verified matches of every pair that kept any, by (frame1, frame2).
  std::vector<FramePairMatches> verified_pairs;
  ImageSetMatchingSummary summary;
};

// Called with (work done, total work): frames described, then pairs matched, counted together.
using ImageSetMatchingProgress = std::function<void(size_t done, size_t total)>;

// `progress` (frames done, frames) told the work of MatchImageSet in frames, as the patch tracker
// tells its own: frame k of n once k/n of the steps are done, each k once, in order.
ImageSetMatchingProgress ProgressInFrames(std::function<void(size_t, size_t)> progress,
                                          size_t num_frames);

// The frame pairs (i < j) matched for `num_frames` frames: all of them (window 0), or those with
// j − i <= window, and with `quadratic_overlap` also those with j − i a power of two. In order of
// i, then j.
std::vector<std::pair<int, int>> ImageSetPairs(int num_frames, int window,
                                               bool quadratic_overlap = false);

// Matches the frames of `sequence` (as opened, e.g. resized). A combined detector's components are
// detected, described and matched one by one (features of different detectors are never matched
// to each other) and the results merged as frontend/matching/combined_tracking.h does. Throws
// comic::Error for bad options or unreadable frames. `filter` (frontend/feature_masks.h), when
// set, is applied to each frame's detection before the features are selected.
ImageSetMatching MatchImageSet(const io::ImageSequence& sequence, const Detector& detector,
                               const ImageSetMatchingOptions& options,
                               const ImageSetMatchingProgress& progress = {},
                               const DetectionFilter& filter = {});

// Adds descriptors to tracks made without them (the patch tracker's): every feature of every frame
// of `sequence` (the frames the tracks were made from, read again) described with `options`, or
// DescriptorOptionsFor(tracks->detector_name) when unset, on `num_threads` threads (the result
// does not depend on it). So that an exported database carries descriptors for COLMAP's matchers.
// Returns the CPU seconds description took. Throws comic::Error(kInvalidArgument) when the tracks
// are not of the sequence's frames.
double DescribeTrackedFeatures(const io::ImageSequence& sequence, FeatureTracks* tracks,
                               int num_threads,
                               const std::optional<DescriptorOptions>& options = std::nullopt,
                               const ImageSetMatchingProgress& progress = {});

// The same over grey frames in memory (all CV_8UC1 of one size); `frame_names` may be empty.
ImageSetMatching MatchImageFrames(const std::vector<cv::Mat>& grays, const Detector& detector,
                                  const ImageSetMatchingOptions& options,
                                  const std::vector<std::string>& frame_names = {},
                                  const ImageSetMatchingProgress& progress = {});

}  // namespace comic::frontend
