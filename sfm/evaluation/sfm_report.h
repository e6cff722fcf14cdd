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
#include "sfm/sequence_reconstruction.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {

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
  // Image sets matched by descriptors: pairs, matches and the CPU time of each stage
  // (report.json "image_set_matching").
  std::optional<frontend::ImageSetMatchingSummary> image_set_matching;
};

SfmRunReport MakeRunReport(const SequenceReconstruction& run, const ReconstructionStats& stats,
                           const std::optional<TrajectoryEvaluation>& trajectory);

// Every number of the report (the table's and more: per-frame errors, timings, the alignment).
nlohmann::json RunReportToJson(const SfmRunReport& report);

// One row per run: detector, status, registered / frames, points, mean track length, mean
// reprojection error, ATE (m and % of the path), mean rotation error, wall time; boundary and
// interior points and their errors when any report has region statistics. Missing numbers
// (no ground truth, failed run) are empty cells.
io::ReportTable MakeComparisonTable(const std::vector<SfmRunReport>& reports);

}  // namespace comic::sfm
