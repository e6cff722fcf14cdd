// An object moving through the view, found without masks: the tracks the model cannot explain
// are mapped on their own, and when they make a second model of nearly every frame, one that
// does not explain the first model's tracks either, two rigid motions are in the clip. The
// mapper builds its model on the larger rigid body, which is the moving object when the object
// gives more features than the world behind it (a textured truck crossing a street), and such a
// model is consistent with its own frame pairs, so the self-check cannot see it. Which motion is
// the world is not decided here: the model is called suspect, with the reason, rather than a
// success (docs/results.md gives the measurements and what was tried to choose the world).
//
// A track is explained by a model when the point triangulated from its observations in the
// model's registered frames reprojects within max_explained_drift_px (RMS; sfm/track_drift.h).
// A static scene leaves few tracks unexplained (sliding ones, mismatches), and they rarely make a
// model of their own; when they do, that model explains the first one's tracks too (one world).
//
//   MovingObjectCheck check = CheckForMovingObject(tracks, camera, mapper_options, options,
//                                                  &mapping);
#pragma once

#include <string>

#include "frontend/matching/track.h"
#include "sfm/camera.h"
#include "sfm/incremental_pipeline.h"

namespace comic::sfm {

struct MovingObjectOptions {
  bool enabled = true;
  // RMS reprojection error (pixels) within which a model explains a track.
  double max_explained_drift_px = 1.0;
  // The unexplained tracks (of those with >= 3 views in the model's frames) are mapped on their
  // own only when there are at least this many, and this share of them (a bound on the cost: a
  // moving object with many features leaves the world a minority of the tracks).
  int min_unexplained_tracks = 150;
  double min_unexplained_fraction = 0.1;
  // At most this many of them are mapped (every k-th, in track order): enough for a second
  // motion's model, and the second mapping stays a fraction of the first on long clips.
  int max_tracks_mapped_again = 1500;
  // Their model is a second motion when it registers at least this share of the first model's
  // frames and explains less than max_shared_explanation of the tracks the first explains (else
  // both are models of one world, the second from the first's leftovers).
  double min_second_model_frames = 0.8;
  double max_shared_explanation = 0.5;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct MovingObjectCheck {
  bool mapped_again = false;   // enough unexplained tracks to map them on their own
  int measured_tracks = 0;     // tracks with >= 3 views in the model's registered frames
  int unexplained_tracks = 0;  // of those, not explained by the model
  int second_model_frames = 0;
  // Of the tracks the model explains, the share the second model explains too.
  double first_tracks_explained_by_second = 0.0;
  bool second_motion = false;  // two rigid motions: the model was made suspect
  std::string reason;          // one sentence: what was found
};

// Checks `*mapping` (the model ReconstructIncrementally built from `tracks` with
// `mapper_options`) for a second rigid motion as above; when one is found, a model that was a
// success or partial becomes suspect with the reason. Deterministic.
MovingObjectCheck CheckForMovingObject(const frontend::FeatureTracks& tracks, const Camera& camera,
                                       const IncrementalPipelineOptions& mapper_options,
                                       const MovingObjectOptions& options,
                                       IncrementalReconstruction* mapping);

}  // namespace comic::sfm
