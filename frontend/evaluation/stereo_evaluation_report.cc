#include "frontend/evaluation/stereo_evaluation_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

using Cell = io::ReportTable::Cell;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kOverall = static_cast<int>(StereoRegion::kOverall);

Cell Percent(const std::optional<double>& ratio) {
  if (!ratio) return std::monostate{};
  return 100.0 * *ratio;
}

Cell Int(int value) { return static_cast<int64_t>(value); }

std::string Number(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string NumberList(const std::vector<double>& values, const std::string& unit = "") {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ", ") + Number(v) + unit;
  return text;
}

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// The thresholds reported: the sensitivity list and max_cost, ascending, then T = ∞.
std::vector<double> ReportedThresholds(const StereoEvaluationOptions& options) {
  std::vector<double> thresholds = options.sensitivity_costs;
  thresholds.push_back(options.max_cost);
  std::sort(thresholds.begin(), thresholds.end());
  thresholds.erase(std::unique(thresholds.begin(), thresholds.end()), thresholds.end());
  thresholds.push_back(kInfinity);
  return thresholds;
}

// The paper's columns (Tables 1 and 2): CoMIC, Harris, Hessian, MSER, FAST. The default "comic"
// fills the CoMIC column of the paper layout; "comic-paper" (Algorithm 1, the paper's own
// search) is compared with the same printed CoMIC numbers.
const std::vector<std::string>& PaperDetectors() {
  static const std::vector<std::string> kPaperDetectors = {"comic", "harris", "hessian", "mser",
                                                           "fast"};
  return kPaperDetectors;
}

int DetectorIndex(const std::string& name) {
  if (name == "comic-paper") return 0;
  const auto& names = PaperDetectors();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

// The matching shown for a detector in the paper's layout: its first method in the options.
const StereoMatching* PrimaryMatching(const StereoRun& run, const std::string& detector) {
  for (const StereoMatching& m : run.matchings) {
    if (m.method.detector == detector) return &m;
  }
  return nullptr;
}

std::string RunTitle(const StereoPairEvaluation& pair, const StereoRun& run) {
  std::string title = pair.name + ", N = " + std::to_string(run.target_count);
  if (run.requested_count == 0) title += " (the reference detector's own count)";
  return title;
}

// The cut-off as text: "–" when nothing was cut (too few candidates) or nothing kept.
Cell CutCell(const ThresholdCut& cut) {
  if (cut.min_response == -std::numeric_limits<float>::max()) return std::string("all");
  if (std::isinf(cut.min_response)) return std::string("none");
  return static_cast<double>(cut.min_response);
}

io::ReportTable ProtocolTable(const StereoEvaluationOptions& options) {
  io::ReportTable table({"parameter", "value"});
  auto add = [&](const std::string& name, const std::string& value) {
    table.AddRow({name, value});
  };
  std::string methods;
  for (const StereoMethod& m : options.methods)
    methods += (methods.empty() ? "" : ", ") + m.Label();
  std::string counts;
  for (int n : options.target_counts) {
    counts += (counts.empty() ? "" : ", ") +
              (n == 0 ? options.count_reference + "'s own count at its default threshold"
                      : std::to_string(n));
  }
  add("working size", options.working_height > 0
                          ? "height " + std::to_string(options.working_height) +
                                " px (paper §5.1); images resized (INTER_AREA/INTER_LINEAR), GT "
                                "disparity scaled by the horizontal resize factor"
                          : "as given (no resizing)");
  add("mask and GT resizing", "exact nearest neighbour (INTER_NEAREST_EXACT)");
  add("methods (detector/matcher)", methods);
  add("target count N (valid left features)", counts);
  add("threshold equalisation",
      "one response cut-off chosen on the left image so N features lie on valid pixels, applied "
      "unchanged to the right image");
  add("ties at the cut-off",
      "with r the N-th largest response: keep >= r (count c_hi) or > r (c_lo), whichever count "
      "is closer to N; on equal distance, or c_lo = 0, keep the tie (c_hi)");
  add("patch fit", "features whose 23x23 patch does not fit are dropped before equalisation");
  add("MSER merging", "centroids closer than " + Number(options.detectors.mser.merge_radius) +
                          " px merged, the more stable region kept (MSER detector option)");
  add("valid / excluded pixels",
      "excluded: GT disparity unknown (0) or occluded (nonocc = 0); they are counted, not scored; "
      "all left detections still take part in matching");
  add("boundary region", "disc = 255 (near a depth discontinuity), valid pixels only");
  add("non-boundary region", "every other valid pixel (disc = 128)");
  add("row gate", "|y_right - y_left| <= " + Number(options.row_tolerance) + " px");
  add("disparity search range",
      "[" + Number(options.min_disparity) + ", " +
          (options.max_disparity > 0
               ? Number(options.max_disparity)
               : "max GT disparity at working size + " + Number(options.disparity_margin)) +
          "] px");
  add("patch cost",
      "23x23, mean squared difference of 0-255 grey values; full = 529 pixels; split = min over "
      "the 4 side pairings (Algorithm 2); like-sides = (ic+,ic+) and (ic-,ic-) only; pairings "
      "need >= " +
          std::to_string(options.min_side_overlap) +
          " shared pixels; calibrated = min of the full patch and the object sides' (or like "
          "sides') costs in full-patch units, sides >= " +
          Number(options.min_side_fraction) + " of the patch, noise sigma " +
          (options.side_noise_from_pair ? std::string("from each pair's full-patch matches")
                                        : Number(options.side_noise_sigma)));
  add("one-to-one", "mutual best over all gated candidates, then the threshold T");
  add("SSD threshold T", Number(options.max_cost) + " (mean squared difference)");
  add("T sensitivity", NumberList(options.sensitivity_costs) + ", inf");
  add("correct match", "right feature within " + Number(options.correct_tolerance) +
                           " px (Euclidean, working size) of (x - d(x, y), y)");
  add("M_score(1)", "correct accepted matches / valid left detections in the region");
  add("ResM_1", "correct accepted matches in the region");
  add("precision", "correct / accepted, left feature in the region");
  add("share of all", "correct in the region / valid left detections overall");
  add("matched precision", options.target_precision > 0
                               ? "common target " + Number(100 * options.target_precision) + " %"
                               : "common target = overall precision of " +
                                     options.precision_reference.Label() +
                                     " at T = " + Number(options.max_cost) +
                                     "; per method the largest T reaching it (overall precision)");
  add("repeatability", "share of valid left features with any right feature within " +
                           NumberList(options.repeatability_tolerances, " px") +
                           " of the true position");
  return table;
}

}  // namespace

std::optional<PaperStereoNumbers> PaperStereoNumbersFor(const std::string& pair_name) {
  const std::string name = Lower(pair_name);
  // Ravindran & Mittal, Table 1 (M_score, %) and Table 2 (ResM), rows "Tsukuba" and "Cones";
  // columns CoMIC, Harris, Hessian, MSER, FAST per region. Copied as printed (the Tsukuba
  // CoMIC Overall ResM reads 881 although Boundary + Non-Boundary = 781).
  if (name.find("tsukuba") != std::string::npos) {
    return PaperStereoNumbers{
        "Tsukuba",
        {{{32.6, 20.9, 29.2, 11.6, 30.7},
          {48.2, 47.8, 51.1, 43.3, 43.9},
          {81.1, 68.4, 79.7, 54.9, 74.2}}},
        {{{278, 112, 266, 56, 171}, {503, 489, 514, 544, 409}, {881, 591, 763, 599, 571}}}};
  }
  if (name.find("cones") != std::string::npos) {
    return PaperStereoNumbers{
        "Cones",
        {{{22.1, 10.1, 19.6, 4.4, 13.5},
          {35.1, 44.1, 37.8, 43.1, 32.2},
          {57.4, 53.3, 56.1, 47.5, 44.9}}},
        {{{338, 188, 299, 121, 330}, {514, 429, 524, 450, 471}, {852, 614, 817, 571, 797}}}};
  }
  return std::nullopt;
}

nlohmann::json StereoReport::ToJson() const {
  return nlohmann::json{{"protocol", protocol.ToJson()},
                        {"pairs", pairs.ToJson()},
                        {"detections", detections.ToJson()},
                        {"scores", scores.ToJson()},
                        {"matched_precision", matched_precision.ToJson()},
                        {"repeatability", repeatability.ToJson()},
                        {"paper_comparison", paper_comparison.ToJson()}};
}

namespace {

// The report's tables with their columns and number formats, no rows yet.
void MakeEmptyTables(const StereoEvaluationOptions& options, StereoReport& report) {
  report.pairs = io::ReportTable({"pair", "width", "height", "resize factor", "disparity scale",
                                  "max GT disparity px", "gate min disparity px",
                                  "gate max disparity px", "boundary pixels", "non-boundary pixels",
                                  "occluded pixels", "unknown pixels", "reference count"});
  report.detections = io::ReportTable(
      {"pair", "N", "detector", "cut-off response", "left candidates", "valid candidates",
       "reached N", "left kept", "right kept", "detected boundary", "detected non-boundary",
       "detected overall", "excluded unknown disparity", "excluded occluded"});
  report.scores =
      io::ReportTable({"pair", "N", "method", "T", "region", "detected", "accepted",
                       "correct (ResM_1)", "M_score(1) %", "precision %", "share of all %"});
  report.matched_precision = io::ReportTable(
      {"pair", "N", "method", "target precision %", "T at target", "accepted", "correct",
       "precision %", "M_score boundary %", "M_score non-boundary %", "M_score overall %",
       "T=inf M_score boundary %", "T=inf M_score non-boundary %", "T=inf M_score overall %",
       "T=inf precision %"});
  std::vector<std::string> repeatability_columns = {"pair", "N", "detector", "region", "detected"};
  for (double t : options.repeatability_tolerances) {
    repeatability_columns.push_back("repeatable within " + Number(t) + " px %");
  }
  report.repeatability = io::ReportTable(repeatability_columns);
  report.paper_comparison = io::ReportTable(
      {"pair", "N", "detector", "method", "region", "M_score(1) %", "paper M_score %", "ResM_1",
       "paper ResM", "precision %", "share of all %", "detected"});
  for (io::ReportTable* table : {&report.scores, &report.matched_precision, &report.repeatability,
                                 &report.paper_comparison}) {
    for (const std::string& column : table->columns()) {
      if (column.find('%') != std::string::npos) table->SetPrecision(column, 1);
    }
  }
  report.pairs.SetPrecision("resize factor", 4);
  for (const char* column :
       {"max GT disparity px", "gate min disparity px", "gate max disparity px"}) {
    report.pairs.SetPrecision(column, 2);
  }
  report.matched_precision.SetPrecision("T at target", 1);
  report.detections.SetPrecision("cut-off response", 6);
}

// One detections row per detector and its repeatability rows per region.
void AddDetectionRows(const StereoPairEvaluation& pair, const StereoRun& run,
                      const StereoEvaluationOptions& options, StereoReport& report) {
  const Cell n = Int(run.target_count);
  for (const StereoDetection& d : run.detections) {
    report.detections.AddRow(
        {pair.name, n, d.detector, CutCell(d.cut), Int(d.left_candidates), Int(d.cut.available),
         std::string(d.cut.reached ? "yes" : "no"), Int(static_cast<int>(d.left.size())),
         Int(static_cast<int>(d.right.size())), Int(d.detected[0]), Int(d.detected[1]),
         Int(d.detected[2]), Int(d.unknown_disparity), Int(d.occluded)});
    for (StereoRegion region : kStereoRegions) {
      const int r = static_cast<int>(region);
      std::vector<Cell> row = {pair.name, n, d.detector, StereoRegionName(region),
                               Int(d.detected[r])};
      for (size_t k = 0; k < options.repeatability_tolerances.size(); ++k) {
        row.push_back(
            Percent(RegionCounts{d.detected[r], d.detected[r], d.repeatable[k][r]}.MScore()));
      }
      report.repeatability.AddRow(std::move(row));
    }
  }
}

// Per matching method: scores at each reported threshold, and at the matched precision.
void AddMatchingRows(const StereoPairEvaluation& pair, const StereoRun& run,
                     const std::vector<double>& thresholds, StereoReport& report) {
  const Cell n = Int(run.target_count);
  for (const StereoMatching& m : run.matchings) {
    const StereoDetection& d = run.DetectionFor(m.method.detector);
    for (double t : thresholds) {
      const RegionScores s = ScoreAt(d, m, t);
      for (StereoRegion region : kStereoRegions) {
        const RegionCounts& c = s[static_cast<int>(region)];
        report.scores.AddRow({pair.name, n, m.method.Label(), Number(t), StereoRegionName(region),
                              Int(c.detected), Int(c.accepted), Int(c.correct), Percent(c.MScore()),
                              Percent(c.Precision()),
                              Percent(RegionCounts{s[kOverall].detected, 0, c.correct}.MScore())});
      }
    }
    const RegionScores all = ScoreAt(d, m, kInfinity);
    std::vector<Cell> row = {pair.name, n, m.method.Label(), Percent(run.target_precision)};
    if (run.target_precision) {
      const MatchedPrecision mp = ScoreAtPrecision(d, m, *run.target_precision);
      if (mp.point) {
        row.insert(row.end(), {mp.point->max_cost, Int(mp.point->accepted), Int(mp.point->correct),
                               Percent(mp.point->precision)});
      } else {
        row.insert(row.end(), 4, std::monostate{});
      }
      for (const RegionCounts& c : mp.scores) {
        row.push_back(mp.point ? Percent(c.MScore()) : Cell(std::monostate{}));
      }
    } else {
      row.insert(row.end(), 7, std::monostate{});
    }
    for (const RegionCounts& c : all) row.push_back(Percent(c.MScore()));
    row.push_back(Percent(all[kOverall].Precision()));
    report.matched_precision.AddRow(std::move(row));
  }
}

// Each detector's primary method at the paper's cost, beside the paper's numbers for this pair.
void AddPaperComparisonRows(const StereoPairEvaluation& pair, const StereoRun& run,
                            const std::optional<PaperStereoNumbers>& paper,
                            const StereoEvaluationOptions& options, StereoReport& report) {
  const Cell n = Int(run.target_count);
  for (const std::string& detector : DetectorNames()) {
    const StereoMatching* m = PrimaryMatching(run, detector);
    if (m == nullptr) continue;
    const StereoDetection& d = run.DetectionFor(detector);
    const RegionScores s = ScoreAt(d, *m, options.max_cost);
    const int di = DetectorIndex(detector);
    for (StereoRegion region : kStereoRegions) {
      const int r = static_cast<int>(region);
      report.paper_comparison.AddRow(
          {pair.name, n, detector, m->method.Label(), StereoRegionName(region),
           Percent(s[r].MScore()), paper ? Cell(paper->m_score_percent[r][di]) : Cell(),
           Int(s[r].correct), paper ? Cell(paper->resm[r][di]) : Cell(), Percent(s[r].Precision()),
           Percent(RegionCounts{s[kOverall].detected, 0, s[r].correct}.MScore()),
           Int(s[r].detected)});
    }
  }
}

}  // namespace

StereoReport BuildStereoReport(const std::vector<StereoPairEvaluation>& results,
                               const StereoEvaluationOptions& options) {
  StereoReport report;
  report.protocol = ProtocolTable(options);
  MakeEmptyTables(options, report);
  const std::vector<double> thresholds = ReportedThresholds(options);
  for (const StereoPairEvaluation& pair : results) {
    const auto& px = pair.pixel_counts;
    report.pairs.AddRow({pair.name, Int(pair.size.width), Int(pair.size.height), pair.resize_factor,
                         pair.disparity_scale, pair.max_gt_disparity, pair.gate_min_disparity,
                         pair.gate_max_disparity,
                         Int(px[static_cast<int>(StereoPixelClass::kBoundary)]),
                         Int(px[static_cast<int>(StereoPixelClass::kNonBoundary)]),
                         Int(px[static_cast<int>(StereoPixelClass::kOccluded)]),
                         Int(px[static_cast<int>(StereoPixelClass::kUnknownDisparity)]),
                         Int(pair.reference_count)});
    const auto paper = PaperStereoNumbersFor(pair.name);
    for (const StereoRun& run : pair.runs) {
      AddDetectionRows(pair, run, options, report);
      AddMatchingRows(pair, run, thresholds, report);
      AddPaperComparisonRows(pair, run, paper, options, report);
    }
  }
  return report;
}

namespace {

// "12.3" or "–".
std::string PercentText(const std::optional<double>& ratio) {
  if (!ratio) return "–";
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << 100.0 * *ratio;
  return out.str();
}

// The paper-layout view of one run: rows of measures, columns region x detector.
io::ReportTable PaperLayout(const StereoPairEvaluation& pair, const StereoRun& run,
                            const StereoEvaluationOptions& options) {
  static const char* kShort[] = {"CoMIC", "Har", "Hes", "MSER", "FAST"};
  static const char* kRegionShort[] = {"B", "NB", "O"};
  std::vector<std::string> columns = {"measure"};
  for (int r = 0; r < kNumStereoRegions; ++r) {
    for (int d = 0; d < 5; ++d) columns.push_back(std::string(kRegionShort[r]) + " " + kShort[d]);
  }
  io::ReportTable table(columns);
  for (size_t c = 1; c < columns.size(); ++c) table.SetPrecision(columns[c], 1);
  const auto paper = PaperStereoNumbersFor(pair.name);
  std::array<std::optional<RegionScores>, 5> ours;
  for (int d = 0; d < 5; ++d) {
    const StereoMatching* m = PrimaryMatching(run, PaperDetectors()[d]);
    if (m != nullptr) ours[d] = ScoreAt(run.DetectionFor(m->method.detector), *m, options.max_cost);
  }
  enum Measure { kM, kShare, kPrecision, kResM, kDetected };
  auto our_row = [&](const std::string& label, Measure measure) {
    std::vector<Cell> row = {label};
    for (int r = 0; r < kNumStereoRegions; ++r) {
      for (int d = 0; d < 5; ++d) {
        if (!ours[d]) {
          row.push_back(std::monostate{});
          continue;
        }
        const RegionCounts& c = (*ours[d])[r];
        switch (measure) {
          case kM:
            row.push_back(Percent(c.MScore()));
            break;
          case kShare:
            row.push_back(
                Percent(RegionCounts{(*ours[d])[kOverall].detected, 0, c.correct}.MScore()));
            break;
          case kPrecision:
            row.push_back(Percent(c.Precision()));
            break;
          case kResM:
            row.push_back(Int(c.correct));
            break;
          case kDetected:
            row.push_back(Int(c.detected));
            break;
        }
      }
    }
    table.AddRow(std::move(row));
  };
  auto paper_row = [&](const std::string& label, bool m_score) {
    std::vector<Cell> row = {label};
    for (int r = 0; r < kNumStereoRegions; ++r) {
      for (int d = 0; d < 5; ++d) {
        row.push_back(m_score ? paper->m_score_percent[r][d] : paper->resm[r][d]);
      }
    }
    table.AddRow(std::move(row));
  };
  our_row("M_score(1) % ours", kM);
  if (paper) paper_row("M_score % paper", true);
  our_row("share of all % ours", kShare);
  our_row("precision % ours", kPrecision);
  our_row("ResM_1 ours", kResM);
  if (paper) paper_row("ResM paper", false);
  our_row("detected ours", kDetected);
  return table;
}

io::ReportTable FixedThresholdView(const StereoRun& run, double max_cost) {
  io::ReportTable table({"method", "B M %", "B prec %", "B ResM", "B det", "NB M %", "NB prec %",
                         "NB ResM", "NB det", "O M %", "O prec %", "O ResM", "O det"});
  for (const std::string& c : table.columns()) {
    if (c.find('%') != std::string::npos) table.SetPrecision(c, 1);
  }
  for (const StereoMatching& m : run.matchings) {
    const RegionScores s = ScoreAt(run.DetectionFor(m.method.detector), m, max_cost);
    std::vector<Cell> row = {m.method.Label()};
    for (const RegionCounts& c : s) {
      row.insert(row.end(),
                 {Percent(c.MScore()), Percent(c.Precision()), Int(c.correct), Int(c.detected)});
    }
    table.AddRow(std::move(row));
  }
  return table;
}

io::ReportTable SensitivityView(const StereoRun& run, const std::vector<double>& thresholds) {
  std::vector<std::string> columns = {"method"};
  for (double t : thresholds) columns.push_back("T = " + Number(t));
  io::ReportTable table(columns);
  for (const StereoMatching& m : run.matchings) {
    const StereoDetection& d = run.DetectionFor(m.method.detector);
    std::vector<Cell> row = {m.method.Label()};
    for (double t : thresholds) {
      const RegionScores s = ScoreAt(d, m, t);
      row.push_back(PercentText(s[0].MScore()) + " / " + PercentText(s[1].MScore()) + " / " +
                    PercentText(s[2].MScore()) + " (" + PercentText(s[2].Precision()) + ")");
    }
    table.AddRow(std::move(row));
  }
  return table;
}

io::ReportTable MatchedPrecisionView(const StereoRun& run) {
  io::ReportTable table({"method", "T at target", "precision %", "accepted", "B M %", "NB M %",
                         "O M %", "T=inf B M %", "T=inf NB M %", "T=inf O M %", "T=inf prec %"});
  for (const std::string& c : table.columns()) {
    if (c.find('%') != std::string::npos) table.SetPrecision(c, 1);
  }
  table.SetPrecision("T at target", 1);
  for (const StereoMatching& m : run.matchings) {
    const StereoDetection& d = run.DetectionFor(m.method.detector);
    std::vector<Cell> row = {m.method.Label()};
    std::optional<MatchedPrecision> mp;
    if (run.target_precision) mp = ScoreAtPrecision(d, m, *run.target_precision);
    if (mp && mp->point) {
      row.insert(row.end(),
                 {mp->point->max_cost, Percent(mp->point->precision), Int(mp->point->accepted)});
      for (const RegionCounts& c : mp->scores) row.push_back(Percent(c.MScore()));
    } else {
      row.insert(row.end(), 6, std::monostate{});
    }
    const RegionScores all = ScoreAt(d, m, kInfinity);
    for (const RegionCounts& c : all) row.push_back(Percent(c.MScore()));
    row.push_back(Percent(all[kOverall].Precision()));
    table.AddRow(std::move(row));
  }
  return table;
}

io::ReportTable RepeatabilityView(const StereoRun& run, const StereoEvaluationOptions& options) {
  std::vector<std::string> columns = {"detector", "det B", "det NB"};
  for (double t : options.repeatability_tolerances) {
    for (const char* r : {"B", "NB", "O"}) columns.push_back(std::string(r) + " ≤" + Number(t));
  }
  io::ReportTable table(columns);
  for (size_t c = 3; c < columns.size(); ++c) table.SetPrecision(columns[c], 1);
  for (const StereoDetection& d : run.detections) {
    std::vector<Cell> row = {d.detector, Int(d.detected[0]), Int(d.detected[1])};
    for (size_t k = 0; k < options.repeatability_tolerances.size(); ++k) {
      for (int r = 0; r < kNumStereoRegions; ++r) {
        row.push_back(Percent(RegionCounts{d.detected[r], 0, d.repeatable[k][r]}.MScore()));
      }
    }
    table.AddRow(std::move(row));
  }
  return table;
}

io::ReportTable DetectionView(const StereoRun& run) {
  io::ReportTable table({"detector", "cut-off", "valid candidates", "left kept", "right kept",
                         "det B", "det NB", "excluded unknown", "excluded occluded"});
  table.SetPrecision("cut-off", 6);
  for (const StereoDetection& d : run.detections) {
    table.AddRow({d.detector, CutCell(d.cut), Int(d.cut.available),
                  Int(static_cast<int>(d.left.size())), Int(static_cast<int>(d.right.size())),
                  Int(d.detected[0]), Int(d.detected[1]), Int(d.unknown_disparity),
                  Int(d.occluded)});
  }
  return table;
}

}  // namespace

std::string StereoReportMarkdown(const StereoReport& report,
                                 const std::vector<StereoPairEvaluation>& results,
                                 const StereoEvaluationOptions& options) {
  std::ostringstream out;
  out << "# Middlebury stereo evaluation\n\n"
      << "Protocol of paper §5.2.2 (Tables 1 and 2, stereo rows) as set out in "
         "docs/stereo_evaluation.md. B = boundary (disc = 255), NB = non-boundary, O = overall; "
         "M = M_score(1) = correct / detected in the region; prec = correct / accepted; "
         "\"–\" = undefined (nothing detected or accepted).\n\n"
      << "## Protocol\n\n"
      << report.protocol.ToMarkdown() << "\n## Pairs\n\n"
      << report.pairs.ToMarkdown();
  const std::vector<double> thresholds = ReportedThresholds(options);
  for (const StereoPairEvaluation& pair : results) {
    for (const StereoRun& run : pair.runs) {
      out << "\n## " << RunTitle(pair, run) << "\n\n"
          << "### Paper layout at T = " << Number(options.max_cost) << " (CoMIC = "
          << (PrimaryMatching(run, "comic") ? PrimaryMatching(run, "comic")->method.Label() : "–")
          << ")\n\n"
          << PaperLayout(pair, run, options).ToMarkdown()
          << "\n### Every method at T = " << Number(options.max_cost) << "\n\n"
          << FixedThresholdView(run, options.max_cost).ToMarkdown()
          << "\n### Threshold sensitivity: M_score(1) % B / NB / O (overall precision %)\n\n"
          << SensitivityView(run, thresholds).ToMarkdown() << "\n### Matched precision (target "
          << PercentText(run.target_precision) << " %";
      if (options.target_precision <= 0) {
        out << " = " << options.precision_reference.Label()
            << " at T = " << Number(options.max_cost);
      }
      out << ") and every mutual-best match accepted (T = inf)\n\n"
          << MatchedPrecisionView(run).ToMarkdown()
          << "\n### Repeatability (% of valid left features with a right feature within the "
             "tolerance of their true position)\n\n"
          << RepeatabilityView(run, options).ToMarkdown() << "\n### Detections\n\n"
          << DetectionView(run).ToMarkdown();
    }
  }
  return out.str();
}

}  // namespace comic::frontend
