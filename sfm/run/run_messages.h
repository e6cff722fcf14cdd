// The lines a front door shows for a run, as comic_sfm prints them on stdout (the Python module
// can show the same): what the inputs resolved to, each registered frame, each detector's
// summary, and where the outputs went. `program` starts the lines that speak for the run
// ("comic_sfm: 12 frames 1226x370, camera PINHOLE ...").
#pragma once

#include <string>
#include <vector>

#include "sfm/incremental_pipeline.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/reconstruction_run.h"
#include "sfm/run/run_inputs.h"

namespace comic::sfm {

// The frames, the camera and where it came from, the ground truth, and the pairing chosen and
// why: shown even when quiet, so that a run says which intrinsics it used.
std::vector<std::string> RunInputsLines(const RunInputs& inputs, const std::string& program);

// "[harris] registered 000004.png: 5/12 frames, 612 points, 270 PnP inliers".
std::string FrameRegisteredLine(const std::string& detector, const MapperProgress& progress);

// "[harris] bundle adjustment of 196 frames, 14210 points: iteration 7 of 50, 2.3 s".
std::string AdjustmentProgressLine(const std::string& detector,
                                   const BundleAdjustmentProgress& progress);

// "[harris] success: 12/12 frames registered, 1586 points, ...": status, registered frames,
// the models, points, track length, reprojection error, the trajectory error with ground truth,
// time, the camera of the model (in the input's pixels; held at the prior and why, when
// self-calibration left the plausible range) and the unregistered frames in ranges with the check
// that failed ("40-47 registration/visible_points"); last, "; page: out/x/report.html" when the
// run writes its page (DetectorRun::page_path).
std::string DetectorSummaryLine(const DetectorRun& run);

// After the run, in order: where a video's frames went (unless `quiet`), the --colmap-db
// database and the command to run on it, the --compare-colmap table, what a failed run found
// and the --compare table followed by the path of its page. `output` is --output.
std::vector<std::string> RunOutcomeLines(const ReconstructionRunResult& result,
                                         const std::string& output, const std::string& program,
                                         bool quiet);

}  // namespace comic::sfm
