#include "sfm/run/colmap_outputs.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "frontend/matching/image_set_matching.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/report/json_text.h"
#include "sfm/colmap/colmap_comparison.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/colmap/colmap_runner.h"

namespace comic::sfm {

namespace {

// The camera exported as known intrinsics (held fixed by COLMAP), or none for COLMAP's guess.
std::optional<Camera> KnownCamera(const RunInputs& inputs) {
  if (inputs.camera.self_calibrating) return std::nullopt;
  return inputs.camera.camera;
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

ColmapExportSummary WriteTracksDatabase(const frontend::FeatureTracks& tracks,
                                        const ReconstructionRunOptions& options,
                                        const RunInputs& inputs, const std::string& path) {
  return ExportTracksToColmapDatabase(TracksWithDescriptors(tracks, options, inputs),
                                      KnownCamera(inputs), RunExportOptions(options, inputs), path,
                                      /*overwrite=*/true);
}

ColmapDatabaseOutput WriteRunColmapDatabase(const DetectorRun& run,
                                            const ReconstructionRunOptions& options,
                                            const RunInputs& inputs,
                                            const std::string& image_path) {
  ColmapDatabaseOutput output;
  output.path = options.colmap.colmap_db;
  output.summary = ExportTracksToColmapDatabase(
      TracksWithDescriptors(run.run.tracks, options, inputs), KnownCamera(inputs),
      RunExportOptions(options, inputs), output.path, options.colmap.overwrite);
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
  const ColmapComparison comparison = CompareWithColmap(
      run.run.tracks, inputs.camera.camera, !inputs.camera.self_calibrating, truth, options.frames,
      io::JoinPaths(out.path(), "colmap"), comparison_options, &run.run.mapping);
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

void CheckColmapOutputs(const ReconstructionRunOptions& options) {
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
    CheckColmapDatabaseOutput(options.colmap.colmap_db, options.colmap.overwrite);
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
