#include "sfm/run/run_messages.h"

#include <iomanip>
#include <sstream>

#include "frontend/matching/pairing.h"
#include "io/core/file_utils.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

namespace {

std::string WithoutFinalNewline(std::string text) {
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

}  // namespace

namespace {

// How the frames are matched, as the run will try it.
std::string MatchersText(const RunInputs& inputs) {
  if (inputs.matchers.size() > 1) {
    return ", by the patch tracker (every pair verified), then by SIFT descriptors too if frames "
           "are left out";
  }
  if (!inputs.matchers.empty() && inputs.matchers[0].image_set) return ", by SIFT descriptors";
  return "";
}

}  // namespace

std::vector<std::string> RunInputsLines(const RunInputs& inputs, const std::string& program) {
  std::ostringstream frames;
  frames << program << ": " << inputs.sequence->NumFrames() << " frames "
         << inputs.sequence->FrameSize().width << "x" << inputs.sequence->FrameSize().height;
  if (inputs.at_working_size) {
    frames << " (working size; stored " << inputs.sequence->SourceFrameSize().width << "x"
           << inputs.sequence->SourceFrameSize().height << ", the models are written at it)";
  }
  frames << ", camera " << inputs.camera.camera.Describe() << " (" << inputs.camera.source << ")";
  if (inputs.ground_truth) {
    frames << ", ground truth for " << inputs.ground_truth->num_matched << " frames";
  }
  std::ostringstream matching;
  matching << program << ": matching " << frontend::PairingName(inputs.pairing.chosen) << " ("
           << (inputs.pairing.requested.mode == frontend::PairingMode::kAuto ? "auto: " : "")
           << inputs.pairing.reason << ")" << MatchersText(inputs);
  return {frames.str(), matching.str()};
}

std::string FrameRegisteredLine(const std::string& detector, const MapperProgress& p) {
  std::ostringstream line;
  line << "[" << detector << "] "
       << (p.attempt > 0 ? "model " + std::to_string(p.attempt + 1) + ": " : "") << "registered "
       << p.frame_name << (p.initial_pair ? " (initial pair)" : "") << ": " << p.num_registered
       << "/" << p.num_frames << " frames, " << p.num_points3D << " points";
  if (p.merged) {
    line << " (merged from an earlier model)";
  } else if (!p.initial_pair) {
    line << ", " << p.num_pose_inliers << " PnP inliers";
  }
  return line.str();
}

std::string AdjustmentProgressLine(const std::string& detector,
                                   const BundleAdjustmentProgress& progress) {
  std::ostringstream line;
  line << "[" << detector << "] bundle adjustment of " << progress.num_variable_images
       << " frames, " << progress.num_points << " points: iteration " << progress.iteration
       << " of " << progress.max_num_iterations << ", " << std::fixed << std::setprecision(1)
       << progress.elapsed_s << " s";
  return line.str();
}

std::string DetectorSummaryLine(const DetectorRun& run) {
  const SfmRunReport& report = run.report;
  std::ostringstream line;
  // Interpolated poses are guesses: not in the count, not in the models (issue 47).
  line << "[" << report.detector << "] " << report.status << ": " << report.stats.num_registered
       << "/" << report.num_frames << " frames registered";
  if (!report.rotation_only_frames.empty()) {
    line << " (" << report.rotation_only_frames.size() << " by rotation only)";
  }
  if (!report.interpolated_frames.empty()) {
    line << ", " << report.interpolated_frames.size()
         << " more interpolated (not registered, report.json only)";
  }
  if (report.models.size() > 1) {
    if (report.self_check.passed_over_model_frames > 0) {
      line << " in the first of " << report.models.size() << " models (a model of "
           << report.self_check.passed_over_model_frames
           << " frames came second: " << report.self_check.passed_over_pairs_disagreeing
           << " of its own frame pairs contradict it; ";
    } else {
      line << " in the largest of " << report.models.size() << " models (";
    }
    for (size_t m = 1; m < report.models.size(); ++m) {
      line << (m > 1 ? ", " : "") << report.models[m].num_registered;
    }
    line << " frames in the others)";
  }
  line << ", " << report.stats.all.num_points << " points, mean track length "
       << report.stats.all.mean_track_length << ", mean reprojection error "
       << report.stats.all.mean_reprojection_error_px << " px";
  if (report.trajectory) {
    line << ", ATE " << report.trajectory->ate_rmse << " ("
         << 100.0 * report.trajectory->ate_fraction_of_path << " % of "
         << report.trajectory->path_length << "), rotation error "
         << report.trajectory->mean_rotation_error_deg << " deg";
  }
  line << ", " << report.wall_time_s << " s";
  if (report.self_check.suspect) line << "; suspect: " << report.self_check.reason;
  const IncrementalReconstruction& mapping = run.run.mapping;
  if (mapping.reconstruction.NumRegisteredImages() > 0 &&
      !mapping.reconstruction.cameras().empty()) {
    // In the input's pixels, as the models are written.
    const Camera& camera = mapping.reconstruction.cameras().begin()->second;
    line << "; camera "
         << ResizedCamera(camera, run.run.input_size.width, run.run.input_size.height).Describe()
         << (mapping.intrinsics_refined ? " (refined)" : "");
    if (!report.intrinsics_rejection.empty()) {
      line << " (held at the prior: " << report.intrinsics_rejection << ")";
    }
    if (mapping.focal_assessed && !mapping.focal_observability.observable) {
      line << ", focal unobservable (optical axes within "
           << mapping.focal_observability.max_viewing_angle_deg << " deg): prior kept";
    }
  }
  // The frames the largest model could not take, in ranges with the check that failed (e.g.
  // "40-47 registration/visible_points"; report.json words each).
  if (report.stats.num_registered > 0 && !report.unregistered_ranges.empty()) {
    line << "; unregistered frames: " << DescribeUnregisteredRanges(report.unregistered_ranges);
  }
  // Last, so that the line a user reads first after a run says where to look next.
  if (!run.page_path.empty()) line << "; page: " << run.page_path;
  return line.str();
}

std::vector<std::string> RunOutcomeLines(const ReconstructionRunResult& result,
                                         const std::string& output, const std::string& program,
                                         bool quiet) {
  std::vector<std::string> lines;
  if (!result.frames_folder.empty() && !quiet) {
    lines.push_back(program + ": " + std::to_string(result.inputs.sequence->NumFrames()) +
                    " frames as PNG in " + result.frames_folder + " (COLMAP's --image_path)");
  }
  if (result.colmap_database) {
    const ColmapDatabaseOutput& database = *result.colmap_database;
    std::ostringstream line;
    line << "wrote " << database.path << " (" << database.summary.num_images << " images, "
         << database.summary.num_verified_pairs << " of " << database.summary.num_matched_pairs
         << " pairs verified); run COLMAP on it with:\n  " << database.mapper_command;
    lines.push_back(line.str());
  }
  if (result.colmap_pipeline) {
    const ColmapPipelineOutput& pipeline = *result.colmap_pipeline;
    std::string line = pipeline.table_markdown + "COLMAP ran (log: " + pipeline.log_path + "):";
    for (const std::string& command : pipeline.commands) line += "\n  " + command;
    lines.push_back(line);
  }
  if (result.colmap_comparison) {
    const ColmapComparisonOutput& comparison = *result.colmap_comparison;
    lines.push_back(comparison.table_markdown + "COLMAP ran: " + comparison.mapper_command +
                    "\n(log: " + comparison.log_path + ")");
  }
  // What a failed run found, on stdout even when quiet: the error line stays short.
  if (!result.success() && result.runs.front().keeps_tracks && !output.empty()) {
    const DetectorRun& run = result.runs.front();
    std::string line = program +
                       ": no model; what was found: " + io::JoinPaths(output, "tracks.db") +
                       " (the tracks, a COLMAP database)";
    if (run.rotation_only && run.rotation_only->num_registered >= 2) {
      line += ", " + io::JoinPaths(output, "rotation_only/") + " (a rotation-only camera path of " +
              std::to_string(run.rotation_only->num_registered) + " frames)";
    }
    lines.push_back(line);
  }
  if (result.comparison) {
    lines.push_back(WithoutFinalNewline(result.comparison->ToMarkdown()));
    // The table is the last thing printed: the comparison's page is named after it.
    if (!output.empty()) {
      lines.push_back(program + ": page: " + io::JoinPaths(output, "report.html") +
                      " (each detector's in its folder)");
    }
  }
  return lines;
}

}  // namespace comic::sfm
