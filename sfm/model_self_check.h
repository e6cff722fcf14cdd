// A model checked against its own evidence, without ground truth: a wrong model can have a low
// reprojection error (it explains the tracks it kept), but the frame pairs it is made of still
// say, each on its own, how one camera is turned against the other. Every registered frame is
// paired with frames it shares tracks with; the pair's relative pose is estimated again from
// those correspondences alone (an essential matrix, as the initial pair is) and its rotation is
// compared with the model's. Rotation-averaging methods test their pairs the same way (a pair
// whose rotation disagrees with the cycle it closes is an outlier); here the disagreement
// condemns the model instead: when too many of its well-conditioned pairs disagree, the run
// says `suspect` and why, never `success`.
//
//   const ModelSelfCheck check = CheckModelAgainstItsPairs(model, tracks, {});
//   if (check.suspect) std::cerr << check.reason;
#pragma once

#include <string>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/reconstruction.h"
#include "sfm/two_view_geometry.h"

namespace comic::sfm {

struct ModelSelfCheckOptions {
  // A pair is estimated when its frames share at least this many tracks.
  int min_shared_tracks = 40;
  // ... and when the model puts the two cameras at least this far apart, seen from the nearer
  // one's median depth (degrees): the pair's own relative pose is then estimated (an essential
  // matrix; a homography-like pair still tests the rotation) ...
  double min_parallax_deg = 1.0;
  // ... and kept when at least this fraction of the shared tracks are inliers of that pose: a pair
  // whose correspondences mostly disagree with each other (tracks chained through other frames) has
  // no coherent evidence of its own.
  double min_inlier_ratio = 0.5;
  // The pair disagrees with the model when its inliers lie, in the median, more than this many
  // times farther (Sampson distance) from the model's epipolar geometry of the pair than from the
  // pair's own (with min_error_px as the least own distance counted). The rotations themselves
  // are only reported: with a narrow field of view an essential matrix trades rotation against
  // translation (the bas-relief ambiguity), and pairs of a right model differ from it by up to
  // 10 deg while fitting it as well as their own estimate.
  double max_error_ratio = 3.0;
  double min_error_px = 0.5;
  // The model is suspect when more than this fraction of the kept pairs disagree, and at least
  // min_disagreeing_pairs do: a model that went wrong once (a wrong link, a turn it got wrong)
  // is contradicted only by the few pairs across the break, whatever its length, while a few
  // pairs whose own estimate is wrong (a moving object, a repeated facade) must not condemn it.
  double max_disagreeing_fraction = 0.05;
  int min_disagreeing_pairs = 3;
  // ... and at least this many pairs were kept (fewer: nothing to say either way).
  int min_pairs = 5;
  // Cost bound: each frame is paired with at most this many partners (among those the model
  // gives at least min_triangulation_angle_deg of parallax, most shared tracks first), trying at
  // most twice as many.
  int max_pairs_per_frame = 2;
  TwoViewGeometryOptions two_view;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// One kept pair the model's cameras do not explain, for the report: which frames, by how much.
struct DisagreeingPair {
  int frame1 = 0;
  int frame2 = 0;
  double error_ratio = 0.0;  // the model's median distance over the pair's own
  double rotation_difference_deg = 0.0;
  int inliers = 0;  // of the pair's own pose
  int shared_tracks = 0;
};

struct ModelSelfCheck {
  int pairs_checked = 0;      // kept: a pose with enough of the shared tracks as inliers
  int pairs_disagreeing = 0;  // of those, the model's epipolar geometry fits too badly
  // Over the kept pairs: the model's median distance over the pair's own, and the angle between
  // the model's relative rotation and the pair's own.
  double median_error_ratio = 0.0;
  double median_rotation_difference_deg = 0.0;
  double max_rotation_difference_deg = 0.0;
  bool suspect = false;
  std::string reason;                        // one sentence when suspect, empty otherwise
  std::vector<DisagreeingPair> disagreeing;  // in frame order, suspect or not
  // Set by the pipeline when a larger model was suspect and this one, which its pairs do not
  // contradict, is returned in its place: the larger model's registered frames and its check's
  // disagreeing pairs (0: no model was passed over).
  int passed_over_model_frames = 0;
  int passed_over_pairs_disagreeing = 0;
};

// Checks the registered images of `model` (image i + 1 is frame i of `tracks`, in the same
// pixels) against the pairwise evidence in `tracks`. Deterministic.
ModelSelfCheck CheckModelAgainstItsPairs(const Reconstruction& model,
                                         const frontend::FeatureTracks& tracks,
                                         const ModelSelfCheckOptions& options);

// Which of a run's models to return first, and its check.
struct KeptModelChoice {
  size_t index = 0;  // into the models given
  ModelSelfCheck check;
};

// `models` (one run's, largest first) checked in turn: the first model's check, and when it is
// suspect, the first later model holding at least `yield_fraction` of the first's registered
// frames whose own pairs do not contradict it (with at least options.min_pairs pairs kept), with
// its passed_over_* fields set. Two models that grew over the same frames and could not be merged
// are two answers for those frames; the one its evidence contradicts is the worse answer whatever
// its size. Deterministic.
KeptModelChoice ChooseKeptModel(const std::vector<const Reconstruction*>& models,
                                const frontend::FeatureTracks& tracks,
                                const ModelSelfCheckOptions& options, double yield_fraction);

}  // namespace comic::sfm
