// report.html of a run (issue 28): one self-contained page (io/report/html_page.h) that says in
// one look whether the run is good and where it went wrong. A detector's page holds the summary
// (status, registered frames, points, the camera and where its intrinsics came from, the time per
// stage, the diagnosis of a failure), the 3-D view of the points and cameras (with the ground
// truth's path), the registration timeline, with ground truth each camera's error and the top
// view, frames with their tracks, a thumbnail strip, the options and report.json itself. Written
// for every run: success, partial and failed. --compare adds one page across the detectors.
//
//   const io::HtmlPage page = RunPage(run, options, inputs);
//   io::WriteHtmlPage("out/report.html", page, options.report_page.html);
#pragma once

#include <vector>

#include "io/report/html_page.h"
#include "io/report/report_table.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/run_inputs.h"
#include "sfm/run/run_options.h"

namespace comic::sfm {

// Sections that hold measured durations carry "durations": true, so that a comparison of two
// runs' pages can leave them out, as it leaves out report.json's time_s.
inline constexpr const char* kDurationsKey = "durations";

// The summary's words for what loop closure did: "2 loops closed: frames 1990 → 3, 1993 → 6 ·
// 180 points fused · cameras moved up to 4.1 (model units)", or "no loop found among 400
// keyframes searched (3 candidates by appearance)".
std::string LoopClosureWords(const LoopClosureSummary& summary);

// The page of one detector's run. Reads a few frames of inputs.sequence (options.report_page).
// Throws comic::Error for frames it cannot read.
io::HtmlPage RunPage(const DetectorRun& run, const ReconstructionRunOptions& options,
                     const RunInputs& inputs);

// --compare: the table, bar charts of ATE, points and time per detector, the paths in one top
// view and each detector's timeline, with links to each detector's own page.
io::HtmlPage ComparisonPage(const io::ReportTable& table, const std::vector<DetectorRun>& runs,
                            const ReconstructionRunOptions& options, const RunInputs& inputs);

}  // namespace comic::sfm
