// COLMAP's own pipeline on the same frames, beside ours (issue 30, "side by side with COLMAP"):
// `colmap feature_extractor` (SIFT), `sequential_matcher` for a video or `exhaustive_matcher` for
// an image set, and `colmap mapper`, each with COLMAP's defaults except the thread count and no
// GPU (the table ran them on one thread). Every model COLMAP writes is read back:
// registered frames of the largest and of all models together, and, with ground truth, the ATE of
// the largest (trajectory_evaluation.h, the code our own runs are measured with).
//
//   ColmapPipelineOptions options;            // sequential matching, one thread
//   const ColmapPipelineRun colmap = RunColmapPipeline("frames/", names, "out/colmap_sift",
//                                                      truth, options);
//   io::ReportTable table = ColmapPipelineTable(our_report, colmap);
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/report/report_table.h"
#include "sfm/evaluation/sfm_report.h"
#include "sfm/rigid3d.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {

struct ColmapPipelineOptions {
  // sequential_matcher (a video: each frame with the next ones, COLMAP's default overlap of 10,
  // plus its loop detection off as by default), else exhaustive_matcher (an image set).
  bool sequential = true;
  // --SiftExtraction.num_threads, --SiftMatching.num_threads, --Mapper.num_threads (-1: every
  // core, COLMAP's default).
  int num_threads = 1;
  std::string colmap_executable = "colmap";

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct ColmapPipelineRun {
  int num_frames = 0;
  // Registered frames of every model, largest first, and of all models together (a frame in two
  // models counts once).
  std::vector<int> num_registered_per_model;
  int num_registered_largest = 0;
  int num_registered_all = 0;
  std::optional<std::string> largest_model_path;
  // The largest model against the ground truth (when given and enough frames have it).
  std::optional<TrajectoryEvaluation> trajectory;
  // Wall time of each program and CPU time of all (children, user and system).
  double extraction_time_s = 0.0;
  double matching_time_s = 0.0;
  double mapper_time_s = 0.0;
  double cpu_time_s = 0.0;
  std::vector<std::string> commands;  // exactly what ran (paste-able)
  std::string log_path;
};

// Runs COLMAP on the frames `frame_names` of `image_path` (an --image_list_path, so a --first/
// --last range is honoured) in `work_folder` (database.db, sparse/<k>, image_list.txt,
// colmap.log; a folder holding a previous run is refused with comic::Error(kIo)).
// `ground_truth` holds a cam_from_world per frame (std::nullopt where unknown) or is empty.
// Throws comic::Error(kNotFound) without COLMAP, kExternal when a COLMAP program fails (a mapper
// that finds no initial pair gives a run without models).
ColmapPipelineRun RunColmapPipeline(const std::string& image_path,
                                    const std::vector<std::string>& frame_names,
                                    const std::string& work_folder,
                                    const std::vector<std::optional<Rigid3d>>& ground_truth,
                                    const ColmapPipelineOptions& options);

// Ours and COLMAP's side by side: method, registered frames of the largest model and of all
// models, models, time (ours: the whole run, tracking included; COLMAP's: extraction, matching and
// mapping), ATE RMSE, ATE as % of the path, rotation error; and our status with the unregistered
// ranges.
io::ReportTable ColmapPipelineTable(const SfmRunReport& ours, const ColmapPipelineRun& colmap);

}  // namespace comic::sfm
