// report.html of the evaluation apps (issue 28): comic_track_eval's and comic_stereo_eval's
// tables and figures in one self-contained page (io/report/html_page.h), with what their PNGs
// leave unsaid: what each colour on a figure means, what the scores count, the axes' units.
//
//   io::WriteHtmlPage("out/report.html",
//                     TrackEvaluationPage(evaluation, {command, "masks Annotations/", overlays}));
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/evaluation/stereo_evaluation.h"
#include "frontend/evaluation/stereo_evaluation_report.h"
#include "frontend/evaluation/track_evaluation.h"
#include "io/report/html_page.h"

namespace comic::frontend {

// A figure of an evaluation (e.g. tracks_00005.png): its caption and picture (BGR).
struct EvaluationFigure {
  std::string caption;
  cv::Mat image;
};

struct TrackEvaluationPageInputs {
  std::string command;                     // the command line, under the title
  std::string region;                      // "masks DIR", "regions FILE" or "none"
  std::vector<EvaluationFigure> overlays;  // frames with every detector's tracks
};

// The summary of the protocol, per n the score table with M_score(n) and ResM_n as bar charts,
// the threshold sweeps, the epipolar precision (with ground truth), and the track overlays with
// their legend.
io::HtmlPage TrackEvaluationPage(const TrackEvaluation& evaluation,
                                 const TrackEvaluationPageInputs& inputs);

// The protocol, every table of the report, M_score(1) per method and region as bar charts, and
// each pair's match figure with its legend.
io::HtmlPage StereoEvaluationPage(const StereoReport& report,
                                  const std::vector<StereoPairEvaluation>& results,
                                  const StereoEvaluationOptions& options,
                                  const std::vector<EvaluationFigure>& figures,
                                  const std::string& command);

}  // namespace comic::frontend
