#include "sfm/run/colmap_outputs.h"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "frontend/matching/image_set_matching.h"
#include "frontend/matching/pairing.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/report/json_text.h"
#include "sfm/colmap/colmap_comparison.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/colmap/colmap_pipeline.h"
#include "sfm/colmap/colmap_runner.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

namespace {

// The camera exported as known intrinsics (held fixed by COLMAP), or none for COLMAP's guess; in
// the pixels of `size` (the image files').
std::optional<Camera> KnownCamera(const RunInputs& inputs, cv::Size size) {
  if (inputs.camera.self_calibrating) return std::nullopt;
  return ResizedCamera(inputs.camera.camera, size.width, size.height);
}

// A folder's frames are COLMAP's images at their stored size; a video's are written as the run
// saw them.
cv::Size FileSize(const DetectorRun& run, const RunInputs& inputs) {
  return inputs.sequence->IsVideo() ? run.run.frame_size : run.run.input_size;
}

// The tracks a database is written from, with a descriptor for every feature (an image set's
// have them; a video's tracked features are described now, reading the frames again), so that
// COLMAP's matchers can extend the database.
frontend::FeatureTracks TracksWithDescriptors(const frontend::FeatureTracks& tracks,
                                              const ReconstructionRunOptions& options,
                                              const RunInputs& inputs) {
  frontend::FeatureTracks described = tracks;
  if (!described.HasDescriptors()) {
    frontend::DescribeTrackedFeatures(*inputs.sequence, &described, options.threads);
  }
  return described;
}

}  // namespace

ColmapExportOptions RunExportOptions(const ReconstructionRunOptions& options,
                                     const RunInputs& inputs) {
  ColmapExportOptions export_options = options.colmap.export_options;
  export_options.num_threads = options.threads;
  // An image set matched by descriptors: its pairs are any two frames that share tracks, whatever
  // their distance in the list (--window is a video's).
  if (inputs.image_set) {
    export_options.pair_window = std::max(1, static_cast<int>(inputs.sequence->NumFrames()) - 1);
  }
  export_options.default_camera_model = inputs.camera.camera.model;  // of a guessed camera
  return export_options;
}

frontend::FeatureTracks TracksInFilePixels(const DetectorRun& run) {
  const double factor = static_cast<double>(run.run.input_size.height) /
                        static_cast<double>(run.run.frame_size.height);
  return factor == 1.0 ? run.run.tracks : ScaleTracks(run.run.tracks, factor);
}

namespace {

// The tracks a database is written from: described in the pixels they were found in, then, for an
// image set, in the pixels of the files (a video's frames are written at the working size).
frontend::FeatureTracks DatabaseTracks(const DetectorRun& run,
                                       const ReconstructionRunOptions& options,
                                       const RunInputs& inputs) {
  frontend::FeatureTracks tracks = TracksWithDescriptors(run.run.tracks, options, inputs);
  if (inputs.sequence->IsVideo()) return tracks;
  const double factor = static_cast<double>(run.run.input_size.height) /
                        static_cast<double>(run.run.frame_size.height);
  return factor == 1.0 ? tracks : ScaleTracks(tracks, factor);
}

}  // namespace

ColmapExportSummary WriteTracksDatabase(const DetectorRun& run,
                                        const ReconstructionRunOptions& options,
                                        const RunInputs& inputs, const std::string& path) {
  return ExportTracksToColmapDatabase(DatabaseTracks(run, options, inputs),
                                      KnownCamera(inputs, FileSize(run, inputs)),
                                      RunExportOptions(options, inputs), path, /*overwrite=*/true);
}

ColmapDatabaseOutput WriteRunColmapDatabase(const DetectorRun& run,
                                            const ReconstructionRunOptions& options,
                                            const RunInputs& inputs, const std::string& image_path,
                                            const std::string& database_path) {
  ColmapDatabaseOutput output;
  output.path = options.colmap.colmap_db;
  output.summary = ExportTracksToColmapDatabase(
      DatabaseTracks(run, options, inputs), KnownCamera(inputs, FileSize(run, inputs)),
      RunExportOptions(options, inputs), database_path, options.colmap.overwrite);
  ColmapMapperOptions mapper = RecommendedColmapMapperOptions(output.summary);
  mapper.num_threads = options.colmap.colmap_threads;
  // Into colmap/sparse beside the database: never over our own sparse/0 (issue 29).
  output.mapper_command = ColmapMapperCommandLine(output.path, image_path,
                                                  ColmapMapperOutputBeside(output.path), mapper);
  return output;
}

ColmapComparisonOutput CompareRunWithColmap(const DetectorRun& run,
                                            const ReconstructionRunOptions& options,
                                            const RunInputs& inputs, const io::StagedFolder& out) {
  ColmapComparisonOptions comparison_options;
  comparison_options.export_options = RunExportOptions(options, inputs);
  comparison_options.colmap_threads = options.colmap.colmap_threads;
  const std::vector<std::optional<Rigid3d>> truth = inputs.ground_truth
                                                        ? inputs.ground_truth->cams_from_world
                                                        : std::vector<std::optional<Rigid3d>>();
  // COLMAP reads the folder's images at their stored size: the tracks in those pixels.
  const ColmapComparison comparison = CompareWithColmap(
      TracksInFilePixels(run),
      ResizedCamera(inputs.camera.camera, run.run.input_size.width, run.run.input_size.height),
      !inputs.camera.self_calibrating, truth, options.frames, io::JoinPaths(out.path(), "colmap"),
      comparison_options, &run.run.mapping);
  const io::ReportTable table = comparison.Table();
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_compare.md"), table.ToMarkdown());
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_compare.csv"), table.ToCsv());
  const ColmapExportSummary& exported = comparison.export_summary;
  const nlohmann::json json = {
      {"table", table.ToJson()},
      // Paths as they will be after the outputs move into place, not the staging folder's.
      {"colmap_mapper_command", out.ToTargetPaths(comparison.colmap_mapper_command)},
      {"colmap_model", comparison.colmap_model_path
                           ? nlohmann::json(out.ToTargetPaths(*comparison.colmap_model_path))
                           : nlohmann::json(nullptr)},
      {"colmap_log", out.ToTargetPaths(comparison.log_path)},
      {"export_time_s", comparison.export_time_s},
      {"export",
       {{"images", exported.num_images},
        {"pairs", exported.num_matched_pairs},
        {"verified_pairs", exported.num_verified_pairs},
        {"matches", exported.num_matches},
        {"inlier_matches", exported.num_inlier_matches},
        {"known_intrinsics", exported.known_intrinsics}}}};
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_compare.json"), io::JsonText(json, 2));
  return {out.ToTargetPaths(table.ToMarkdown()),
          out.ToTargetPaths(comparison.colmap_mapper_command),
          out.ToTargetPaths(comparison.log_path)};
}

ColmapPipelineOutput RunColmapPipelineBeside(const DetectorRun& run,
                                             const ReconstructionRunOptions& options,
                                             const RunInputs& inputs, const io::StagedFolder& out) {
  ColmapPipelineOptions pipeline;
  pipeline.sequential = inputs.pairing.chosen.mode == frontend::PairingMode::kSequential;
  if (options.colmap.colmap_threads != -1) pipeline.num_threads = options.colmap.colmap_threads;
  const ColmapPipelineRun colmap = RunColmapPipeline(
      options.frames, inputs.sequence->FrameNames(), io::JoinPaths(out.path(), "colmap_sift"),
      inputs.ground_truth ? inputs.ground_truth->cams_from_world
                          : std::vector<std::optional<Rigid3d>>(),
      pipeline);
  const io::ReportTable table = ColmapPipelineTable(run.report, colmap);
  ColmapPipelineOutput output;
  output.table_markdown = table.ToMarkdown();
  output.log_path = out.ToTargetPaths(colmap.log_path);
  nlohmann::json json = {{"table", table.ToJson()},
                         {"registered_per_model", colmap.num_registered_per_model},
                         {"commands", nlohmann::json::array()},
                         {"log", output.log_path}};
  for (const std::string& command : colmap.commands) {
    output.commands.push_back(out.ToTargetPaths(command));
    json["commands"].push_back(output.commands.back());
  }
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_sift_compare.md"),
                          output.table_markdown);
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_sift_compare.json"),
                          json.dump(2) + "\n");
  return output;
}

bool DatabaseInsideOutput(const ReconstructionRunOptions& options) {
  if (options.output.empty() || options.colmap.colmap_db.empty()) return false;
  const auto normal = [](const std::string& path) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(absolute, ec);
    return ec ? absolute.lexically_normal() : resolved;
  };
  const std::filesystem::path relative =
      normal(options.colmap.colmap_db).lexically_relative(normal(options.output));
  return !relative.empty() && *relative.begin() != "..";
}

void CheckColmapOutputs(const ReconstructionRunOptions& options) {
  if (options.compare_colmap_sift) {
    COMIC_CHECK(io::IsDirectory(options.frames), kInvalidArgument,
                "--compare-colmap-sift needs FRAMES to be a folder of images");
    COMIC_CHECK(IsColmapAvailable(), kNotFound,
                "--compare-colmap-sift: colmap is not installed (apt-get install colmap)");
    const std::string work = io::JoinPaths(options.output, "colmap_sift");
    COMIC_CHECK(!io::PathExists(work), kIo,
                work << ": exists from an earlier --compare-colmap-sift; remove it or use another "
                        "--output");
  }
  if (options.colmap.colmap_db.empty() && !options.compare_colmap) return;
  // A folder's frames are COLMAP's images as stored; a video's are written by --write-frames as
  // the model sees them (resized too), so only a folder needs --resize-height 0.
  const bool video = io::PathExists(options.frames) && !io::IsDirectory(options.frames);
  COMIC_CHECK(video || options.sequence.resize_height == 0, kInvalidArgument,
              "--colmap-db and --compare-colmap need --resize-height 0 (COLMAP reads the image "
              "files at their stored size)");
  COMIC_CHECK(!options.compare_colmap || io::IsDirectory(options.frames), kInvalidArgument,
              "--compare-colmap needs FRAMES to be a folder of images (for a video use "
              "--colmap-db, which writes the frames, and run COLMAP on it)");
  if (!options.colmap.colmap_db.empty()) {
    const std::string folder = io::ParentPath(options.colmap.colmap_db);
    if (DatabaseInsideOutput(options) && !folder.empty() && !io::PathExists(folder)) {
      // Inside a new --output (out/x/tracks.db with a first -o out/x): written into the staging
      // folder, its folder created there. Elsewhere a missing folder stays an error.
      io::CheckCreatableFolder(folder);
    } else {
      CheckColmapDatabaseOutput(options.colmap.colmap_db, options.colmap.overwrite);
    }
  }
  if (options.compare_colmap) {
    COMIC_CHECK(IsColmapAvailable(), kNotFound,
                "--compare-colmap: colmap is not installed (apt-get install colmap)");
    const std::string work = io::JoinPaths(options.output, "colmap");
    COMIC_CHECK(
        !io::PathExists(work), kIo,
        work << ": exists from an earlier --compare-colmap; remove it or use another --output");
  }
}

}  // namespace comic::sfm
