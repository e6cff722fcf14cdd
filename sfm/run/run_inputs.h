// What every detector of a run shares, resolved and validated once before any heavy work: the
// frames, the ground truth matched to them, the camera (camera_resolution.h), the object regions,
// the plane of the trajectory plot, the frame pairs matched and the tracker options they give.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frontend/feature_masks.h"
#include "frontend/matching/image_set_matching.h"
#include "frontend/matching/pairing.h"
#include "frontend/matching/tracker.h"
#include "io/datasets/ground_truth_cameras.h"
#include "io/image/image_sequence.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/evaluation/reconstruction_stats.h"
#include "sfm/evaluation/trajectory_plot.h"
#include "sfm/run/camera_resolution.h"
#include "sfm/run/run_options.h"

namespace comic::sfm {

// One way of matching the frames: the patch tracker with `tracker` (no image_set), or
// descriptors with `image_set`.
struct MatcherAttempt {
  frontend::TrackerOptions tracker;
  std::optional<frontend::ImageSetMatchingOptions> image_set;
};

struct RunInputs {
  std::unique_ptr<io::ImageSequence> sequence;
  std::vector<int> source_indices;  // per frame: its index in the folder or video
  // The frames were opened at the working size (--max-working-size), smaller than stored; the
  // models are written at the stored size (sequence->SourceFrameSize()).
  bool at_working_size = false;
  ResolvedCamera camera;
  std::optional<FrameGroundTruth> ground_truth;
  io::GroundTruthFormat gt_format = io::GroundTruthFormat::kAuto;
  std::vector<cv::Mat> region_labels;  // per frame, empty without --regions / --masks
  // --masks: the features every detector drops, per frame (mask_drops_nonzero, a 2 px margin;
  // frontend/feature_masks.h). Null without --masks (--regions only label).
  std::shared_ptr<const frontend::FeatureMasks> feature_masks;
  PlotPlane plot_plane;
  bool plot_plane_from_estimate = false;  // auto without ground truth: PCA of our centres
  frontend::PairingChoice pairing;        // --matching resolved on the frames
  frontend::TrackerOptions tracker;       // the tracker settings set up for that pairing
  // --matcher resolved: the descriptor matching of the pairs, or none (the patch tracker).
  std::optional<frontend::ImageSetMatchingOptions> image_set;
  // What matches the frames, tried in order until a model holds every frame (ResolveMatchers).
  std::vector<MatcherAttempt> matchers;
};

// What --matcher auto tries, in order; the next only while no model holds every frame, and the
// better model is kept: the auto choice's two paths compared where they differ.
//  - A video: the patch tracker with every frame pair verified (fast, and on a clean drive the
//    more precise: its links align the patches themselves), then descriptors over a window of
//    frames (their links survive blur and passing occluders).
//  - An image set: the patch tracker's image-set set-up (right on the temple ring, where
//    descriptors alone once built a wrong model), then descriptors (right on the NeRF lego set,
//    where the patches find no initial pair).
// --matcher patches or descriptors, or the tracker's --match-window, ask for one of them (the
// one `tracker` and `image_set` describe).
std::vector<MatcherAttempt> ResolveMatchers(const ReconstructionRunOptions& options,
                                            const RunInputs& inputs);

// Opens the frames and resolves everything above. Throws comic::Error for unreadable or
// inconsistent input (frames, ground truth, calibration, regions), naming the file.
RunInputs ResolveRunInputs(const ReconstructionRunOptions& options);

// The region label of an observation, from the per-frame labels of `inputs` (none without
// regions).
RegionLabelFn RegionLabelsOf(const RunInputs& inputs);

}  // namespace comic::sfm
