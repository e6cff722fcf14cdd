// Feature tracks judged against rendered truth (io/datasets/rendered_truth.h): which features lie
// on occlusion boundaries, how long their tracks live, and whether a track follows one 3-D
// surface point or slides along a silhouette — the question behind the paper's claim that
// CoMIC's side-aware matching helps at object boundaries (§4), asked of the tracks SfM consumes.
//
// A track is a *boundary track* when at least half of its observations lie in the occlusion-
// boundary band. It *follows a surface point* when one 3-D point explains its observations through
// the true cameras to an RMS of `follow_tolerance_px`: the candidates are the surfaces seen around
// its first, middle and last observations (the true depths within `neighbourhood_px`, back-
// projected through the observed position; three anchors, so that one noisy detection does not
// decide), or, where no depth is known (a composited object), the point triangulated from all its
// observations. Otherwise it *slides*: the feature stayed on an image structure (a T-junction of a
// silhouette with the background, say) that no surface point makes. RMS rather than the largest
// error: a detector's jitter of a pixel in one frame is not a slide, a slide grows over the track.
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/camera.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

struct BoundaryTrackOptions {
  // A track follows a surface point if one point reprojects to an RMS within this (pixels).
  double follow_tolerance_px = 1.5;
  // Tracks with fewer observations are counted but neither following nor sliding.
  int min_track_length = 3;
  // Depth candidates come from the (2n+1)^2 pixels around the first observation.
  int neighbourhood_px = 1;

  void Check() const;
};

struct TrackTruth {
  bool boundary = false;    // at least half of the observations in the band
  bool classified = false;  // long enough and with a candidate point
  bool follows = false;     // one 3-D point explains every observation
  double drift_px = 0.0;    // the best candidate's RMS reprojection error
  double worst_px = 0.0;    // and its largest
};

// Summary of a set of tracks (the boundary ones, or the others).
struct TrackSetSummary {
  size_t num_tracks = 0;
  double mean_length = 0.0;  // observations per track
  double median_length = 0.0;
  size_t num_classified = 0;
  size_t num_following = 0;
  double median_drift_px = 0.0;  // over the classified ones

  double FollowingFraction() const {
    return num_classified == 0 ? 0.0 : static_cast<double>(num_following) / num_classified;
  }
};

struct BoundaryTrackEvaluation {
  size_t num_features = 0;              // every detected feature of every frame
  size_t num_boundary_features = 0;     // of which in the band
  double boundary_area_fraction = 0.0;  // mean share of the image the band covers
  std::vector<TrackTruth> tracks;       // one per track of the input
  TrackSetSummary boundary;
  TrackSetSummary other;
};

// The truth of frame k: its band (CV_8UC1, non-zero = boundary) and depth (CV_32F metres; 0 where
// nothing is drawn (sky: a point at infinity), +inf beyond a PNG's range (taken as infinity too),
// NaN where unknown). Called once per frame, in order.
struct FrameTruth {
  cv::Mat band;
  cv::Mat depth;
};
using FrameTruthFn = std::function<FrameTruth(int frame)>;

// Frame k of `tracks` is seen from cams_from_world[k] through `camera`. Throws
// comic::Error(kInvalidArgument) for sizes that disagree or bad options.
BoundaryTrackEvaluation EvaluateBoundaryTracks(const frontend::FeatureTracks& tracks,
                                               const Camera& camera,
                                               const std::vector<Rigid3d>& cams_from_world,
                                               const FrameTruthFn& truth,
                                               const BoundaryTrackOptions& options);

// Summarises the tracks picked by `pick` (per track index).
TrackSetSummary SummarizeTracks(const frontend::FeatureTracks& tracks,
                                const std::vector<TrackTruth>& truth,
                                const std::function<bool(size_t)>& pick);

}  // namespace comic::sfm
