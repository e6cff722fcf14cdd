// How long the SfM tracker's tracks live on real video, beside a reference that follows the same
// points without re-detecting them: OpenCV's pyramidal Lucas–Kanade (cv::calcOpticalFlowPyrLK)
// with a forward–backward check. And where the tracks that die are lost (issue 30): each feature
// of frame i whose LK reference position in frame i+1 is known is either continued by its track
// (to that position, or elsewhere) or lost, and a lost one is charged to the first stage of the
// tracker that could not find it: not re-detected near the reference, re-detected outside its
// search region, above the cost threshold, or beaten under the one-to-one (mutual best) rule.
//
//   std::vector<int> starts = SurvivalStartFrames(150, 10, 10);   // 0, 10, ..., 130
//   SurvivalSummary ours = SummariseSurvival(FramesFollowedFrom(result.tracks, starts));
//   SurvivalSummary lk = SummariseSurvival(LkFramesFollowedFrom(grays, result.tracks, starts, {}));
//
// "Followed" = how many frames after its start frame a feature is still in its track (the last
// frame of the track; a track that skips a frame and resumes counts to where it resumes), for LK
// how many frames it is followed frame to frame until the flow fails or leaves the image.
#pragma once

#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/matching/track.h"
#include "frontend/matching/tracker.h"

namespace comic::frontend {

struct LkReferenceOptions {
  // cv::calcOpticalFlowPyrLK: window side (pixels), pyramid levels above the base, iterations and
  // convergence epsilon per level.
  int window = 21;
  int levels = 3;
  int max_iterations = 30;
  double epsilon = 0.01;
  // A point is followed only if tracking it back lands within this distance of where it started
  // (pixels) and it stays inside the image by the patch radius.
  double max_forward_backward_px = 1.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The LK positions of `points` (of gray1) in gray2, and whether each passed the checks.
struct LkFlow {
  std::vector<cv::Point2f> positions;
  std::vector<bool> valid;
  std::vector<bool> outside;  // the window left the image (status failed or beyond the margin)
};

// Deterministic (each point is tracked on its own). Throws comic::Error(kInvalidArgument) for
// images that are not CV_8UC1 of one size.
LkFlow TrackPointsLk(const cv::Mat& gray1, const cv::Mat& gray2,
                     const std::vector<cv::Point2f>& points, const LkReferenceOptions& options);

// Start frames 0, stride, 2·stride, ... that leave `horizon` frames after them in a sequence of
// `num_frames` (at least frame 0 if the sequence is shorter).
std::vector<int> SurvivalStartFrames(int num_frames, int stride, int horizon);

// For every detected feature of every start frame (start frames in order, features in order; a
// continued feature, TrackingResult::continued, is not a start): the frames it is followed by
// its track.
std::vector<int> FramesFollowedFrom(const TrackingResult& result, const std::vector<int>& starts);

// The same for LK started at the same features' positions, over `grays` (the frames the tracks
// were built on).
std::vector<int> LkFramesFollowedFrom(const std::vector<cv::Mat>& grays,
                                      const TrackingResult& result, const std::vector<int>& starts,
                                      const LkReferenceOptions& options);

struct SurvivalSummary {
  int num_features = 0;
  // Fractions of the features followed >= 1, >= 5 and >= 10 frames.
  std::array<double, 3> share_followed = {0, 0, 0};
  double mean_frames_followed = 0.0;
  // Mean length (observations = frames followed + 1) of the features followed at least one frame:
  // the quantity report.json's tracker.mean_track_length averages over every track.
  double mean_track_length = 0.0;
};
SurvivalSummary SummariseSurvival(const std::vector<int>& frames_followed);

// report.json's tracker.mean_track_length: observations per track over all tracks.
double MeanTrackLength(const FeatureTracks& tracks);

// Where a feature of frame i goes in frame i+1.
enum class FeatureFate {
  kContinued,             // its track continues to a detection near the reference position
  kContinuedElsewhere,    // ... to a detection far from it (a mismatch, or LK's error)
  kContinuedByAlignment,  // ... to a continued feature (no detection; align_patches)
  kLeavesImage,           // LK takes its window out of the image
  kNoReference,           // LK cannot follow it (occluded, blurred, fails its check)
  kNotDetected,           // no feature of frame i+1 (not even one cut by max_features) near it
  kCutByMaxFeatures,      // re-detected, but not among the max_features strongest
  kOutsideSearch,         // re-detected and kept, but outside the region it was searched in
  kAboveThreshold,        // inside, but the patch cost exceeds the threshold
  kLostMutualBest,        // inside and below the threshold, but not the one-to-one choice
  // With align_patches, a feature not re-detected (or cut) is lost because it was not continued:
  kAlignmentUntrusted,  // its alignment failed or was not trusted
  kContinuationLimit,   // its track had been continued max_continued_frames already
  kNextToAnotherTrack,  // another track's feature (or a better continuation) lay too close
};
inline constexpr int kNumFeatureFates = 13;
const char* FeatureFateName(FeatureFate fate);

struct LossSplitOptions {
  // A feature of frame i+1 within this distance of the reference position is "the same" feature.
  double reference_tolerance_px = 2.0;
  // A feature whose reference motion is farther than this from the epipolar geometry of all the
  // reference motions (fundamental matrix, RANSAC) counts as moving (independently moving
  // objects; also LK's own errors).
  double moving_epipolar_px = 2.0;
};

struct LossSplit {
  int num_features = 0;
  // counts[fate][0]: static features, [1]: moving ones.
  std::array<std::array<int, 2>, kNumFeatureFates> counts = {};
  // Features lost at i+1 whose track resumes at a later frame (re-association after a gap).
  int resumed_later = 0;
};

// The split of the features of `frame` (result.tracks.features[frame]) into their fates in frame
// + 1. `detected_next` = every detection of frame + 1 before SelectTrackableFeatures (to tell
// "not detected" from "cut"); grays are the two frames. Throws comic::Error(kInvalidArgument) for
// a frame without a next one.
LossSplit SplitLosses(const TrackingResult& result, int frame, const cv::Mat& gray,
                      const cv::Mat& gray_next, const FeatureSet& detected_next,
                      const LkReferenceOptions& lk, const LossSplitOptions& options);

// Adds b to a.
void Accumulate(const LossSplit& b, LossSplit* a);

// How well the tracks agree with known cameras (KITTI): every track of three or more
// observations is triangulated from all of them with the true poses (linear, least squares), and
// each observation's reprojection error is counted, for detected and continued observations
// apart. A track that drifts, or joins two points, leaves observations far from its point.
struct TrackAccuracy {
  std::array<int, 2> observations = {0, 0};  // [0] detected, [1] continued
  std::array<int, 2> beyond_tolerance = {0, 0};
  std::array<double, 2> median_error_px = {0, 0};
  int tracks = 0;  // triangulated (in front of every camera)
};

// `world_from_camera` per frame (camera-to-world [R | t], KITTI's convention), `K` at the frames'
// size. Throws comic::Error(kInvalidArgument) for a pose count that differs from the frames.
TrackAccuracy EvaluateTrackAccuracy(const TrackingResult& result, const cv::Matx33d& K,
                                    const std::vector<cv::Matx34d>& world_from_camera,
                                    double tolerance_px);

}  // namespace comic::frontend
