#include "sfm/colmap/colmap_comparison.h"

#include <chrono>
#include <filesystem>

#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/colmap/colmap_runner.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Fills the ground-truth columns of `row` from per-frame poses.
void Evaluate(const std::vector<std::optional<Rigid3d>>& estimated,
              const std::vector<std::optional<Rigid3d>>& ground_truth, ColmapComparisonRow* row) {
  if (ground_truth.empty()) return;
  const auto evaluation = EvaluateTrajectory(estimated, ground_truth);
  if (!evaluation) return;
  row->ate_rmse = evaluation->ate_rmse;
  row->ate_fraction_of_path = evaluation->ate_fraction_of_path;
  row->rotation_error_deg = evaluation->mean_rotation_error_deg;
}

// The common_ate_rmse of two rows: each model's ATE over the frames both registered (at least
// 3 with ground truth), the similarity fitted on those frames alone.
void EvaluateOnCommonFrames(const std::vector<std::optional<Rigid3d>>& poses_a,
                            const std::vector<std::optional<Rigid3d>>& poses_b,
                            const std::vector<std::optional<Rigid3d>>& ground_truth,
                            ColmapComparisonRow* row_a, ColmapComparisonRow* row_b) {
  if (ground_truth.empty() || poses_a.size() != ground_truth.size() ||
      poses_b.size() != ground_truth.size()) {
    return;
  }
  std::vector<std::optional<Rigid3d>> common_truth(ground_truth.size());
  int num_common = 0;
  for (size_t i = 0; i < ground_truth.size(); ++i) {
    if (poses_a[i] && poses_b[i] && ground_truth[i]) {
      common_truth[i] = ground_truth[i];
      ++num_common;
    }
  }
  if (num_common < 3) return;
  const auto evaluation_a = EvaluateTrajectory(poses_a, common_truth);
  const auto evaluation_b = EvaluateTrajectory(poses_b, common_truth);
  if (!evaluation_a || !evaluation_b) return;
  row_a->common_ate_rmse = evaluation_a->ate_rmse;
  row_a->num_common_frames = num_common;
  row_b->common_ate_rmse = evaluation_b->ate_rmse;
  row_b->num_common_frames = num_common;
}

// COLMAP's image names of the frames.
std::vector<std::string> ColmapImageNames(const frontend::FeatureTracks& tracks,
                                          const std::string& prefix) {
  std::vector<std::string> names;
  for (const std::string& name : tracks.frame_names) names.push_back(prefix + name);
  return names;
}

// The poses of a COLMAP model (a folder), per frame, matched by image name.
std::vector<std::optional<Rigid3d>> ModelPoses(const std::string& text_model_folder,
                                               const std::vector<std::string>& names) {
  const Reconstruction model = FromColmapTextModel(io::ReadColmapTextModel(text_model_folder),
                                                   /*ignore_distortion=*/true);
  return RegisteredPosesByName(model, names);
}

// COLMAP's "mean reprojection error" (Reconstruction::ComputeMeanReprojectionError, what
// model_analyzer prints): the mean over 3-D points of each point's mean reprojection error.
double MeanPointReprojectionError(const Reconstruction& reconstruction) {
  double sum = 0.0;
  size_t count = 0;
  for (const auto& [id, point] : reconstruction.points3D()) {
    if (point.track.empty()) continue;
    double point_sum = 0.0;
    for (const TrackElement& element : point.track) {
      point_sum += reconstruction.ReprojectionError(element.image_id, element.point2D_idx);
    }
    sum += point_sum / static_cast<double>(point.track.size());
    ++count;
  }
  return count == 0 ? 0.0 : sum / static_cast<double>(count);
}

ColmapComparisonRow RowFromAnalyzer(const std::string& method, const ColmapModelStats& stats,
                                    int num_frames) {
  ColmapComparisonRow row;
  row.method = method;
  row.num_frames = num_frames;
  row.num_registered = static_cast<int>(stats.num_registered_images);
  row.num_points3D = stats.num_points3D;
  row.mean_track_length = stats.mean_track_length;
  row.mean_reprojection_error_px = stats.mean_reprojection_error;
  return row;
}

}  // namespace

void ColmapComparisonOptions::Check() const {
  ours.Check();
  export_options.Check();
  COMIC_CHECK(colmap_threads == -1 || colmap_threads >= 1, kInvalidArgument,
              "COLMAP comparison colmap_threads must be -1 or >= 1, got " << colmap_threads);
  COMIC_CHECK(!colmap_executable.empty(), kInvalidArgument, "COLMAP executable name is empty");
}

io::ReportTable ColmapComparison::Table() const {
  io::ReportTable table({"method", "registered frames", "3-D points", "mean track length",
                         "mean reprojection error (px)", "ATE RMSE", "ATE % of path",
                         "rotation error (deg)", "wall time (s)", "local BA (s)", "global BA (s)",
                         "CPU time (s)", "common frames", "ATE RMSE, common frames"});
  table.SetPrecision("mean track length", 2);
  table.SetPrecision("mean reprojection error (px)", 3);
  table.SetPrecision("ATE RMSE", 3);
  table.SetPrecision("ATE % of path", 2);
  table.SetPrecision("rotation error (deg)", 3);
  table.SetPrecision("wall time (s)", 1);
  table.SetPrecision("local BA (s)", 1);
  table.SetPrecision("global BA (s)", 1);
  table.SetPrecision("CPU time (s)", 1);
  table.SetPrecision("ATE RMSE, common frames", 4);
  const auto optional_cell = [](const std::optional<double>& value,
                                double scale) -> io::ReportTable::Cell {
    if (!value) return std::monostate();
    return *value * scale;
  };
  for (const ColmapComparisonRow& row : rows) {
    table.AddRow({row.method,
                  std::to_string(row.num_registered) + "/" + std::to_string(row.num_frames),
                  row.num_points3D, row.mean_track_length, row.mean_reprojection_error_px,
                  optional_cell(row.ate_rmse, 1.0), optional_cell(row.ate_fraction_of_path, 100.0),
                  optional_cell(row.rotation_error_deg, 1.0), optional_cell(row.wall_time_s, 1.0),
                  optional_cell(row.local_ba_time_s, 1.0), optional_cell(row.global_ba_time_s, 1.0),
                  optional_cell(row.cpu_time_s, 1.0),
                  row.common_ate_rmse ? io::ReportTable::Cell(int64_t{row.num_common_frames})
                                      : io::ReportTable::Cell(std::monostate()),
                  optional_cell(row.common_ate_rmse, 1.0)});
  }
  return table;
}

ColmapComparison CompareWithColmap(const frontend::FeatureTracks& tracks, const Camera& camera,
                                   bool intrinsics_known,
                                   const std::vector<std::optional<Rigid3d>>& ground_truth,
                                   const std::string& image_path, const std::string& work_folder,
                                   const ColmapComparisonOptions& options,
                                   const IncrementalReconstruction* ours) {
  options.Check();
  camera.Check();
  tracks.Check();
  COMIC_CHECK(ground_truth.empty() || ground_truth.size() == tracks.NumFrames(), kInvalidArgument,
              "COLMAP comparison: " << ground_truth.size() << " ground-truth poses for "
                                    << tracks.NumFrames() << " frames");
  COMIC_CHECK(IsColmapAvailable(options.colmap_executable), kNotFound,
              options.colmap_executable
                  << ": COLMAP is not installed (apt-get install colmap) or not on PATH");
  COMIC_CHECK(io::IsDirectory(image_path), kNotFound, image_path << ": no such image folder");
  io::EnsureWritableDirectory(work_folder);
  const auto path = [&](const std::string& name) { return io::JoinPaths(work_folder, name); };
  COMIC_CHECK(!io::PathExists(path("database.db")) && !FindLargestColmapModel(path("sparse")), kIo,
              work_folder << ": holds a previous COLMAP comparison (use an empty folder)");
  const int num_frames = static_cast<int>(tracks.NumFrames());

  ColmapComparison comparison;
  comparison.log_path = path("colmap.log");

  // Ours.
  IncrementalReconstruction computed;
  if (ours == nullptr) {
    computed = ReconstructIncrementally(tracks, camera, options.ours);
    ours = &computed;
  }
  std::vector<std::optional<Rigid3d>> our_poses, colmap_poses;
  ColmapComparisonRow our_row;
  our_row.method = "comic-sfm";
  our_row.num_frames = num_frames;
  our_row.wall_time_s = ours->wall_time_s;
  our_row.local_ba_time_s = ours->local_ba_time_s;
  our_row.global_ba_time_s = ours->global_ba_time_s;
  our_row.cpu_time_s = ours->cpu_time_s;
  if (HasModel(ours->status)) {
    const Reconstruction& reconstruction = ours->reconstruction;
    our_row.num_registered = static_cast<int>(reconstruction.NumRegisteredImages());
    our_row.num_points3D = static_cast<int64_t>(reconstruction.NumPoints3D());
    our_row.mean_track_length = reconstruction.ComputeMeanTrackLength();
    our_row.mean_reprojection_error_px = MeanPointReprojectionError(reconstruction);
    our_poses = RegisteredPosesByName(reconstruction, tracks.frame_names);
    Evaluate(our_poses, ground_truth, &our_row);
  }
  comparison.rows.push_back(our_row);

  // COLMAP's mapper on the same tracks.
  const auto export_start = Clock::now();
  const std::string database = path("database.db");
  comparison.export_summary = ExportTracksToColmapDatabase(
      tracks, intrinsics_known ? std::optional<Camera>(camera) : std::nullopt,
      options.export_options, database, /*overwrite=*/false);
  comparison.export_time_s = SecondsSince(export_start);
  ColmapMapperOptions mapper_options = RecommendedColmapMapperOptions(comparison.export_summary);
  mapper_options.num_threads = options.colmap_threads;
  const std::string sparse = path("sparse");
  std::vector<std::string> command = {options.colmap_executable};
  const auto mapper_args = ColmapMapperArguments(database, image_path, sparse, mapper_options);
  command.insert(command.end(), mapper_args.begin(), mapper_args.end());
  comparison.colmap_mapper_command = ShellCommandLine(command);
  const auto mapper_start = Clock::now();
  const double children_cpu_start = ChildrenCpuSeconds();
  comparison.colmap_model_path = RunColmapMapper(database, image_path, sparse, mapper_options,
                                                 comparison.log_path, options.colmap_executable);
  const double mapper_time = SecondsSince(mapper_start);
  const double mapper_cpu_time = ChildrenCpuSeconds() - children_cpu_start;
  const std::vector<std::string> colmap_names =
      ColmapImageNames(tracks, options.export_options.image_name_prefix);
  ColmapComparisonRow colmap_row;
  colmap_row.method = "COLMAP 3.8 mapper";
  colmap_row.num_frames = num_frames;
  if (comparison.colmap_model_path) {
    colmap_row = RowFromAnalyzer(colmap_row.method,
                                 AnalyzeColmapModel(*comparison.colmap_model_path,
                                                    comparison.log_path, options.colmap_executable),
                                 num_frames);
    ConvertColmapModel(*comparison.colmap_model_path, path("sparse_text"), "TXT",
                       comparison.log_path, options.colmap_executable);
    colmap_poses = ModelPoses(path("sparse_text"), colmap_names);
    Evaluate(colmap_poses, ground_truth, &colmap_row);
  }
  colmap_row.wall_time_s = mapper_time;
  colmap_row.cpu_time_s = mapper_cpu_time;
  if (io::PathExists(comparison.log_path)) {
    const ColmapBundleAdjustmentTimes times =
        ParseColmapBundleAdjustmentTimes(io::ReadFileToString(comparison.log_path));
    if (times.num_local + times.num_global > 0) {
      colmap_row.local_ba_time_s = times.local_s;
      colmap_row.global_ba_time_s = times.global_s;
    }
  }
  EvaluateOnCommonFrames(our_poses, colmap_poses, ground_truth, &comparison.rows[0], &colmap_row);
  comparison.rows.push_back(colmap_row);

  // Our model read back through COLMAP: our text model, converted to binary by COLMAP, measured
  // by COLMAP, converted back to text and evaluated like COLMAP's own.
  if (HasModel(ours->status)) {
    io::WriteColmapTextModel(ToColmapTextModel(ours->reconstruction), path("ours_text"));
    ConvertColmapModel(path("ours_text"), path("ours_bin"), "BIN", comparison.log_path,
                       options.colmap_executable);
    ColmapComparisonRow read_back = RowFromAnalyzer(
        "comic-sfm read by COLMAP",
        AnalyzeColmapModel(path("ours_bin"), comparison.log_path, options.colmap_executable),
        num_frames);
    ConvertColmapModel(path("ours_bin"), path("ours_from_colmap_text"), "TXT", comparison.log_path,
                       options.colmap_executable);
    const std::vector<std::optional<Rigid3d>> read_back_poses =
        ModelPoses(path("ours_from_colmap_text"), tracks.frame_names);
    Evaluate(read_back_poses, ground_truth, &read_back);
    ColmapComparisonRow unused = colmap_row;
    EvaluateOnCommonFrames(read_back_poses, colmap_poses, ground_truth, &read_back, &unused);
    comparison.rows.push_back(read_back);
  }
  return comparison;
}

}  // namespace comic::sfm
