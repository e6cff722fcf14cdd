// Structure from motion on a frame sequence, end to end: detect and track features
// (frontend::TrackSequence with any Detector; for an image set, match descriptors of every frame
// pair instead: frontend/matching/image_set_matching.h), reconstruct incrementally, colour the
// points. The
// SfM itself only sees the tracks, so every detector is treated alike; a combined detector
// ("comic+hessian") is tracked one component at a time (frontend/matching/combined_tracking.h).
//
//   SequenceReconstructionOptions options;          // tracker set up for video SfM
//   auto detector = frontend::MakeDetector("harris");
//   SequenceReconstruction run = ReconstructSequence(sequence, *detector, camera, options);
//   if (HasModel(run.mapping.status)) { ... run.mapping.reconstruction (the largest model) }
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "frontend/detector.h"
#include "frontend/feature_masks.h"
#include "frontend/matching/image_set_matching.h"
#include "frontend/matching/track.h"
#include "frontend/matching/tracker.h"
#include "io/image/image_sequence.h"
#include "sfm/camera.h"
#include "sfm/incremental_pipeline.h"
#include "sfm/moving_object.h"

namespace comic::sfm {

struct SequenceReconstructionOptions {
  // Feature tracking. The defaults differ from the paper's matching protocol where video SfM
  // needs it: constant-velocity motion prediction (near points move tens of pixels per frame in
  // driving video), a 60 px radius where nothing predicts a feature, and the 2000 strongest
  // features per frame.
  frontend::TrackerOptions tracker;
  // Image sets: when set, features are matched by descriptors over frame pairs with these options
  // (views far apart, turned, in any order) instead of being tracked (`tracker` is then unused).
  std::optional<frontend::ImageSetMatchingOptions> image_set;
  // Masks of moving objects (frontend/feature_masks.h), one per frame at the frames' size as
  // tracked: every feature they drop is removed from each frame's detection before tracking or
  // matching, on both paths. Shared, not copied: a long clip's masks are large. Null: none.
  std::shared_ptr<const frontend::FeatureMasks> feature_masks;
  // Incremental mapping.
  IncrementalPipelineOptions mapper;
  // Models whose tracks do not meet are linked through matches between the frames at their
  // seams (IncrementalPipelineOptions::seam_num_frames): the tracker's matcher on the two frames
  // with coarse-to-fine prediction and geometric verification (MakeSeamMatcher).
  bool match_seams = true;
  // A second rigid motion (an object moving through the view) found without masks: the model is
  // then suspect (sfm/moving_object.h).
  MovingObjectOptions moving_object;

  SequenceReconstructionOptions();
  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct SequenceReconstruction {
  std::string detector_name;
  frontend::FeatureTracks tracks;  // what the mapper consumed
  // Matches given to the track builder and what it dropped or refused (conflicts arise only with
  // tracker.match_window > 1).
  frontend::TrackBuildSummary track_building;
  // With options.image_set: what descriptor matching met and cost.
  std::optional<frontend::ImageSetMatchingSummary> image_set_matching;
  // Detected features removed by options.feature_masks (before the per-frame max_features cap).
  int64_t masked_features = 0;
  IncrementalReconstruction mapping;  // in the pixels of the frames (the working size)
  // What the search for a second rigid motion found (options.moving_object).
  MovingObjectCheck moving_object;
  // The size of the frames as stored; the frames were worked on at `frame_size` (resized, e.g. to
  // the working resolution: sfm/working_resolution.h). Models are written in the input's pixels.
  cv::Size input_size;
  cv::Size frame_size;
  // Detection and tracking (or description and matching), and the description of the tracked
  // features for loop closure.
  double tracking_time_s = 0.0;
  double mapping_time_s = 0.0;   // incremental reconstruction
  double coloring_time_s = 0.0;  // reading frames again for point colours
  double wall_time_s = 0.0;      // everything
};

// What tracking (or image-set matching) found: all the mapper needs from the frames, and what a
// track cache keeps (sfm/run/track_cache.h).
struct SequenceTracking {
  frontend::FeatureTracks tracks;
  frontend::TrackBuildSummary track_building;
  std::optional<frontend::ImageSetMatchingSummary> image_set_matching;  // with options.image_set
  int64_t masked_features = 0;  // detected features removed by options.feature_masks
  double time_s = 0.0;  // detection and tracking (or description and matching; or a cache read)
};

// The first half of ReconstructSequence: detection and tracking (or, with options.image_set,
// description and matching). Throws comic::Error for bad options and unreadable frames.
SequenceTracking TrackFrames(const io::ImageSequence& sequence, const frontend::Detector& detector,
                             const SequenceReconstructionOptions& options,
                             const frontend::TrackingProgress& tracking_progress = {});

// The second half: incremental mapping of `tracking` (TrackFrames of the same sequence, detector
// and options, or the same read back from a cache) and the colouring. `detector` is used again
// only to link models that do not meet (MakeSeamMatcher: detection on a seam's two frames).
// Throws comic::Error(kInvalidArgument) when the camera or the tracks do not fit the frames.
SequenceReconstruction ReconstructFromTracks(const io::ImageSequence& sequence,
                                             const frontend::Detector& detector,
                                             const Camera& camera,
                                             const SequenceReconstructionOptions& options,
                                             SequenceTracking tracking,
                                             const MapperProgressCallback& mapper_progress = {});

// TrackFrames then ReconstructFromTracks: tracks `sequence` with `detector`, reconstructs it with
// `camera` (intrinsics at the size of the sequence's frames), and colours the points. Throws
// comic::Error for invalid input (camera size different from the frames, bad options, unreadable
// frames); a reconstruction that cannot start comes back as mapping.status.
SequenceReconstruction ReconstructSequence(const io::ImageSequence& sequence,
                                           const frontend::Detector& detector, const Camera& camera,
                                           const SequenceReconstructionOptions& options,
                                           const frontend::TrackingProgress& tracking_progress = {},
                                           const MapperProgressCallback& mapper_progress = {});

// The seam matcher of `sequence` (its frames as tracked into `tracks` with `tracker`): the
// features of the two frames matched by the tracker's patch matcher with coarse-to-fine
// prediction (`detector` finds the coarse features), then verified geometrically.
FrameMatcher MakeSeamMatcher(const io::ImageSequence& sequence, const frontend::Detector& detector,
                             const frontend::FeatureTracks& tracks,
                             const frontend::TrackerOptions& tracker);

// Sets each point's colour to the mean colour (bilinear) of its observations in the frames of
// `sequence`; image i + 1 of the reconstruction is frame i (as the mapper numbers them).
void ColorizeReconstruction(const io::ImageSequence& sequence, Reconstruction* reconstruction);

}  // namespace comic::sfm
