// The numbers of one SfM run, gathered in one place and written the same way everywhere: as JSON
// (report.json) and as a row of the comparison table (Markdown / CSV / JSON via io::ReportTable).
//
//   SfmRunReport report = MakeRunReport(run, stats, evaluation);
//   nlohmann::json json = RunReportToJson(report);
//   io::ReportTable table = MakeComparisonTable({report_a, report_b});
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/report/report_table.h"
#include "sfm/evaluation/reconstruction_stats.h"
#include "sfm/model_self_check.h"
#include "sfm/sequence_reconstruction.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {

// One model of a run (sparse/<index>; 0 is the largest).
struct SfmModelReport {
  int index = 0;
  size_t num_registered = 0;     // frames registered (poses from observations)
  size_t num_rotation_only = 0;  // of those, posed by their rotation against the map
  size_t num_interpolated = 0;   // frames not registered, with a pose interpolated in this model
  size_t num_points = 0;
  int first_frame = -1;  // the first and last registered frames
  int last_frame = -1;
  std::vector<int> registered_frames;
  int initial_frame1 = -1;
  int initial_frame2 = -1;
  int num_merged_models = 0;
};

struct SfmRunReport {
  std::string detector;
  std::string status;  // ReconstructionStatusName
  size_t num_frames = 0;
  size_t num_tracks = 0;  // tracks of two or more observations from the tracker
  double mean_tracker_track_length = 0.0;
  std::vector<int> registered_frames;
  std::vector<int> unregistered_frames;
  int initial_frame1 = -1;
  int initial_frame2 = -1;
  // Every model, the largest first (models[0] is the one `stats` describes).
  std::vector<SfmModelReport> models;
  // Frames of the largest model posed without PnP (sfm/pose_gap_filling.h): registered by their
  // rotation against the map, and not registered but interpolated (a guess; with their poses).
  std::vector<int> rotation_only_frames;
  std::vector<int> interpolated_frames;
  std::vector<Rigid3d> interpolated_poses;
  // The largest model against its own frame pairs (sfm/model_self_check.h).
  ModelSelfCheck self_check;
  // Frames registered in the largest model over all frames (kSuccess at
  // >= success_min_registered_fraction).
  double registered_fraction = 0.0;
  // The frames missing from the largest model, with the stage and check that failed.
  std::vector<UnregisteredRange> unregistered_ranges;
  int num_models_started = 0;
  int num_merges = 0;
  int num_seam_links = 0;
  int num_appearance_links = 0;
  int num_initial_pair_searches = 0;
  double initial_pair_search_cpu_time_s = 0.0;
  std::vector<PlanarPoseChoice> planar_pose_choices;
  int num_seam_matches = 0;
  double seam_matching_cpu_time_s = 0.0;
  // A self-calibrated camera reset to its prior (empty reason: kept or never refined).
  std::string intrinsics_rejection;
  double working_scale = 1.0;  // the mapper's pixels over the frames'
  ReconstructionStats stats;
  std::optional<TrajectoryEvaluation> trajectory;
  double tracking_time_s = 0.0;
  double mapping_time_s = 0.0;
  double wall_time_s = 0.0;
  double local_ba_time_s = 0.0;
  double global_ba_time_s = 0.0;
  // CPU time of the mapper and of its bundle adjustments (process, all threads).
  double mapping_cpu_time_s = 0.0;
  double local_ba_cpu_time_s = 0.0;
  double global_ba_cpu_time_s = 0.0;
  int num_local_ba = 0;
  int num_global_ba = 0;
  // Keyframes (IncrementalPipelineOptions::keyframes_only; report.json "keyframes", null
  // without): the keyframes with the reason each is one, and the frames the largest model
  // registered but could not pose again against its final map.
  bool keyframes_only = false;
  std::vector<int> keyframes;
  std::vector<std::string> keyframe_reasons;
  std::vector<int> non_keyframes_lost;
  // Loop closure (IncrementalPipelineOptions::close_loops; report.json "loop_closure", null
  // without): what the largest model's loop closure found and did.
  std::optional<LoopClosureSummary> loop_closure;
  // Image sets matched by descriptors: pairs, matches and the CPU time of each stage
  // (report.json "image_set_matching").
  std::optional<frontend::ImageSetMatchingSummary> image_set_matching;
};

SfmRunReport MakeRunReport(const SequenceReconstruction& run, const ReconstructionStats& stats,
                           const std::optional<TrajectoryEvaluation>& trajectory);

// "0-24 registration/visible_points; 36 tracking/features": the ranges in one cell or line.
std::string DescribeUnregisteredRanges(const std::vector<UnregisteredRange>& ranges);

// Every number of the report (the table's and more: per-frame errors, timings, the alignment).
nlohmann::json RunReportToJson(const SfmRunReport& report);

// One row per run: detector, status, registered / frames, models, points, mean track length, mean
// reprojection error, ATE (m and % of the path), mean rotation error, wall time, the unregistered
// ranges with their failed check (e.g. "0-24 registration/visible_points"); boundary and
// interior points and their errors when any report has region statistics. Missing numbers
// (no ground truth, failed run) are empty cells.
io::ReportTable MakeComparisonTable(const std::vector<SfmRunReport>& reports);

}  // namespace comic::sfm
