// The two stages the tracker adds to detect-and-match for real video (issue 30), both built on
// pyramidal patch alignment (patch_alignment.h):
//
//  1. Guided search. Each feature of frame i is aligned into frame i+1 from its predicted
//     position (the motion prediction's search centre); where the alignment is trusted (it
//     converged with a small residual after gain and bias), the matcher searches the detections
//     of frame i+1 only within a small radius of the aligned position instead of the wide
//     predicted region. A shaky camera, a large motion or a change of exposure then no longer
//     sends the search to the wrong place, and fewer wrong candidates compete under the
//     one-to-one rule.
//  2. Continuation. A feature whose track found no detection in frame i+1 (the detector missed
//     it: motion blur, a change of scale, a weak corner) but whose alignment is trusted continues
//     at the aligned position, as a feature of frame i+1 that copies its predecessor (scale,
//     response, side mask...) with the new position. A track may continue so for a limited number
//     of consecutive frames; it goes on as before as soon as a detection is matched to it again
//     (re-association after a gap), and it ends when the limit is reached.
//
//   std::vector<PatchAlignment> aligned =
//       AlignFeatures(features1, pyramid1, pyramid2, predicted, weights, options.alignment);
//   SearchRegions search = GuidedSearchRegions(features1, predicted, radius, aligned, options);
//   ... match ...
//   std::vector<Continuation> more = ContinueUnmatched(features1, runs1, features2, accepted,
//                                                      aligned, options);
#pragma once

#include <vector>

#include "frontend/feature.h"
#include "frontend/matching/patch_alignment.h"
#include "frontend/matching/patch_matcher.h"

namespace comic::frontend {

struct TrackContinuationOptions {
  // The alignment (pyramid levels, window, iterations...).
  PatchAlignmentOptions alignment;
  // An alignment is trusted when its residual (mean squared difference after gain and bias,
  // grey levels²) is at most this.
  double max_residual = 400.0;
  // ... and its normalised cross-correlation at least this.
  double min_correlation = 0.8;
  // Search radius around a trusted alignment (pixels): the detector's position of a corner and
  // the aligned position of its patch differ by its localisation error, larger under blur.
  double aligned_radius = 4.0;
  // Consecutive frames a track may continue without a matched detection (0 = never).
  int max_continued_frames = 0;
  // A continuation within this distance (pixels) of a feature another track already holds in
  // frame i+1, or of a better continuation, is not made: two tracks would follow one point.
  double min_separation = 2.0;
  // Re-association after a gap: a track that ended at frame i (no match, no continuation into
  // i+1: a frame too blurred, an occlusion) is aligned from frame i into each of the frames i+2 ..
  // i+bridge_frames until it is found; there it takes a detection within aligned_radius of
  // the aligned position that no track holds, or, within max_continued_frames of its last
  // detection, continues at the aligned position. 0 or 1 = no gaps.
  int bridge_frames = 0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// Aligns each feature of frame 1 (features1 on pyramid1) into pyramid2, starting at its search
// centre in `predicted` (its own position if `predicted` has no centres). `weights` is empty (the
// full window for every feature) or holds one entry per feature (an empty entry = the full
// window).
std::vector<PatchAlignment> AlignFeatures(const FeatureSet& features1, const ImagePyramid& pyramid1,
                                          const ImagePyramid& pyramid2,
                                          const SearchRegions& predicted,
                                          const std::vector<AlignmentWeights>& weights,
                                          const PatchAlignmentOptions& options);

// True if `alignment` is trusted under `options`.
bool IsTrusted(const PatchAlignment& alignment, const TrackContinuationOptions& options);

// `predicted` (empty = own position, `default_radius`) with every trusted alignment's position and
// options.aligned_radius in place of the prediction.
SearchRegions GuidedSearchRegions(const FeatureSet& features1, const SearchRegions& predicted,
                                  double default_radius, const std::vector<PatchAlignment>& aligned,
                                  const TrackContinuationOptions& options);

// The displacement of the `k` tracked features nearest to each point of `points` (median of the
// samples within `max_distance`), added to the point: the start of an alignment across several
// frames. A point without a sample near it stays where it is.
struct MotionSample {
  cv::Point2f position;
  cv::Point2f displacement;
};
std::vector<cv::Point2f> PredictFromNeighbours(const std::vector<cv::Point2f>& points,
                                               const std::vector<MotionSample>& samples, int k,
                                               double max_distance);

// A feature of frame 1 continued into frame 2 without a detection.
struct Continuation {
  int index1 = -1;  // the feature of frame 1
  Feature feature;  // its copy at the aligned position
  float residual = 0.0f;
};

// The continuations into frame 2 (see above): each feature of frame 1 not in `accepted`
// (index1), whose alignment is trusted and whose run of continued frames `runs1` (0 for a
// detection) is below options.max_continued_frames, unless a feature of frame 2 matched in
// `accepted` or a continuation of lower residual lies within options.min_separation. Ordered by
// index1. Throws comic::Error(kInvalidArgument) for inputs of mismatched sizes.
std::vector<Continuation> ContinueUnmatched(const FeatureSet& features1,
                                            const std::vector<int>& runs1,
                                            const FeatureSet& features2,
                                            const std::vector<PatchMatch>& accepted,
                                            const std::vector<PatchAlignment>& aligned,
                                            const TrackContinuationOptions& options);

}  // namespace comic::frontend
