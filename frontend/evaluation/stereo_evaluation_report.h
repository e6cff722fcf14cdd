// Tables of a Middlebury stereo evaluation (stereo_evaluation.h) in Markdown, CSV and JSON, with
// the paper's own Tsukuba and Cones numbers (Tables 1 and 2, "Stereo" rows) beside ours.
//
//   std::vector<StereoPairEvaluation> results = {EvaluateStereoPair(pair, options)};
//   StereoReport report = BuildStereoReport(results, options);
//   io::WriteFileAtomically("scores.csv", report.scores.ToCsv());
//   io::WriteFileAtomically("stereo_eval.md", StereoReportMarkdown(report, results, options));
//
// Percentages are M_score(1), precision, share-of-all and repeatability times 100; a ratio with a
// zero denominator (no detection, nothing accepted, no precision target) is an empty cell,
// written "–" in Markdown, empty in CSV and null in JSON.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "frontend/evaluation/stereo_evaluation.h"
#include "io/report/report_table.h"

namespace comic::frontend {

// The paper's stereo rows (Tables 1 and 2) for one pair. Indices: [region][detector], regions in
// StereoRegion order, detectors in DetectorNames() order (comic, harris, hessian, mser, fast).
// Table 1 is captioned M_score(5) for the whole table; for the stereo rows the text (§5.2.2)
// says M_score(1) and ResM_1.
struct PaperStereoNumbers {
  std::string pair;  // "Tsukuba", "Cones"
  std::array<std::array<double, 5>, kNumStereoRegions> m_score_percent;
  std::array<std::array<double, 5>, kNumStereoRegions> resm;
};

// The paper's numbers for a pair whose name contains "tsukuba" or "cones" (case-insensitive);
// nullopt for any other pair (e.g. Teddy, which the paper does not report).
std::optional<PaperStereoNumbers> PaperStereoNumbersFor(const std::string& pair_name);

// The long tables (one fact per row), written as CSV and JSON.
struct StereoReport {
  io::ReportTable protocol{{"parameter", "value"}};
  io::ReportTable pairs{{"pair"}};
  io::ReportTable detections{{"pair"}};
  // One row per pair, N, method, threshold T (sensitivity list, max_cost, inf) and region.
  io::ReportTable scores{{"pair"}};
  io::ReportTable matched_precision{{"pair"}};
  io::ReportTable repeatability{{"pair"}};
  // Our numbers at T = max_cost beside the paper's, one row per pair, N, detector and region
  // (the first method of each detector, CoMIC's split matcher by default).
  io::ReportTable paper_comparison{{"pair"}};

  nlohmann::json ToJson() const;
};

StereoReport BuildStereoReport(const std::vector<StereoPairEvaluation>& results,
                               const StereoEvaluationOptions& options);

// A readable report: the protocol, then per pair and N the paper-layout table (ours and the
// paper's), scores at T with precision, the T sensitivity, matched precision and T = ∞, the
// repeatability and the detection counts.
std::string StereoReportMarkdown(const StereoReport& report,
                                 const std::vector<StereoPairEvaluation>& results,
                                 const StereoEvaluationOptions& options);

}  // namespace comic::frontend
