// Our incremental mapper and COLMAP's, side by side on the same feature tracks, to hold our SfM to
// account: the tracks are exported to a COLMAP database (colmap_export.h), `colmap mapper` runs on
// it with the options the sequence needs (colmap_runner.h), and the largest model it writes is
// measured like ours: registered frames, 3-D points, mean track length and mean reprojection
// error as `colmap model_analyzer` defines them (for our model computed here the same way), and
// against ground truth ATE and rotation error with the same code (trajectory_evaluation.h).
// A third row shows our model read back through COLMAP: written as a text model, converted by
// `colmap model_converter` and measured by `colmap model_analyzer`, to show COLMAP reads what we
// write.
//
//   const ColmapComparison comparison = CompareWithColmap(
//       tracks, camera, /*intrinsics_known=*/true, ground_truth, "frames/", "out/colmap", {});
//   io::WriteFileAtomically("out/colmap/comparison.md", comparison.Table().ToMarkdown());
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "frontend/matching/track.h"
#include "io/report/report_table.h"
#include "sfm/camera.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/colmap/colmap_runner.h"
#include "sfm/incremental_pipeline.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

struct ColmapComparisonOptions {
  // Our mapper (used when no reconstruction of ours is passed in).
  IncrementalPipelineOptions ours;
  // The database COLMAP reconstructs from (pair window, two-view verification, threads).
  ColmapExportOptions export_options;
  // --Mapper.num_threads of COLMAP's mapper (-1: every core).
  int colmap_threads = -1;
  // The COLMAP program (a name looked up on PATH, or a path).
  std::string colmap_executable = "colmap";

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// One method's row of the comparison.
struct ColmapComparisonRow {
  std::string method;
  int num_frames = 0;
  int num_registered = 0;
  int64_t num_points3D = 0;
  double mean_track_length = 0.0;
  // As COLMAP defines it (model_analyzer): the mean over 3-D points of each point's mean
  // reprojection error, pixels.
  double mean_reprojection_error_px = 0.0;
  // Against ground truth (when given and at least 3 registered frames have it).
  std::optional<double> ate_rmse;              // ground-truth units (KITTI: metres)
  std::optional<double> ate_fraction_of_path;  // ate_rmse / path length
  std::optional<double> rotation_error_deg;    // mean
  // ATE RMSE over the frames both mappers registered (ours and COLMAP's rows; the Sim(3) fitted
  // on those frames alone), so that a model that stopped short is compared on what it has, and
  // how many frames that is.
  std::optional<double> common_ate_rmse;
  int num_common_frames = 0;
  std::optional<double> wall_time_s;  // the mapper alone (not tracking or export)
  // Of wall_time_s: local and global bundle adjustment (ours: measured; COLMAP's: the sum of the
  // solver times its log reports, when it reports them).
  std::optional<double> local_ba_time_s;
  std::optional<double> global_ba_time_s;
  // CPU time of the mapper (ours: the process during mapping; COLMAP's: the child process, user
  // and system), all threads: robust to other jobs on the machine, unlike the wall time.
  std::optional<double> cpu_time_s;
};

struct ColmapComparison {
  // "comic-sfm", "COLMAP 3.8 mapper", "comic-sfm read by COLMAP" (the last two only when COLMAP
  // produced them).
  std::vector<ColmapComparisonRow> rows;
  ColmapExportSummary export_summary;
  double export_time_s = 0.0;                    // writing and verifying the database
  std::string colmap_mapper_command;             // exactly what ran (paste-able)
  std::optional<std::string> colmap_model_path;  // the largest model, if any
  std::string log_path;                          // every COLMAP run's output

  // One table: method, registered frames, 3-D points, mean track length, mean reprojection
  // error, ATE RMSE, ATE as % of the path, rotation error, wall time, and of it local and global
  // bundle adjustment, CPU time, then the frames both registered and the ATE over them.
  io::ReportTable Table() const;
};

// Runs the comparison in `work_folder` (created if needed; one holding a previous comparison's
// database or models is refused with comic::Error(kIo)): database.db (the export), sparse/<n>
// (COLMAP's models), sparse_text (the largest as text), ours_text (our model), ours_bin (converted
// by COLMAP), ours_from_colmap_text (and back), colmap.log (every COLMAP run). `camera` is what our
// mapper uses; it is exported as known intrinsics when `intrinsics_known`, else COLMAP gets its own
// guess. `ground_truth` holds a cam_from_world per frame (std::nullopt where unknown) or is empty.
// `image_path` is COLMAP's --image_path, holding the frames under their names
// (options.export_options.image_name_prefix + frame name). `ours` is our reconstruction of these
// tracks if already computed (its wall_time_s is reported), else our mapper runs here. Throws
// comic::Error(kExternal) if a COLMAP program fails; a COLMAP mapper that finds no initial pair
// gives a row with 0 registered frames.
ColmapComparison CompareWithColmap(const frontend::FeatureTracks& tracks, const Camera& camera,
                                   bool intrinsics_known,
                                   const std::vector<std::optional<Rigid3d>>& ground_truth,
                                   const std::string& image_path, const std::string& work_folder,
                                   const ColmapComparisonOptions& options,
                                   const IncrementalReconstruction* ours = nullptr);

}  // namespace comic::sfm
