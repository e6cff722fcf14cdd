// One detector's run on the resolved inputs (run_inputs.h): detection and tracking, incremental
// mapping, the evaluation against the ground truth, the diagnosis of a failure and what a failed
// run still recovers (the tracks; a rotation-only camera path when the camera only turned), and
// report.json's content. Writes nothing: run_outputs.h writes a DetectorRun.
#pragma once

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sfm/evaluation/sfm_report.h"
#include "sfm/reconstruction_diagnosis.h"
#include "sfm/rotation_only_path.h"
#include "sfm/run/run_inputs.h"
#include "sfm/run/run_options.h"
#include "sfm/run/track_cache.h"
#include "sfm/sequence_reconstruction.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {

struct DetectorRun;

// The stages of a run that go frame by frame, and kTracksFromCache: the tracks were read from
// --cache instead (no frame_done follows; nothing was detected).
enum class RunStage { kTracking, kWritingFrames, kTracksFromCache };

// Progress of a run, for a front door to show (every member may be empty). Called on the thread
// that called the run.
struct RunCallbacks {
  // The inputs are resolved (frames, camera and its source, ground truth, pairing); nothing heavy
  // has run yet.
  std::function<void(const RunInputs&)> inputs_resolved;
  // A stage that goes frame by frame starts: `detector`'s detection and tracking, or writing the
  // video's frames (detector empty). frame_done(done, total) follows after each frame.
  std::function<void(RunStage stage, const std::string& detector)> stage_started;
  std::function<void(size_t done, size_t total)> frame_done;
  // The mapper registered a frame.
  std::function<void(const std::string& detector, const MapperProgress&)> frame_registered;
  // A global bundle adjustment has run more than a second: once per iteration from then on.
  std::function<void(const std::string& detector, const BundleAdjustmentProgress&)>
      adjustment_progress;
  // Something the run worked around, in one line (a --cache file that could not be read, tracked
  // again and replaced).
  std::function<void(const std::string& message)> warning;
  // A choice the run made as it went, in one line (--matcher auto matching by descriptors too).
  std::function<void(const std::string& message)> note;
  // A detector's run is complete (its outputs not yet written).
  std::function<void(const DetectorRun&)> detector_finished;
};

struct DetectorRun {
  std::string detector;
  // "patches" or "descriptors": what matched the frames of this model; and every matcher tried
  // (--matcher auto tries the patch tracker first and descriptors when it gives no success), each
  // {matcher, status, registered_frames}, in the order tried.
  std::string matcher;
  nlohmann::json matcher_attempts;
  // The patch tracker's --verify-min-gap as this model was matched (auto verifies every pair of
  // a video).
  int verify_min_gap = 0;
  SequenceReconstruction run;
  // Per frame: the PnP inliers of its last registration by PnP, as the mapper reported it; -1
  // for a frame never so registered (the initial pair, frames merged from another model, frames
  // posed without PnP). Empty when not recorded (a run built by hand).
  std::vector<int> pose_inliers;
  TrackCacheUse track_cache;  // --cache: the file, and whether the tracks came from it
  SfmRunReport report;
  std::optional<TrajectoryEvaluation> evaluation;  // with ground truth
  ReconstructionDiagnosis diagnosis;               // failed = false for a model
  // No model, but the tracks are kept (written as tracks.db, a COLMAP database).
  bool keeps_tracks = false;
  // keeps_tracks and the camera only turned: its rotations (rotation_only/ when >= 2 frames).
  std::optional<RotationOnlyPath> rotation_only;
  // report.json as written (without an output folder: without "outputs").
  nlohmann::json report_json;
  // Where its report.html will be (DetectorPagePath; empty without --output).
  std::string page_path;

  // A model (status success or partial: HasModel).
  bool success() const { return HasModel(run.mapping.status); }
  // The largest model holds at least `fraction` of the frames (frames with interpolated poses not
  // counted): --min-registered.
  bool RegistersAtLeast(double fraction) const {
    return success() && report.registered_fraction >= fraction;
  }
};

// Runs `detector` on `inputs` with `options`; `writes_outputs` says whether the outputs will be
// written (report.json then lists them). Throws comic::Error for invalid input; a reconstruction
// that fails comes back with its diagnosis.
DetectorRun RunDetector(const std::string& detector, const ReconstructionRunOptions& options,
                        const RunInputs& inputs, bool writes_outputs,
                        const RunCallbacks& callbacks = {});

}  // namespace comic::sfm
