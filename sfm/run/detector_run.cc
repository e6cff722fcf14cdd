#include "sfm/run/detector_run.h"

#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "frontend/detector_factory.h"
#include "frontend/matching/pairing.h"
#include "io/core/error.h"
#include "sfm/evaluation/reconstruction_stats.h"
#include "sfm/model_agreement.h"
#include "sfm/run/run_outputs.h"
#include "sfm/run/run_report.h"
#include "sfm/run/tracker_settings.h"

namespace comic::sfm {

namespace {

frontend::DetectorOptions RunDetectorOptions(const std::string& name,
                                             const ReconstructionRunOptions& options) {
  frontend::DetectorOptions detector_options = options.detector_options;
  detector_options.name = name;
  detector_options.comic.num_threads = options.threads;
  detector_options.comic_paper.num_threads = options.threads;
  return detector_options;
}

// Detection and tracking (or the tracks of --cache), then incremental mapping, with progress.
SequenceReconstruction Reconstruct(const frontend::DetectorOptions& detector_options,
                                   const frontend::Detector& detector,
                                   const SequenceReconstructionOptions& sfm_options,
                                   const ReconstructionRunOptions& options, const RunInputs& inputs,
                                   const RunCallbacks& callbacks, TrackCacheUse* cache,
                                   std::vector<int>* pose_inliers) {
  const std::string& name = detector_options.name;
  const std::function<void()> tracking_started = [&] {
    if (callbacks.stage_started) callbacks.stage_started(RunStage::kTracking, name);
  };
  SequenceTracking tracking =
      TrackFramesThroughCache(options.cache, detector_options, detector, *inputs.sequence,
                              sfm_options, tracking_started, callbacks.frame_done, cache);
  if (!cache->warning.empty() && callbacks.warning) callbacks.warning(cache->warning);
  if (cache->from_cache && callbacks.stage_started) {
    callbacks.stage_started(RunStage::kTracksFromCache, name);
  }
  // The inliers are kept for the page's per-frame diagnostics: the models do not hold them.
  pose_inliers->assign(inputs.sequence->NumFrames(), -1);
  const MapperProgressCallback registered = [&](const MapperProgress& progress) {
    const bool by_pnp = !progress.initial_pair && !progress.merged;
    if (by_pnp && progress.frame >= 0 && progress.frame < static_cast<int>(pose_inliers->size())) {
      (*pose_inliers)[progress.frame] = progress.num_pose_inliers;
    }
    if (callbacks.frame_registered) callbacks.frame_registered(name, progress);
  };
  return ReconstructFromTracks(*inputs.sequence, detector, inputs.camera.camera, sfm_options,
                               std::move(tracking), registered);
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

// One run of `detector` with the given descriptor matching (none: the patch tracker), to its
// diagnosis; the report's JSON is made by the caller.
DetectorRun RunDetectorWith(const std::string& detector, const ReconstructionRunOptions& options,
                            const RunInputs& inputs, const frontend::TrackerOptions& tracker,
                            const std::optional<frontend::ImageSetMatchingOptions>& image_set,
                            const RunCallbacks& callbacks) {
  const frontend::DetectorOptions detector_options = RunDetectorOptions(detector, options);
  const std::unique_ptr<frontend::Detector> made = frontend::MakeDetector(detector_options);
  SequenceReconstructionOptions sfm_options =
      MakeSequenceReconstructionOptions(options, tracker, inputs.camera.refine_intrinsics,
                                        image_set, frontend::IsVideo(inputs.pairing));
  sfm_options.feature_masks = inputs.feature_masks;
  if (callbacks.adjustment_progress) {
    sfm_options.mapper.global_ba.progress = [&](const BundleAdjustmentProgress& progress) {
      callbacks.adjustment_progress(detector, progress);
    };
  }
  DetectorRun result;
  result.detector = detector;
  result.matcher = image_set ? "descriptors" : "patches";
  result.verify_min_gap = tracker.verify_min_gap;
  result.run = Reconstruct(detector_options, *made, sfm_options, options, inputs, callbacks,
                           &result.track_cache, &result.pose_inliers);
  Evaluate(inputs, &result);
  result.diagnosis =
      DiagnoseReconstruction(result.run.mapping, sfm_options.mapper, inputs.sequence->FrameNames());
  RecoverWhatWasFound(inputs, &result);
  return result;
}

// A success with every frame in its largest model: nothing left for another matcher to find.
bool EveryFrameInOneModel(const DetectorRun& run, const RunInputs& inputs) {
  return run.run.mapping.status == ReconstructionStatus::kSuccess &&
         run.run.mapping.registered_frames.size() == inputs.sequence->NumFrames();
}

// A success first (95 % of the frames in one model that passes its self-check), then more
// frames in the largest model: neither of two failed runs is right, both say why, and a suspect
// model of most frames shows more than a partial one of a few (a shaky, blurred clip: the
// patches keep a few frames); on equal frames partial before suspect before none.
bool Better(const DetectorRun& a, const DetectorRun& b) {
  const auto rank = [](const DetectorRun& run) {
    switch (run.run.mapping.status) {
      case ReconstructionStatus::kSuccess:
        return 3;
      case ReconstructionStatus::kPartial:
        return 2;
      case ReconstructionStatus::kSuspect:
        return 1;
      default:
        return 0;
    }
  };
  const bool a_success = rank(a) == 3, b_success = rank(b) == 3;
  if (a_success != b_success) return a_success;
  const size_t a_frames = a.run.mapping.registered_frames.size();
  const size_t b_frames = b.run.mapping.registered_frames.size();
  if (a_frames != b_frames) return a_frames > b_frames;
  return rank(a) > rank(b);
}

nlohmann::json AttemptJson(const DetectorRun& run) {
  return {{"matcher", run.matcher},
          {"status", ReconstructionStatusName(run.run.mapping.status)},
          {"registered_frames", run.run.mapping.registered_frames.size()}};
}

// Two matchers' models of one clip that each pass as a success must turn their cameras alike on
// the frames both register: where they differ, at least one of them is wrong, and without
// ground truth the run cannot say which, so the kept model is not called a success (the
// self-check's reason says why). A model that failed on its own (partial, suspect) is not
// compared: it may be wrong where the kept one is right (the patch tracker's partial model of
// a long ordered set, whole rings turned the wrong way).
//
// The main test is from frame to frame (model_agreement.h): a model that turns its cameras too
// far between nearby frames differs from a right one by degrees within ten frames, while two
// right models drift apart by hundredths of a degree per frame. The absolute bound catches a
// slow bend that is large in the end; it is looser because two right models of a long clip also
// drift apart, by degrees over hundreds of frames.
constexpr int kMinCommonFramesCompared = 5;
constexpr int kNeighbourIdsCompared = 10;
constexpr double kMaxMedianRelativeRotationDifferenceDeg = 1.0;
constexpr double kMaxMedianRotationDifferenceDeg = 5.0;

// Compares the kept success with another matcher's success; adds the comparison to that
// attempt's JSON and makes the kept run suspect when the two disagree.
void CompareWithOtherMatcher(const RunInputs& inputs, const DetectorRun& other,
                             nlohmann::json* other_json, DetectorRun* kept) {
  IncrementalReconstruction& mapping = kept->run.mapping;
  if (mapping.status != ReconstructionStatus::kSuccess ||
      other.run.mapping.status != ReconstructionStatus::kSuccess) {
    return;
  }
  const ModelAgreement agreement = CompareModelRotations(
      mapping.reconstruction, other.run.mapping.reconstruction, kNeighbourIdsCompared);
  if (agreement.common_frames < kMinCommonFramesCompared) return;
  (*other_json)["common_frames_with_kept"] = agreement.common_frames;
  (*other_json)["median_rotation_difference_to_kept_deg"] =
      agreement.median_rotation_difference_deg;
  (*other_json)["median_relative_rotation_difference_to_kept_deg"] =
      agreement.median_relative_rotation_difference_deg;
  const bool turns_apart_between_neighbours =
      agreement.median_relative_rotation_difference_deg > kMaxMedianRelativeRotationDifferenceDeg;
  const bool turned_apart =
      agreement.median_rotation_difference_deg > kMaxMedianRotationDifferenceDeg;
  if (!turns_apart_between_neighbours && !turned_apart) return;
  std::ostringstream reason;
  reason.setf(std::ios::fixed);
  reason.precision(1);
  reason << "the " << other.matcher << " matcher's model turns the cameras of the "
         << agreement.common_frames << " frames both register "
         << agreement.median_rotation_difference_deg << " deg away from this one's (median; "
         << agreement.max_rotation_difference_deg << " at most; "
         << agreement.median_relative_rotation_difference_deg << " deg between frames up to "
         << kNeighbourIdsCompared << " apart)";
  ModelSelfCheck& check = mapping.self_check;
  check.reason = reason.str();  // a success: its own check found nothing
  check.suspect = true;
  mapping.status = ReconstructionStatus::kSuspect;
  Evaluate(inputs, kept);
}

}  // namespace

DetectorRun RunDetector(const std::string& detector, const ReconstructionRunOptions& options,
                        const RunInputs& inputs, bool writes_outputs,
                        const RunCallbacks& callbacks) {
  const std::vector<MatcherAttempt>& attempts = inputs.matchers;
  COMIC_CHECK(!attempts.empty(), kInvalidArgument, "run: no matcher resolved");
  DetectorRun result = RunDetectorWith(detector, options, inputs, attempts[0].tracker,
                                       attempts[0].image_set, callbacks);
  nlohmann::json tried = nlohmann::json::array({AttemptJson(result)});
  std::optional<DetectorRun> other;  // the last model not kept, when a second matcher ran
  size_t kept_index = 0, other_index = 0;
  for (size_t a = 1; a < attempts.size(); ++a) {
    if (EveryFrameInOneModel(result, inputs)) break;
    if (callbacks.note) {
      callbacks.note("[" + detector + "] the " + result.matcher + " matcher's model is " +
                     ReconstructionStatusName(result.run.mapping.status) + " (" +
                     std::to_string(result.run.mapping.registered_frames.size()) + "/" +
                     std::to_string(inputs.sequence->NumFrames()) +
                     " frames): matching by descriptors too, the better model is kept");
    }
    DetectorRun next = RunDetectorWith(detector, options, inputs, attempts[a].tracker,
                                       attempts[a].image_set, callbacks);
    tried.push_back(AttemptJson(next));
    if (Better(next, result)) {
      std::swap(next, result);
      other_index = kept_index;
      kept_index = a;
    } else {
      other_index = a;
    }
    other = std::move(next);
  }
  if (other) CompareWithOtherMatcher(inputs, *other, &tried[other_index], &result);
  result.matcher_attempts = std::move(tried);
  result.report_json = DetectorReportJson(result, options, inputs, writes_outputs);
  if (writes_outputs) result.page_path = DetectorPagePath(options, detector);
  if (callbacks.detector_finished) callbacks.detector_finished(result);
  return result;
}

}  // namespace comic::sfm
