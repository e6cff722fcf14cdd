#include "sfm/colmap/colmap_pipeline.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <set>

#include "io/colmap/colmap_binary_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "sfm/colmap/colmap_runner.h"

namespace comic::sfm {
namespace {

using Clock = std::chrono::steady_clock;

// Runs one COLMAP program, records its command line, returns its wall time.
double Run(const std::vector<std::string>& args, const ColmapPipelineOptions& options,
           ColmapPipelineRun* run) {
  std::vector<std::string> command = {options.colmap_executable};
  command.insert(command.end(), args.begin(), args.end());
  run->commands.push_back(ShellCommandLine(command));
  const auto start = Clock::now();
  RunColmap(args, run->log_path, options.colmap_executable);
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The model folders COLMAP's mapper wrote under `sparse` (numbered sub-folders).
std::vector<std::string> ModelFolders(const std::string& sparse) {
  std::vector<std::string> folders;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(sparse, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && !name.empty() &&
        std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
        io::IsRegularFile(io::JoinPaths(entry.path().string(), "images.bin"))) {
      folders.push_back(entry.path().string());
    }
  }
  std::sort(folders.begin(), folders.end());
  return folders;
}

}  // namespace

void ColmapPipelineOptions::Check() const {
  COMIC_CHECK(num_threads == -1 || num_threads >= 1, kInvalidArgument,
              "COLMAP pipeline num_threads must be -1 or >= 1, got " << num_threads);
  COMIC_CHECK(!colmap_executable.empty(), kInvalidArgument, "COLMAP executable name is empty");
}

ColmapPipelineRun RunColmapPipeline(const std::string& image_path,
                                    const std::vector<std::string>& frame_names,
                                    const std::string& work_folder,
                                    const std::vector<std::optional<Rigid3d>>& ground_truth,
                                    const ColmapPipelineOptions& options) {
  options.Check();
  COMIC_CHECK(ground_truth.empty() || ground_truth.size() == frame_names.size(), kInvalidArgument,
              "COLMAP pipeline: " << ground_truth.size() << " ground-truth poses for "
                                  << frame_names.size() << " frames");
  COMIC_CHECK(IsColmapAvailable(options.colmap_executable), kNotFound,
              options.colmap_executable
                  << ": COLMAP is not installed (apt-get install colmap) or not on PATH");
  COMIC_CHECK(io::IsDirectory(image_path), kNotFound, image_path << ": no such image folder");
  io::EnsureWritableDirectory(work_folder);
  const auto path = [&](const std::string& name) { return io::JoinPaths(work_folder, name); };
  COMIC_CHECK(!io::PathExists(path("database.db")) && !FindLargestColmapModel(path("sparse")), kIo,
              work_folder << ": holds a previous COLMAP run (use an empty folder)");
  ColmapPipelineRun run;
  run.num_frames = static_cast<int>(frame_names.size());
  run.log_path = path("colmap.log");
  std::string list;
  for (const std::string& name : frame_names) list += name + "\n";
  io::WriteFileAtomically(path("image_list.txt"), list);
  io::EnsureWritableDirectory(path("sparse"));
  const std::string threads = std::to_string(options.num_threads);
  const double cpu_start = ChildrenCpuSeconds();
  run.extraction_time_s =
      Run({"feature_extractor", "--database_path", path("database.db"), "--image_path", image_path,
           "--image_list_path", path("image_list.txt"), "--SiftExtraction.use_gpu", "0",
           "--SiftExtraction.num_threads", threads},
          options, &run);
  run.matching_time_s = Run(
      {options.sequential ? "sequential_matcher" : "exhaustive_matcher", "--database_path",
       path("database.db"), "--SiftMatching.use_gpu", "0", "--SiftMatching.num_threads", threads},
      options, &run);
  try {
    run.mapper_time_s =
        Run({"mapper", "--database_path", path("database.db"), "--image_path", image_path,
             "--output_path", path("sparse"), "--Mapper.num_threads", threads},
            options, &run);
  } catch (const Error& e) {
    // COLMAP 3.8 exits with status 1 when it finds no initial pair: a run without models.
    if (e.kind() != ErrorKind::kExternal || FindLargestColmapModel(path("sparse"))) throw;
  }
  run.cpu_time_s = ChildrenCpuSeconds() - cpu_start;

  std::set<std::string> registered_names;
  for (const std::string& folder : ModelFolders(path("sparse"))) {
    const io::ColmapTextModel model = io::ReadColmapBinaryModel(folder);
    run.num_registered_per_model.push_back(static_cast<int>(model.images.size()));
    for (const io::ColmapImage& image : model.images) registered_names.insert(image.name);
  }
  std::sort(run.num_registered_per_model.rbegin(), run.num_registered_per_model.rend());
  run.num_registered_all = static_cast<int>(registered_names.size());
  run.largest_model_path = FindLargestColmapModel(path("sparse"));
  if (run.largest_model_path) {
    run.num_registered_largest = run.num_registered_per_model.front();
    if (!ground_truth.empty()) {
      // The poses alone: COLMAP's tracks may observe one image twice, which a Reconstruction
      // refuses, and the trajectory needs no points.
      std::map<std::string, Rigid3d> by_name;
      for (const io::ColmapImage& image :
           io::ReadColmapBinaryModel(*run.largest_model_path).images) {
        by_name[image.name] =
            Rigid3d(image.cam_from_world_rotation, image.cam_from_world_translation);
      }
      std::vector<std::optional<Rigid3d>> poses(frame_names.size());
      for (size_t i = 0; i < frame_names.size(); ++i) {
        const auto it = by_name.find(frame_names[i]);
        if (it != by_name.end()) poses[i] = it->second;
      }
      run.trajectory = EvaluateTrajectory(poses, ground_truth);
    }
  }
  return run;
}

io::ReportTable ColmapPipelineTable(const SfmRunReport& ours, const ColmapPipelineRun& colmap) {
  io::ReportTable table({"method", "status", "registered (largest model)",
                         "registered (all models)", "models", "time (s)", "ATE RMSE",
                         "ATE % of path", "rotation error (deg)", "unregistered (stage/check)"});
  table.SetPrecision("time (s)", 1);
  table.SetPrecision("ATE RMSE", 4);
  table.SetPrecision("ATE % of path", 3);
  table.SetPrecision("rotation error (deg)", 3);
  const auto fraction = [](int registered, size_t frames) {
    return std::to_string(registered) + "/" + std::to_string(frames);
  };
  const auto trajectory_cells = [](const std::optional<TrajectoryEvaluation>& t) {
    std::vector<io::ReportTable::Cell> cells(3, std::monostate());
    if (t) cells = {t->ate_rmse, 100.0 * t->ate_fraction_of_path, t->mean_rotation_error_deg};
    return cells;
  };
  std::set<int> all_ours;
  for (const SfmModelReport& model : ours.models) {
    all_ours.insert(model.registered_frames.begin(), model.registered_frames.end());
  }
  std::vector<io::ReportTable::Cell> row = {
      "comic-sfm --detector " + ours.detector,
      ours.status,
      fraction(static_cast<int>(ours.stats.num_registered), ours.num_frames),
      fraction(static_cast<int>(all_ours.size()), ours.num_frames),
      static_cast<int64_t>(ours.models.size()),
      ours.wall_time_s};
  for (const auto& cell : trajectory_cells(ours.trajectory)) row.push_back(cell);
  row.push_back(DescribeUnregisteredRanges(ours.unregistered_ranges));
  table.AddRow(std::move(row));
  row = {"COLMAP 3.8 (SIFT, " +
             std::string(colmap.commands.size() > 1 &&
                                 colmap.commands[1].find("sequential") != std::string::npos
                             ? "sequential"
                             : "exhaustive") +
             " matching, mapper)",
         colmap.largest_model_path ? "model" : "no model",
         fraction(colmap.num_registered_largest, colmap.num_frames),
         fraction(colmap.num_registered_all, colmap.num_frames),
         static_cast<int64_t>(colmap.num_registered_per_model.size()),
         colmap.extraction_time_s + colmap.matching_time_s + colmap.mapper_time_s};
  for (const auto& cell : trajectory_cells(colmap.trajectory)) row.push_back(cell);
  row.push_back(std::monostate());
  table.AddRow(std::move(row));
  return table;
}

}  // namespace comic::sfm
