#include "sfm/run/run_outputs.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/datasets/ground_truth_cameras.h"
#include "io/image/image_io.h"
#include "io/report/json_text.h"
#include "io/report/ply.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/colmap/model_set_writer.h"
#include "sfm/run/colmap_outputs.h"
#include "sfm/run/nerfstudio_transforms.h"
#include "sfm/run/run_page.h"
#include "sfm/run/run_report.h"
#include "sfm/run/tum_trajectory.h"
#include "sfm/run/undistorted_output.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

namespace {

const char* const kTextModelFiles[] = {"cameras.txt", "images.txt", "points3D.txt"};

void WriteModel(const DetectorRun& run, const ReconstructionRunOptions& options,
                const std::string& folder) {
  WriteModelSet(run.run.mapping, folder, ModelWriteOptions(run, options));
}

void WritePointCloud(const DetectorRun& run, const ReconstructionRunOptions& options,
                     const std::string& folder) {
  std::vector<io::PlyPoint> cloud;
  for (const auto& [point3D_id, point] : run.run.mapping.reconstruction.points3D()) {
    cloud.push_back({point.xyz, point.color});
  }
  io::WritePly(io::JoinPaths(folder, "points.ply"), cloud, io::ParsePlyFormat(options.ply_format));
}

void WriteTrajectoryPlot(const DetectorRun& run, const ReconstructionRunOptions& options,
                         const RunInputs& inputs, const std::string& folder) {
  io::WriteImageAtomically(
      io::JoinPaths(folder, "trajectory.png"),
      RenderRunPlot(inputs, run.run.mapping.reconstruction, run.evaluation,
                    "comic_sfm --detector " + run.detector + "  " + options.frames));
}

// The absolute path, ".." and the symbolic links of its existing part resolved.
std::filesystem::path ResolvedPath(const std::string& path) {
  std::error_code ec;
  std::filesystem::path resolved =
      std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec);
  return ec ? std::filesystem::absolute(path).lexically_normal() : resolved;
}

// Where each frame's image file is once the run has committed: a folder's own files, a video's
// frames in the folder they are written to (--write-frames, or images/ in --output; without
// either they are not written, and --write-frames puts them where the paths point).
std::string FrameFileAfterCommit(const ReconstructionRunOptions& options, const RunInputs& inputs,
                                 size_t frame) {
  const io::ImageSequence& sequence = *inputs.sequence;
  if (!sequence.IsVideo()) return sequence.FramePath(frame);
  const std::string frames = options.write_frames.empty() || options.write_frames == kFramesInOutput
                                 ? io::JoinPaths(options.output, "images")
                                 : options.write_frames;
  return io::JoinPaths(frames, sequence.FrameNames()[frame]);
}

// transforms.json (nerfstudio) of the largest model: the image paths relative to where the file
// will be after the commit (`folder` is its staging copy), so the output folder can be moved
// with its input beside it.
void WriteNerfstudioTransforms(const DetectorRun& run, const ReconstructionRunOptions& options,
                               const RunInputs& inputs, const std::string& folder) {
  const std::filesystem::path final_folder =
      ResolvedPath(options.compare ? io::JoinPaths(options.output, run.detector) : options.output);
  std::map<std::string, size_t> frame_of_name;
  const std::vector<std::string>& names = inputs.sequence->FrameNames();
  for (size_t i = 0; i < names.size(); ++i) frame_of_name[names[i]] = i;
  const auto file_path = [&](const Image& image) {
    const auto frame = frame_of_name.find(image.name);
    if (frame == frame_of_name.end()) return image.name;
    return ResolvedPath(FrameFileAfterCommit(options, inputs, frame->second))
        .lexically_relative(final_folder)
        .generic_string();
  };
  io::WriteFileAtomically(
      io::JoinPaths(folder, "transforms.json"),
      io::JsonText(NerfstudioTransforms(run.run.mapping.reconstruction, run.run.input_size.width,
                                        run.run.input_size.height, file_path),
                   2));
}

// trajectory_tum.txt: the largest model's camera path for evo and the SLAM tools.
void WriteTumTrajectory(const DetectorRun& run, const RunInputs& inputs,
                        const std::string& folder) {
  io::WriteFileAtomically(
      io::JoinPaths(folder, "trajectory_tum.txt"),
      TumTrajectoryText(run.run.mapping.reconstruction, inputs.sequence->FrameNames(),
                        inputs.source_indices, inputs.sequence->Fps()));
}

// --undistort: dense/ (COLMAP's image_undistorter layout) from the largest model in the input's
// pixels; a folder's images are read at their stored size, a video's frames as decoded.
void WriteUndistortedImages(const DetectorRun& run, const RunInputs& inputs,
                            const std::string& folder) {
  const io::ImageSequence& sequence = *inputs.sequence;
  std::map<std::string, size_t> frame_of_name;
  for (size_t i = 0; i < sequence.NumFrames(); ++i) frame_of_name[sequence.FrameNames()[i]] = i;
  const auto read_image = [&](const Image& image) {
    const size_t frame = frame_of_name.at(image.name);
    const cv::Mat color = sequence.IsVideo() ? sequence.ReadFrame(frame).color
                                             : io::LoadImage(sequence.FramePath(frame)).color;
    return io::ResizeToHeight(color, run.run.input_size.height);
  };
  const Reconstruction& model = run.run.mapping.reconstruction;
  const std::optional<Reconstruction> resized =
      ResizedReconstruction(model, run.run.input_size.width, run.run.input_size.height);
  WriteUndistortedWorkspace(resized ? *resized : model, read_image, io::JoinPaths(folder, "dense"));
}

// No model: the tracks as a COLMAP database (`colmap mapper` or its GUI can be tried on them;
// docs/footage.md), and the rotation-only path when there is one.
void WriteWhatWasFound(const DetectorRun& run, const ReconstructionRunOptions& options,
                       const RunInputs& inputs, const std::string& folder) {
  WriteTracksDatabase(run, options, inputs, io::JoinPaths(folder, "tracks.db"));
  if (run.rotation_only && run.rotation_only->num_registered >= 2) {
    io::WriteColmapTextModel(ToColmapTextModel(run.rotation_only->reconstruction),
                             io::JoinPaths(folder, "rotation_only"));
  }
}

}  // namespace

ModelSetWriteOptions ModelWriteOptions(const DetectorRun& run,
                                       const ReconstructionRunOptions& options) {
  ModelSetWriteOptions write;
  write.text = options.model_format != "bin";
  write.binary = options.model_format != "txt";
  write.width = run.run.input_size.width;
  write.height = run.run.input_size.height;
  return write;
}

std::vector<std::string> DetectorOutputFiles(const DetectorRun& run,
                                             const ReconstructionRunOptions& options) {
  std::vector<std::string> files;
  if (run.success()) {
    files = ModelSetFiles(run.run.mapping, ModelWriteOptions(run, options));
    files.insert(files.end(),
                 {"points.ply", "trajectory.png", "transforms.json", "trajectory_tum.txt"});
    if (options.undistort) {
      for (const std::string& file : UndistortedWorkspaceFiles(run.run.mapping.reconstruction))
        files.push_back("dense/" + file);
    }
  } else if (run.keeps_tracks) {
    files.push_back("tracks.db");
    if (run.rotation_only && run.rotation_only->num_registered >= 2) {
      for (const char* name : kTextModelFiles)
        files.push_back(std::string("rotation_only/") + name);
    }
  }
  files.push_back("report.html");  // every run, failed ones too
  return files;
}

std::string DetectorPagePath(const ReconstructionRunOptions& options, const std::string& detector) {
  if (options.output.empty()) return "";
  const std::string folder =
      options.compare ? io::JoinPaths(options.output, detector) : options.output;
  return io::JoinPaths(folder, "report.html");
}

namespace {

// What a detector's folder may receive, whatever the run's outcome.
const char* const kDetectorFolderEntries[] = {
    "cameras.txt",     "images.txt",         "points3D.txt", "sparse",    "points.ply",
    "trajectory.png",  "report.html",        "report.json",  "tracks.db", "rotation_only",
    "transforms.json", "trajectory_tum.txt", "dense"};

void AddWritten(const std::string& option, const std::string& folder,
                const std::vector<std::string>& names, std::vector<io::NamedPath>* written) {
  for (const std::string& name : names) written->push_back({option, io::JoinPaths(folder, name)});
}

// --output's files: one detector's in it, or --compare's folders and tables.
void AddOutputFolderPaths(const ReconstructionRunOptions& options,
                          std::vector<io::NamedPath>* written) {
  const std::string& out = options.output;
  if (options.compare) {
    AddWritten("--output", out, options.DetectorList(), written);
    AddWritten("--output", out, {"compare.md", "compare.csv", "compare.json", "report.html"},
               written);
  } else {
    AddWritten("--output", out,
               {std::begin(kDetectorFolderEntries), std::end(kDetectorFolderEntries)}, written);
  }
  if (options.compare_colmap) {
    AddWritten("--output", out,
               {"colmap", "colmap_compare.md", "colmap_compare.csv", "colmap_compare.json"},
               written);
  }
  if (options.compare_colmap_sift) {
    AddWritten("--output", out,
               {"colmap_sift", "colmap_sift_compare.md", "colmap_sift_compare.json"}, written);
  }
}

}  // namespace

std::vector<io::NamedPath> RunWrittenPaths(const ReconstructionRunOptions& options) {
  std::vector<io::NamedPath> written;
  if (!options.output.empty()) AddOutputFolderPaths(options, &written);
  written.push_back({"--colmap-db", options.colmap.colmap_db});
  const bool video = io::PathExists(options.frames) && !io::IsDirectory(options.frames);
  if (options.write_frames == kFramesInOutput ||
      (video && options.write_frames.empty() && !options.colmap.colmap_db.empty())) {
    AddWritten("--output", options.output, {"images"}, &written);
  } else {
    written.push_back({"--write-frames", options.write_frames});
  }
  return written;
}

void WriteDetectorOutputs(const DetectorRun& run, const ReconstructionRunOptions& options,
                          const RunInputs& inputs, const std::string& folder) {
  io::EnsureWritableDirectory(folder);
  if (run.success()) {
    WriteModel(run, options, folder);
    WritePointCloud(run, options, folder);
    WriteTrajectoryPlot(run, options, inputs, folder);
    WriteNerfstudioTransforms(run, options, inputs, folder);
    WriteTumTrajectory(run, inputs, folder);
    if (options.undistort) WriteUndistortedImages(run, inputs, folder);
  } else if (run.keeps_tracks) {
    WriteWhatWasFound(run, options, inputs, folder);
  }
  io::WriteHtmlPage(io::JoinPaths(folder, "report.html"), RunPage(run, options, inputs),
                    options.report_page.html);
  io::WriteFileAtomically(io::JoinPaths(folder, "report.json"), io::JsonText(run.report_json, 2));
}

io::ReportTable ComparisonTable(const std::vector<DetectorRun>& runs) {
  std::vector<SfmRunReport> reports;
  for (const DetectorRun& run : runs) reports.push_back(run.report);
  return MakeComparisonTable(reports);
}

void WriteComparisonOutputs(const io::ReportTable& table, const std::vector<DetectorRun>& runs,
                            const ReconstructionRunOptions& options, const RunInputs& inputs,
                            const std::string& folder) {
  io::WriteFileAtomically(io::JoinPaths(folder, "compare.md"), table.ToMarkdown());
  io::WriteFileAtomically(io::JoinPaths(folder, "compare.csv"), table.ToCsv());
  nlohmann::json json = {{"table", table.ToJson()}, {"runs", nlohmann::json::array()}};
  for (const DetectorRun& run : runs) json["runs"].push_back(RunReportToJson(run.report));
  json["options"] = RunOptionsToJson(options, inputs);
  io::WriteFileAtomically(io::JoinPaths(folder, "compare.json"), io::JsonText(json, 2));
  io::WriteHtmlPage(io::JoinPaths(folder, "report.html"),
                    ComparisonPage(table, runs, options, inputs), options.report_page.html);
}

cv::Mat RenderRunPlot(const RunInputs& inputs, const Reconstruction& reconstruction,
                      const std::optional<TrajectoryEvaluation>& evaluation,
                      const std::string& title) {
  const io::ImageSequence& sequence = *inputs.sequence;
  const auto estimated = RegisteredPosesByName(reconstruction, sequence.FrameNames());
  std::vector<std::optional<Eigen::Vector3d>> estimated_centers(estimated.size());
  std::vector<std::optional<Eigen::Vector3d>> true_centers(estimated.size());
  std::vector<Eigen::Vector3d> all_estimated;
  for (size_t i = 0; i < estimated.size(); ++i) {
    if (estimated[i]) {
      Eigen::Vector3d center = ProjectionCenter(*estimated[i]);
      if (evaluation) center = evaluation->gt_from_estimated * center;
      estimated_centers[i] = center;
      all_estimated.push_back(center);
    }
    if (inputs.ground_truth && inputs.ground_truth->cams_from_world[i]) {
      true_centers[i] = ProjectionCenter(*inputs.ground_truth->cams_from_world[i]);
    }
  }
  // Without an alignment the estimate lives in its own frame: draw it alone.
  if (!evaluation) std::fill(true_centers.begin(), true_centers.end(), std::nullopt);
  const PlotPlane plane =
      inputs.plot_plane_from_estimate ? PlotPlaneFromCenters(all_estimated) : inputs.plot_plane;
  TrajectoryPlotOptions plot_options;
  plot_options.title = title;
  plot_options.unit = "model units";
  const size_t registered = all_estimated.size();
  char note[200];
  if (evaluation) {
    const std::string unit = io::GroundTruthLengthUnit(inputs.gt_format);
    plot_options.unit = unit.empty() ? "ground-truth units" : unit;
    std::snprintf(note, sizeof(note), "ATE RMSE %.4g %s (%.3g %% of the %.4g %s path); ",
                  evaluation->ate_rmse, plot_options.unit.c_str(),
                  100.0 * evaluation->ate_fraction_of_path, evaluation->path_length,
                  plot_options.unit.c_str());
    plot_options.note = note;
  }
  plot_options.note +=
      std::to_string(registered) + " of " + std::to_string(estimated.size()) + " frames registered";
  return RenderTrajectoryPlot(estimated_centers, true_centers, plane, plot_options);
}

PlotPlane ParsePlotPlane(const std::string& name) {
  if (name == "xz") return PlotPlaneFromAxes(0, 2);
  if (name == "xy") return PlotPlaneFromAxes(0, 1);
  if (name == "yz") return PlotPlaneFromAxes(1, 2);
  throw Error(ErrorKind::kInvalidArgument,
              "--plot-plane: expected auto, xz, xy or yz, got '" + name + "'");
}

}  // namespace comic::sfm
