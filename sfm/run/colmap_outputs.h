// What a run hands to COLMAP: its tracks as a COLMAP 3.8 database (tracks.db of a failed run,
// --colmap-db) and COLMAP's mapper on them beside ours (--compare-colmap), with the export options
// comic_export_colmap uses. A camera the run self-calibrates is exported as unknown, so that
// COLMAP refines its own guess; a calibration or the ground truth's is held fixed.
#pragma once

#include <optional>
#include <string>

#include "frontend/matching/track.h"
#include "io/core/staged_folder.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/run_inputs.h"
#include "sfm/run/run_options.h"

namespace comic::sfm {

// --colmap-db's result: what was written and the `colmap mapper` command to run on it.
struct ColmapDatabaseOutput {
  std::string path;
  ColmapExportSummary summary;
  std::string mapper_command;
};

// --compare-colmap-sift's result: the side-by-side table (also written as
// colmap_sift_compare.md and .json) and the COLMAP commands, with paths as after the commit.
struct ColmapPipelineOutput {
  std::string table_markdown;
  std::vector<std::string> commands;
  std::string log_path;
};

// --compare-colmap's result: the side-by-side table (compare tables are also written as
// colmap_compare.md, .csv and .json), with paths as they are after the commit.
struct ColmapComparisonOutput {
  std::string table_markdown;
  std::string mapper_command;
  std::string log_path;
};

// The export options of a run's database: --window, --max-error, --min-inliers, --threads, and
// the camera model of a self-calibrated camera.
ColmapExportOptions RunExportOptions(const ReconstructionRunOptions& options,
                                     const RunInputs& inputs);

// Writes `run`'s tracks (in the image files' pixels) as a COLMAP database at `path` (replacing a
// file there).
ColmapExportSummary WriteTracksDatabase(const DetectorRun& run,
                                        const ReconstructionRunOptions& options,
                                        const RunInputs& inputs, const std::string& path);

// --colmap-db lies inside --output (compared by name: --output may not exist yet).
bool DatabaseInsideOutput(const ReconstructionRunOptions& options);

// --colmap-db: `run`'s tracks as options.colmap.colmap_db (refused if it exists unless
// --overwrite), written at `database_path` (the same file, or its place in --output's staging
// folder when it lies inside --output). `image_path` holds the frames as files: FRAMES, or a
// video's written frames.
ColmapDatabaseOutput WriteRunColmapDatabase(const DetectorRun& run,
                                            const ReconstructionRunOptions& options,
                                            const RunInputs& inputs, const std::string& image_path,
                                            const std::string& database_path);

// --compare-colmap: COLMAP's mapper on `run`'s tracks, in `out`/colmap/, and the table in `out`.
// Throws comic::Error(kExternal) if COLMAP fails.
ColmapComparisonOutput CompareRunWithColmap(const DetectorRun& run,
                                            const ReconstructionRunOptions& options,
                                            const RunInputs& inputs, const io::StagedFolder& out);

// --compare-colmap-sift: COLMAP's own pipeline on the frames of FRAMES (a folder), in
// `out`/colmap_sift/, with the table beside `run`'s report (sfm/colmap/colmap_pipeline.h).
// Sequential matching when the run paired frames sequentially, else exhaustive; one thread unless
// --colmap-threads. Throws comic::Error(kExternal) if COLMAP fails.
ColmapPipelineOutput RunColmapPipelineBeside(const DetectorRun& run,
                                             const ReconstructionRunOptions& options,
                                             const RunInputs& inputs, const io::StagedFolder& out);

// The tracks of `run` in the pixels of the image files as stored (a folder's frames are read at
// their stored size by COLMAP; the run may have worked at a smaller size).
frontend::FeatureTracks TracksInFilePixels(const DetectorRun& run);

// The checks of --colmap-db, --compare-colmap and --compare-colmap-sift that look at the file
// system (the frames, the
// database, the colmap program, --output/colmap/), before any work. Throws comic::Error.
void CheckColmapOutputs(const ReconstructionRunOptions& options);

}  // namespace comic::sfm
