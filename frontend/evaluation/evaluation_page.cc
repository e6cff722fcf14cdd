#include "frontend/evaluation/evaluation_page.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "frontend/evaluation/stereo_match_figure.h"
#include "frontend/evaluation/track_drawing.h"
#include "io/report/bar_chart.h"
#include "io/report/data_uri.h"
#include "io/report/number_text.h"
#include "io/report/page_sections.h"

namespace comic::frontend {

namespace {

constexpr int kFigureWidth = 1600;  // pixels: wider figures are shrunk for the page
constexpr int kJpegQuality = 85;

std::vector<io::PageImage> Pictures(const std::vector<EvaluationFigure>& figures) {
  std::vector<io::PageImage> pictures;
  for (const EvaluationFigure& figure : figures) {
    cv::Mat image = figure.image;
    if (image.cols > kFigureWidth) {
      const double scale = static_cast<double>(kFigureWidth) / image.cols;
      cv::resize(figure.image, image, cv::Size(), scale, scale, cv::INTER_AREA);
    }
    pictures.push_back({io::ImageDataUri(image, kJpegQuality), figure.caption, ""});
  }
  return pictures;
}

// M_score(n) and ResM_n of every row, per region, as two charts with one colour per row.
io::PageSection ScoreCharts(const TrackEvaluation& evaluation, size_t k) {
  const std::string n = std::to_string(evaluation.options.ns[k]);
  io::BarChart score, count;
  score.title = "M_score(" + n + ")";
  score.y_label = "M_score(" + n + ") (% of N)";
  count.title = "ResM_" + n;
  count.y_label = "ResM_" + n + " (features)";
  score.groups = count.groups =
      evaluation.has_regions ? std::vector<std::string>{"boundary", "non-boundary", "overall"}
                             : std::vector<std::string>{"overall"};
  for (const EvaluationRow& row : evaluation.rows) {
    const MatchingScores& s = row.scores[k];
    io::BarChartSeries percent{row.label, {}}, features{row.label, {}};
    std::vector<const RegionScore*> regions = {&s.overall};
    if (evaluation.has_regions) regions = {&s.boundary, &s.non_boundary, &s.overall};
    for (const RegionScore* region : regions) {
      percent.values.push_back(100.0 * region->mean_m_score);
      features.values.push_back(region->mean_res_m);
    }
    score.series.push_back(percent);
    count.series.push_back(features);
  }
  return io::BarChartsSection(
      "M_score(" + n + ") and ResM_" + n + " per detector", {score, count},
      "M_score(" + n + "): of the N features detected in a frame, the share still matched " + n +
          " frame(s) later along one track (mean over start frames every " +
          std::to_string(evaluation.options.frame_step) + " frames); ResM_" + n +
          ": how many features that is. Higher is better. Boundary: within " +
          io::NumberText("%g", evaluation.options.boundary_band) +
          " px of the object's edge; non-boundary: inside the object; overall: both.");
}

std::vector<io::PageFact> TrackFacts(const TrackEvaluation& evaluation,
                                     const TrackEvaluationPageInputs& inputs) {
  const TrackEvaluationOptions& options = evaluation.options;
  std::string ns;
  for (int n : options.ns) ns += (ns.empty() ? "" : ", ") + std::to_string(n);
  return {
      {"frames", std::to_string(evaluation.num_frames) + " (" + evaluation.frame_names.front() +
                     " … " + evaluation.frame_names.back() + ") at " +
                     std::to_string(evaluation.frame_size.width) + "×" +
                     std::to_string(evaluation.frame_size.height) + " px"},
      {"object region",
       inputs.region + "; boundary band " + io::NumberText("%g", options.boundary_band) + " px"},
      {"N", std::to_string(evaluation.reference_count) + " features in frame 0's object region (" +
                (evaluation.reference_source == "comic" ? "CoMIC's count" : "requested") +
                "); every detector's threshold is set to give N there"},
      {"matching", "gate r = " + io::NumberText("%g", options.matcher.radius) +
                       " px, SSD threshold T = " + io::NumberText("%g", options.matcher.max_cost) +
                       " (mean squared grey-level difference per pixel), min side overlap " +
                       io::NumberText("%g", options.matcher.min_side_overlap) + " px"},
      {"n", ns}};
}

}  // namespace

io::HtmlPage TrackEvaluationPage(const TrackEvaluation& evaluation,
                                 const TrackEvaluationPageInputs& inputs) {
  io::HtmlPage page;
  page.title = "comic_track_eval · " + std::to_string(evaluation.num_frames) + " frames";
  page.subtitle = inputs.command;
  page.sections.push_back(io::FactsSection("Protocol", TrackFacts(evaluation, inputs)));
  const bool has_precision = !evaluation.rows.empty() && evaluation.rows.front().precision;
  for (size_t k = 0; k < evaluation.options.ns.size(); ++k) {
    const int n = evaluation.options.ns[k];
    page.sections.push_back(io::TableSection(
        "Scores, n = " + std::to_string(n), ScoreTable(evaluation, n),
        "The paper's Table 1/2 layout: the response cut-off, the frame-0 count N_0, M_score(n) in "
        "% and ResM_n for each region."));
    page.sections.push_back(ScoreCharts(evaluation, k));
    page.sections.push_back(io::TableSection(
        "At other SSD thresholds T, n = " + std::to_string(n), ThresholdSweepTable(evaluation, n),
        "The same mutual-best matches re-thresholded: how the comparison depends on T."));
    if (has_precision) {
      page.sections.push_back(io::TableSection(
          "Epipolar precision, n = " + std::to_string(n), PrecisionTable(evaluation, n),
          "A match is correct within " +
              io::NumberText("%g", evaluation.options.epipolar_tolerance) +
              " px of its epipolar line (KITTI poses)."));
    }
  }
  // Rows only when a matcher other than the full patch is compared (as precision_equal_count.*).
  const io::ReportTable equal_count =
      has_precision ? EqualCountPrecisionTable(evaluation) : io::ReportTable({"detector"});
  if (equal_count.NumRows() > 0) {
    page.sections.push_back(io::TableSection(
        "Epipolar precision at equal numbers of matches", equal_count,
        "Each matcher other than the full patch keeps, in every frame pair, as many of its "
        "cheapest mutual-best matches as the same detector's full-patch matcher accepts at T: "
        "precision compared at equal numbers of matches."));
  }
  if (!inputs.overlays.empty()) {
    page.sections.push_back(io::ImagesSection(
        "Tracks on frames", Pictures(inputs.overlays), TrackDrawingLegend(evaluation.has_regions),
        "One tile per detector: each track through the frame drawn over its last 5 frames, "
        "ending in a dot at its feature."));
  }
  return page;
}

io::HtmlPage StereoEvaluationPage(const StereoReport& report,
                                  const std::vector<StereoPairEvaluation>& results,
                                  const StereoEvaluationOptions& options,
                                  const std::vector<EvaluationFigure>& figures,
                                  const std::string& command) {
  io::HtmlPage page;
  page.title = "comic_stereo_eval · " + std::to_string(results.size()) + " pair" +
               (results.size() == 1 ? "" : "s");
  page.subtitle = command;
  page.sections.push_back(io::TableSection("Protocol", report.protocol));
  page.sections.push_back(io::TableSection("Pairs", report.pairs));
  // M_score(1) at T per method and region, for each pair's first count.
  for (const StereoPairEvaluation& pair : results) {
    if (pair.runs.empty()) continue;
    const StereoRun& run = pair.runs.front();
    io::BarChart chart;
    chart.title = pair.name;
    chart.y_label = "M_score(1) (% of detected)";
    for (StereoRegion region : kStereoRegions) chart.groups.push_back(StereoRegionName(region));
    for (const StereoMatching& matching : run.matchings) {
      const RegionScores scores =
          ScoreAt(run.DetectionFor(matching.method.detector), matching, options.max_cost);
      io::BarChartSeries series{matching.method.Label(), {}};
      for (const RegionCounts& counts : scores) {
        series.values.push_back(counts.MScore() ? 100.0 * *counts.MScore() : std::nan(""));
      }
      chart.series.push_back(series);
    }
    page.sections.push_back(io::BarChartSection(
        chart, "N = " + std::to_string(run.target_count) +
                   " features per image, T = " + io::NumberText("%g", options.max_cost) +
                   ": the share of the detected left features whose accepted match is correct "
                   "(within " +
                   io::NumberText("%g", options.correct_tolerance) +
                   " px). Boundary: near a depth discontinuity (disc.png); non-boundary: the "
                   "rest of the valid pixels."));
  }
  page.sections.push_back(io::TableSection("Scores", report.scores));
  page.sections.push_back(io::TableSection("Matched precision", report.matched_precision));
  page.sections.push_back(io::TableSection("Repeatability", report.repeatability));
  page.sections.push_back(io::TableSection("Detections", report.detections));
  page.sections.push_back(io::TableSection("Beside the paper", report.paper_comparison));
  if (!figures.empty()) {
    page.sections.push_back(io::ImagesSection(
        "Matches", Pictures(figures), StereoMatchFigureLegend(options.correct_tolerance),
        "One panel per method: the left image with its accepted matches as disparity vectors."));
  }
  return page;
}

}  // namespace comic::frontend
