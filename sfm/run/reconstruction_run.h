// A reconstruction run, the one behind comic_sfm and comic.reconstruct (as COLMAP's
// RunIncrementalMapperImpl is behind its `mapper` command and pycolmap): the options checked, the
// inputs resolved (frames, ground truth, camera by the rule of camera_resolution.h, pairing), one
// run per detector (detector_run.h), every output written (run_outputs.h, colmap_outputs.h) into
// a staging folder that moves into place only at the end, so that a run that throws leaves the
// file system as it was. A reconstruction that fails is a result, not an exception: its
// report.json (with the diagnosis) and the tracks are committed, and `failure` says why.
//
//   ReconstructionRunOptions options;
//   options.frames = "examples/data/kitti06_000-011/image_l";
//   options.gt = "examples/data/kitti06_000-011/poses.txt";
//   options.output = "out/example";
//   ReconstructionRunResult result = RunReconstruction(options);
//   if (!result.success()) std::cerr << result.failure << "\n";
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/core/protected_inputs.h"
#include "io/report/report_table.h"
#include "sfm/run/colmap_outputs.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/run_inputs.h"
#include "sfm/run/run_options.h"

namespace comic::sfm {

struct ReconstructionRunResult {
  RunInputs inputs;
  std::vector<DetectorRun> runs;              // one per detector, in the order run
  std::optional<io::ReportTable> comparison;  // --compare: the table written as compare.*
  // A video's frames written as PNGs (--write-frames, or for --colmap-db): where they are after
  // the commit (empty: none written).
  std::string frames_folder;
  std::optional<ColmapDatabaseOutput> colmap_database;      // --colmap-db
  std::optional<ColmapComparisonOutput> colmap_comparison;  // --compare-colmap
  std::optional<ColmapPipelineOutput> colmap_pipeline;      // --compare-colmap-sift
  // One detector (no --compare) and no model: the error line, saying which check failed, by how
  // much, what to try and where the report is; or a model holding fewer frames than
  // --min-registered asks for: the line saying so, with the unregistered ranges. Empty otherwise.
  std::string failure;

  bool success() const { return failure.empty(); }
};

// Runs `options`. Throws comic::Error for bad options (kInvalidArgument, naming the flag) and for
// input or outputs it cannot use (kNotFound, kInvalidData, kIo, kExternal), before or during the
// work; nothing is left in options.output then.
ReconstructionRunResult RunReconstruction(const ReconstructionRunOptions& options,
                                          const RunCallbacks& callbacks = {});

// The files and folders a run reads, by the option that names them.
std::vector<io::NamedPath> RunInputPaths(const ReconstructionRunOptions& options);

// The checks before any work: the options, then what they name on the file system (the output
// folder, --colmap-db, COLMAP for --compare-colmap). Throws comic::Error.
void CheckRunOptions(const ReconstructionRunOptions& options);

}  // namespace comic::sfm
