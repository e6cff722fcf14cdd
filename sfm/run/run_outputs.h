// The files a run writes. A detector's folder (--output, or --output/<detector>/ with --compare):
// with a model, the COLMAP model as text (cameras.txt, images.txt, points3D.txt) and binary
// (sparse/0/*.bin, where COLMAP's mapper puts its first model) by --model-format, points.ply,
// trajectory.png, the largest model for the next tools (transforms.json for nerfstudio and the
// splatting trainers, trajectory_tum.txt for evo) and report.json; without one, report.json with
// the diagnosis, tracks.db (the tracks, a COLMAP database) and, when the camera only turned,
// rotation_only/ (a COLMAP text model of the cameras alone). --compare adds compare.md, compare.csv
// and compare.json.
//
// A writer added here is one line in WriteDetectorOutputs (and one name in DetectorOutputFiles).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/core/protected_inputs.h"
#include "io/report/report_table.h"
#include "sfm/colmap/model_set_writer.h"
#include "sfm/evaluation/trajectory_plot.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/run_inputs.h"
#include "sfm/run/run_options.h"

namespace comic::sfm {

// How `run`'s models are written: every model in the input's pixels, sparse/<k>/ as COLMAP's mapper
// numbers its models (sparse/0, the largest, is where nerfstudio and the Gaussian-splatting tools
// look), the largest also as text at the top, by --model-format (sfm/colmap/model_set_writer.h).
ModelSetWriteOptions ModelWriteOptions(const DetectorRun& run,
                                       const ReconstructionRunOptions& options);

// The files WriteDetectorOutputs writes for `run`, relative to its folder, in report.json's order.
std::vector<std::string> DetectorOutputFiles(const DetectorRun& run,
                                             const ReconstructionRunOptions& options);

// Where `detector`'s report.html will be once the run is committed, as the user named --output
// ("out/x/report.html", or "out/x/harris/report.html" with --compare); empty without --output.
// The summary line ends with it, so that a user sees where to look.
std::string DetectorPagePath(const ReconstructionRunOptions& options, const std::string& detector);

// Every file and folder a run of `options` may write, before any work, each named by the option
// that writes it (--output, --colmap-db, --write-frames): what DetectorOutputFiles can list for
// any outcome (every model's sparse/ tree, a failed run's files), --compare's and the COLMAP
// comparisons' files and folders, a video's frames.
std::vector<io::NamedPath> RunWrittenPaths(const ReconstructionRunOptions& options);

// Writes every output of `run` into `folder` (created if needed). Throws comic::Error(kIo).
void WriteDetectorOutputs(const DetectorRun& run, const ReconstructionRunOptions& options,
                          const RunInputs& inputs, const std::string& folder);

// --compare: the table of the runs, one row per detector.
io::ReportTable ComparisonTable(const std::vector<DetectorRun>& runs);

// --compare: `table` as compare.md, compare.csv and compare.json (the table, every run's report
// and the options) in `folder`.
void WriteComparisonOutputs(const io::ReportTable& table, const std::vector<DetectorRun>& runs,
                            const ReconstructionRunOptions& options, const RunInputs& inputs,
                            const std::string& folder);

// The top view of `reconstruction`'s camera centres (with ground truth: Sim(3)-aligned, beside
// the true ones) on the run's plot plane.
cv::Mat RenderRunPlot(const RunInputs& inputs, const Reconstruction& reconstruction,
                      const std::optional<TrajectoryEvaluation>& evaluation,
                      const std::string& title);

// --plot-plane xz, xy or yz. Throws comic::Error(kInvalidArgument) naming --plot-plane.
PlotPlane ParsePlotPlane(const std::string& name);

}  // namespace comic::sfm
