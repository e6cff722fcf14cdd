#include "sfm/run/detector_run.h"

#include <memory>

#include "frontend/detector_factory.h"
#include "sfm/evaluation/reconstruction_stats.h"
#include "sfm/run/run_report.h"

namespace comic::sfm {

namespace {

std::unique_ptr<frontend::Detector> MakeRunDetector(const std::string& name,
                                                    const ReconstructionRunOptions& options) {
  frontend::DetectorOptions detector_options = options.detector_options;
  detector_options.name = name;
  detector_options.comic.num_threads = options.threads;
  detector_options.comic_paper.num_threads = options.threads;
  return frontend::MakeDetector(detector_options);
}

// Detection, tracking and incremental mapping, with progress.
SequenceReconstruction Reconstruct(const std::string& name, const frontend::Detector& detector,
                                   const SequenceReconstructionOptions& sfm_options,
                                   const RunInputs& inputs, const RunCallbacks& callbacks) {
  if (callbacks.stage_started) callbacks.stage_started(RunStage::kTracking, name);
  MapperProgressCallback registered;
  if (callbacks.frame_registered) {
    registered = [&](const MapperProgress& progress) {
      callbacks.frame_registered(name, progress);
    };
  }
  return ReconstructSequence(*inputs.sequence, detector, inputs.camera.camera, sfm_options,
                             callbacks.frame_done, registered);
}

// The report's numbers: statistics (with regions), the trajectory against the ground truth.
void Evaluate(const RunInputs& inputs, DetectorRun* result) {
  const Reconstruction& reconstruction = result->run.mapping.reconstruction;
  const ReconstructionStats stats =
      ComputeReconstructionStats(reconstruction, RegionLabelsOf(inputs));
  if (inputs.ground_truth) {
    result->evaluation =
        EvaluateTrajectory(RegisteredPosesByName(reconstruction, inputs.sequence->FrameNames()),
                           inputs.ground_truth->cams_from_world);
  }
  result->report = MakeRunReport(result->run, stats, result->evaluation);
}

// A failed run keeps what it found (never a silent nothing): the tracks, and when the
// camera only turned, its rotations (sfm/rotation_only_path.h).
void RecoverWhatWasFound(const RunInputs& inputs, DetectorRun* result) {
  result->keeps_tracks =
      !result->success() && inputs.sequence->NumFrames() >= 2 && !result->run.tracks.tracks.empty();
  if (result->keeps_tracks && result->diagnosis.rotation_only) {
    result->rotation_only = EstimateRotationOnlyPath(result->run.tracks, inputs.camera.camera);
  }
}

}  // namespace

DetectorRun RunDetector(const std::string& detector, const ReconstructionRunOptions& options,
                        const RunInputs& inputs, bool writes_outputs,
                        const RunCallbacks& callbacks) {
  const std::unique_ptr<frontend::Detector> made = MakeRunDetector(detector, options);
  SequenceReconstructionOptions sfm_options = MakeSequenceReconstructionOptions(
      options, inputs.tracker, inputs.camera.refine_intrinsics, inputs.image_set);
  if (callbacks.adjustment_progress) {
    sfm_options.mapper.global_ba.progress = [&](const BundleAdjustmentProgress& progress) {
      callbacks.adjustment_progress(detector, progress);
    };
  }
  DetectorRun result;
  result.detector = detector;
  result.run = Reconstruct(detector, *made, sfm_options, inputs, callbacks);
  Evaluate(inputs, &result);
  result.diagnosis =
      DiagnoseReconstruction(result.run.mapping, sfm_options.mapper, inputs.sequence->FrameNames());
  RecoverWhatWasFound(inputs, &result);
  result.report_json = DetectorReportJson(result, options, inputs, writes_outputs);
  if (callbacks.detector_finished) callbacks.detector_finished(result);
  return result;
}

}  // namespace comic::sfm
