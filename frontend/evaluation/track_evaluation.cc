#include "frontend/evaluation/track_evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "frontend/evaluation/epipolar_check.h"
#include "io/core/error.h"
#include "io/image/image_sequence.h"

namespace comic::frontend {

void TrackEvaluationOptions::Check() const {
  COMIC_CHECK(!detectors.empty(), kInvalidArgument, "evaluation: no detector to evaluate");
  for (size_t i = 0; i < detectors.size(); ++i) {
    DetectorOptions named = detector_options;
    named.name = detectors[i];
    named.Check();  // unknown names and bad detector options
    for (size_t j = 0; j < i; ++j) {
      COMIC_CHECK(detectors[j] != detectors[i], kInvalidArgument,
                  "evaluation: detector '" << detectors[i] << "' listed twice");
    }
  }
  const bool has_comic = std::find(detectors.begin(), detectors.end(), "comic") != detectors.end();
  const bool has_comic_paper =
      std::find(detectors.begin(), detectors.end(), "comic-paper") != detectors.end();
  COMIC_CHECK(!(has_comic || has_comic_paper) || !comic_costs.empty(), kInvalidArgument,
              "evaluation: no matcher for CoMIC's features");
  const bool has_baseline =
      std::any_of(detectors.begin(), detectors.end(),
                  [](const std::string& d) { return d != "comic" && d != "comic-paper"; });
  COMIC_CHECK(!has_baseline || !baseline_costs.empty(), kInvalidArgument,
              "evaluation: no matcher for the baselines' features");
  for (const auto* costs : {&comic_costs, &baseline_costs}) {
    for (size_t i = 0; i < costs->size(); ++i) {
      for (size_t j = 0; j < i; ++j) {
        COMIC_CHECK((*costs)[i] != (*costs)[j], kInvalidArgument,
                    "evaluation: matcher '" << MatchCostName((*costs)[i]) << "' listed twice");
      }
    }
  }
  COMIC_CHECK(num_features >= 0, kInvalidArgument,
              "evaluation: num_features must be >= 0 (0 = CoMIC's count), got " << num_features);
  COMIC_CHECK(num_features > 0 || has_comic, kInvalidArgument,
              "evaluation: without CoMIC among the detectors, give the feature count N "
              "(num_features) to equalise to");
  matcher.Check();
  COMIC_CHECK(matcher.gate == CandidateGate::kRadius, kInvalidArgument,
              "evaluation: the matcher must use the radius gate");
  COMIC_CHECK(!ns.empty(), kInvalidArgument, "evaluation: no n to evaluate");
  for (int n : ns) COMIC_CHECK(n >= 1, kInvalidArgument, "evaluation: n must be >= 1, got " << n);
  COMIC_CHECK(frame_step >= 1, kInvalidArgument,
              "evaluation: frame_step must be >= 1, got " << frame_step);
  COMIC_CHECK(boundary_band > 0, kInvalidArgument,
              "evaluation: boundary_band must be > 0 px, got " << boundary_band);
  COMIC_CHECK(epipolar_tolerance > 0, kInvalidArgument,
              "evaluation: epipolar_tolerance must be > 0 px, got " << epipolar_tolerance);
  COMIC_CHECK(target_precision > 0 && target_precision <= 1, kInvalidArgument,
              "evaluation: target_precision must be in (0, 1], got " << target_precision);
  for (double t : sweep_costs) {
    COMIC_CHECK(t >= 0 && !std::isnan(t), kInvalidArgument,
                "evaluation: sweep thresholds must be >= 0, got " << t);
  }
}

namespace {

// Both CoMIC searches ("comic", "comic-paper") fill side masks and are matched by comic_costs.
bool IsComic(const std::string& detector) {
  return detector == "comic" || detector == "comic-paper";
}

std::string RowLabel(const std::string& detector, MatchCost cost) {
  return IsComic(detector) || cost != MatchCost::kFullPatch ? detector + "/" + MatchCostName(cost)
                                                            : detector;
}

// The labels of frame `frame`'s region at the evaluated size, or an empty Mat without regions.
cv::Mat FrameLabels(const RegionMaskSource& regions, size_t frame, const cv::Size& size,
                    double band) {
  if (!regions) return cv::Mat();
  const cv::Mat mask = regions(frame);
  COMIC_CHECK(!mask.empty() && mask.type() == CV_8UC1 && mask.size() == size, kInvalidData,
              "region mask of frame " << frame << " is " << mask.cols << "x" << mask.rows
                                      << ", expected an 8-bit mask of " << size.width << "x"
                                      << size.height);
  return LabelRegion(mask, band);
}

PrecisionSummary SummarisePrecision(const EvaluationRow& row, const EpipolarGroundTruth& truth,
                                    const TrackEvaluationOptions& options) {
  const FeatureTracks& tracks = row.tracking.tracks;
  std::vector<PatchMatch> all;
  std::vector<bool> correct;
  for (size_t p = 0; p + 1 < tracks.NumFrames(); ++p) {
    const cv::Matx33d F =
        FundamentalFromPoses(truth.K, truth.world_from_camera[p], truth.world_from_camera[p + 1]);
    const auto& mutual = row.tracking.mutual_matches[p];
    const std::vector<bool> ok = EpipolarConsistency(F, tracks.features[p], tracks.features[p + 1],
                                                     mutual, options.epipolar_tolerance);
    all.insert(all.end(), mutual.begin(), mutual.end());
    correct.insert(correct.end(), ok.begin(), ok.end());
  }
  PrecisionSummary summary;
  summary.at_threshold = PrecisionAt(all, correct, options.matcher.max_cost);
  summary.all_mutual = PrecisionAt(all, correct, std::numeric_limits<double>::infinity());
  summary.at_target = ThresholdForPrecision(all, correct, options.target_precision);
  if (summary.at_target) {
    const FeatureTracks rethresholded =
        TracksAtThreshold(row.tracking, summary.at_target->max_cost);
    for (int n : options.ns) {
      summary.scores_at_target.push_back(
          ComputeMatchingScores(rethresholded, row.labels, {n, options.frame_step}));
    }
  }
  return summary;
}

// Precision of `row`'s k_p cheapest mutual-best matches in every frame pair p, k_p = the number
// `reference` accepts there at T.
PrecisionPoint PrecisionAtReferenceCount(const EvaluationRow& row, const EvaluationRow& reference,
                                         const EpipolarGroundTruth& truth,
                                         const TrackEvaluationOptions& options) {
  const FeatureTracks& tracks = row.tracking.tracks;
  PrecisionPoint point;
  point.max_cost = std::numeric_limits<double>::quiet_NaN();  // a count per pair, not one T
  for (size_t p = 0; p + 1 < tracks.NumFrames(); ++p) {
    const size_t k =
        ApplyCostThreshold(reference.tracking.mutual_matches[p], options.matcher.max_cost).size();
    std::vector<PatchMatch> cheapest = row.tracking.mutual_matches[p];
    std::stable_sort(cheapest.begin(), cheapest.end(),
                     [](const PatchMatch& a, const PatchMatch& b) { return a.cost < b.cost; });
    cheapest.resize(std::min(k, cheapest.size()));
    const cv::Matx33d F =
        FundamentalFromPoses(truth.K, truth.world_from_camera[p], truth.world_from_camera[p + 1]);
    const std::vector<bool> ok = EpipolarConsistency(F, tracks.features[p], tracks.features[p + 1],
                                                     cheapest, options.epipolar_tolerance);
    point.accepted += static_cast<int>(cheapest.size());
    point.correct += static_cast<int>(std::count(ok.begin(), ok.end(), true));
  }
  point.precision = point.accepted > 0 ? static_cast<double>(point.correct) / point.accepted : 0.0;
  return point;
}

size_t IndexOfN(const TrackEvaluation& evaluation, int n) {
  const auto& ns = evaluation.options.ns;
  const auto it = std::find(ns.begin(), ns.end(), n);
  COMIC_CHECK(it != ns.end(), kInvalidArgument, "n = " << n << " was not evaluated");
  return static_cast<size_t>(it - ns.begin());
}

std::string CutText(const ThresholdCut& cut) {
  if (cut.min_response == -std::numeric_limits<float>::max()) return "all";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", cut.min_response);
  return buffer;
}

double Percent(double ratio) { return 100.0 * ratio; }

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json RegionScoreJson(const RegionScore& score) {
  return {{"mean_m_score", NumberOrNull(score.mean_m_score)},
          {"pooled_m_score", NumberOrNull(score.pooled_m_score)},
          {"mean_res_m", score.mean_res_m},
          {"mean_detections", score.mean_detections},
          {"scored_frames", score.scored_frames}};
}

nlohmann::json ScoresJson(const MatchingScores& scores) {
  nlohmann::json samples = nlohmann::json::array();
  for (const MatchingScoreSample& s : scores.samples) {
    samples.push_back({{"start_frame", s.start_frame},
                       {"detections", {s.detections[0], s.detections[1], s.detections[2]}},
                       {"residual", {s.residual[0], s.residual[1], s.residual[2]}}});
  }
  return {{"n", scores.n},
          {"boundary", RegionScoreJson(scores.boundary)},
          {"non_boundary", RegionScoreJson(scores.non_boundary)},
          {"overall", RegionScoreJson(scores.overall)},
          {"samples (detections/residual: boundary, non-boundary, overall)", samples}};
}

nlohmann::json PrecisionPointJson(const PrecisionPoint& point) {
  return {{"max_cost", NumberOrNull(point.max_cost)},
          {"accepted", point.accepted},
          {"correct", point.correct},
          {"precision", point.precision}};
}

// Frame 0 as every detector sees it: the reference count N and each detector's cut-off are set on
// it, and the tracking loop reuses it rather than reading and detecting it twice.
struct FirstFrame {
  io::Frame frame;
  cv::Mat labels;
  cv::Mat region;                      // empty without region masks
  std::vector<FeatureSet> detections;  // one per detector, in options.detectors order
};

void CheckEvaluationInputs(size_t num_frames,
                           const std::optional<EpipolarGroundTruth>& ground_truth,
                           const TrackEvaluationOptions& options) {
  options.Check();
  for (int n : options.ns) {
    COMIC_CHECK(
        static_cast<size_t>(n) < num_frames, kInvalidArgument,
        "n = " << n << " needs at least " << n + 1 << " frames, the sequence has " << num_frames);
  }
  COMIC_CHECK(!ground_truth || ground_truth->world_from_camera.size() == num_frames,
              kInvalidArgument,
              "ground truth has " << (ground_truth ? ground_truth->world_from_camera.size() : 0)
                                  << " poses for " << num_frames << " frames");
}

std::vector<std::unique_ptr<Detector>> MakeDetectors(const TrackEvaluationOptions& options) {
  std::vector<std::unique_ptr<Detector>> detectors;
  for (const std::string& name : options.detectors) {
    DetectorOptions named = options.detector_options;
    named.name = name;
    detectors.push_back(MakeDetector(named));
  }
  return detectors;
}

FirstFrame DetectFirstFrame(const io::ImageSequence& sequence, const RegionMaskSource& regions,
                            const TrackEvaluationOptions& options,
                            const std::vector<std::unique_ptr<Detector>>& detectors) {
  FirstFrame first;
  first.frame = sequence.ReadFrame(0);
  first.labels = FrameLabels(regions, 0, sequence.FrameSize(), options.boundary_band);
  first.region = regions ? EvaluatedRegionMask(first.labels) : cv::Mat();
  for (const auto& detector : detectors) {
    first.detections.push_back(detector->Detect(first.frame.gray));
  }
  return first;
}

// The count N every detector is cut to: the requested one, or CoMIC's count on frame 0.
void SetReferenceCount(const FirstFrame& first, const cv::Size& size,
                       const TrackEvaluationOptions& options, TrackEvaluation& evaluation) {
  int reference = options.num_features;
  evaluation.reference_source = "requested";
  if (reference == 0) {
    const size_t comic =
        static_cast<size_t>(std::find(options.detectors.begin(), options.detectors.end(), "comic") -
                            options.detectors.begin());
    reference = CountCountedFeatures(first.detections[comic], size, first.region);
    evaluation.reference_source = "comic";
    COMIC_CHECK(reference > 0, kInvalidArgument,
                "CoMIC found no feature in the object region of frame 0, so there is no count to "
                "equalise to; give the count N explicitly (num_features)");
  }
  evaluation.reference_count = reference;
}

// Each detector's response cut-off that keeps the reference count on frame 0.
std::vector<ThresholdCut> EqualiseCuts(const FirstFrame& first, int reference, const cv::Size& size,
                                       const TrackEvaluationOptions& options) {
  std::vector<ThresholdCut> cuts;
  for (size_t d = 0; d < first.detections.size(); ++d) {
    if (options.detectors[d] == "comic" && options.num_features == 0) {
      // CoMIC sets N at its own threshold: it keeps everything it returns.
      ThresholdCut cut;
      cut.target = reference;
      cut.available = reference;
      cut.count = reference;
      cut.reached = true;
      cuts.push_back(cut);
    } else {
      cuts.push_back(EqualiseThreshold(first.detections[d], reference, size, first.region));
    }
  }
  return cuts;
}

// One row and one tracker per (detector, cost); returns each detector's row indices, since rows of
// one detector share its detections.
std::vector<std::vector<size_t>> AddRows(const TrackEvaluationOptions& options,
                                         const std::vector<ThresholdCut>& cuts,
                                         TrackEvaluation& evaluation,
                                         std::vector<Tracker>& trackers) {
  std::vector<std::vector<size_t>> rows_of_detector(cuts.size());
  for (size_t d = 0; d < cuts.size(); ++d) {
    const std::vector<MatchCost>& costs =
        IsComic(options.detectors[d]) ? options.comic_costs : options.baseline_costs;
    for (MatchCost cost : costs) {
      EvaluationRow row;
      row.detector = options.detectors[d];
      row.cost = cost;
      row.label = RowLabel(row.detector, cost);
      row.cut = cuts[d];
      rows_of_detector[d].push_back(evaluation.rows.size());
      evaluation.rows.push_back(std::move(row));
      TrackerOptions tracker_options;
      tracker_options.matcher = options.matcher;
      tracker_options.matcher.cost = cost;
      tracker_options.min_response = cuts[d].min_response;
      trackers.emplace_back(tracker_options, options.detectors[d]);
    }
  }
  return rows_of_detector;
}

void TrackAllFrames(const io::ImageSequence& sequence, const RegionMaskSource& regions,
                    const TrackEvaluationOptions& options, const EvaluationProgress& progress,
                    const std::vector<std::unique_ptr<Detector>>& detectors,
                    const FirstFrame& first, const std::vector<ThresholdCut>& cuts,
                    const std::vector<std::vector<size_t>>& rows_of_detector,
                    TrackEvaluation& evaluation, std::vector<Tracker>& trackers) {
  const size_t num_frames = sequence.NumFrames();
  const cv::Size size = sequence.FrameSize();
  for (size_t i = 0; i < num_frames; ++i) {
    const io::Frame frame = i == 0 ? first.frame : sequence.ReadFrame(i);
    const cv::Mat labels =
        i == 0 ? first.labels : FrameLabels(regions, i, size, options.boundary_band);
    for (size_t d = 0; d < detectors.size(); ++d) {
      TrackerOptions cut_options;
      cut_options.min_response = cuts[d].min_response;
      FeatureSet features = SelectTrackableFeatures(
          i == 0 ? first.detections[d] : detectors[d]->Detect(frame.gray), size, cut_options);
      const std::vector<RegionLabel> feature_labels =
          regions ? LabelFeatures(labels, features) : std::vector<RegionLabel>();
      for (size_t r : rows_of_detector[d]) {
        if (regions) evaluation.rows[r].labels.push_back(feature_labels);
        trackers[r].AddFrame(frame.gray, features, frame.name);
      }
    }
    if (progress) progress(i + 1, num_frames);
  }
}

// Matching scores at each n (and at each swept cost) and, with ground truth, precision.
void ScoreRows(const std::optional<EpipolarGroundTruth>& ground_truth,
               const TrackEvaluationOptions& options, std::vector<Tracker>& trackers,
               TrackEvaluation& evaluation) {
  for (size_t r = 0; r < evaluation.rows.size(); ++r) {
    EvaluationRow& row = evaluation.rows[r];
    row.tracking = trackers[r].Result();
    for (int n : options.ns) {
      row.scores.push_back(
          ComputeMatchingScores(row.tracking.tracks, row.labels, {n, options.frame_step}));
    }
    for (double t : options.sweep_costs) {
      const FeatureTracks rethresholded = TracksAtThreshold(row.tracking, t);
      std::vector<MatchingScores> at_t;
      for (int n : options.ns) {
        at_t.push_back(ComputeMatchingScores(rethresholded, row.labels, {n, options.frame_step}));
      }
      row.sweep.push_back(std::move(at_t));
    }
    if (ground_truth) row.precision = SummarisePrecision(row, *ground_truth, options);
  }
  if (ground_truth) {
    for (EvaluationRow& row : evaluation.rows) {
      if (row.cost == MatchCost::kFullPatch) continue;
      for (const EvaluationRow& reference : evaluation.rows) {
        if (reference.detector != row.detector || reference.cost != MatchCost::kFullPatch) continue;
        row.precision->reference_label = reference.label;
        row.precision->at_reference_count =
            PrecisionAtReferenceCount(row, reference, *ground_truth, options);
      }
    }
  }
}

}  // namespace

TrackEvaluation EvaluateTracking(const io::ImageSequence& sequence, const RegionMaskSource& regions,
                                 const std::optional<EpipolarGroundTruth>& ground_truth,
                                 const TrackEvaluationOptions& options,
                                 const EvaluationProgress& progress) {
  const size_t num_frames = sequence.NumFrames();
  CheckEvaluationInputs(num_frames, ground_truth, options);
  TrackEvaluation evaluation;
  evaluation.options = options;
  evaluation.num_frames = num_frames;
  evaluation.frame_size = sequence.FrameSize();
  evaluation.frame_names = sequence.FrameNames();
  evaluation.has_regions = static_cast<bool>(regions);
  const std::vector<std::unique_ptr<Detector>> detectors = MakeDetectors(options);
  const FirstFrame first = DetectFirstFrame(sequence, regions, options, detectors);
  SetReferenceCount(first, sequence.FrameSize(), options, evaluation);
  const std::vector<ThresholdCut> cuts =
      EqualiseCuts(first, evaluation.reference_count, sequence.FrameSize(), options);
  std::vector<Tracker> trackers;
  const std::vector<std::vector<size_t>> rows_of_detector =
      AddRows(options, cuts, evaluation, trackers);
  TrackAllFrames(sequence, regions, options, progress, detectors, first, cuts, rows_of_detector,
                 evaluation, trackers);
  ScoreRows(ground_truth, options, trackers, evaluation);
  return evaluation;
}

io::ReportTable ScoreTable(const TrackEvaluation& evaluation, int n) {
  const size_t k = IndexOfN(evaluation, n);
  const std::string ms = "M_score(" + std::to_string(n) + ") % ";
  const std::string res = "ResM_" + std::to_string(n) + " ";
  io::ReportTable table({"detector", "cut-off", "N_0", ms + "boundary", ms + "non-boundary",
                         ms + "overall", res + "boundary", res + "non-boundary", res + "overall"});
  for (const char* region : {"boundary", "non-boundary", "overall"}) {
    table.SetPrecision(ms + region, 1);
    table.SetPrecision(res + region, 1);
  }
  for (const EvaluationRow& row : evaluation.rows) {
    const MatchingScores& s = row.scores[k];
    // Boundary and non-boundary exist only with an object region.
    const auto regional = [&](double value) {
      return evaluation.has_regions ? io::ReportTable::Cell(value) : io::ReportTable::Cell();
    };
    table.AddRow({row.label, CutText(row.cut), int64_t{row.cut.count},
                  regional(Percent(s.boundary.mean_m_score)),
                  regional(Percent(s.non_boundary.mean_m_score)), Percent(s.overall.mean_m_score),
                  regional(s.boundary.mean_res_m), regional(s.non_boundary.mean_res_m),
                  s.overall.mean_res_m});
  }
  return table;
}

io::ReportTable PrecisionTable(const TrackEvaluation& evaluation, int n) {
  const size_t k = IndexOfN(evaluation, n);
  char target[64];
  std::snprintf(target, sizeof(target), "@%.0f%%", 100.0 * evaluation.options.target_precision);
  const std::string at_target = target;
  const std::string ns = std::to_string(n);
  io::ReportTable table({"detector", "matches/pair @T", "precision @T %", "mutual/pair",
                         "precision all %", "T " + at_target, "matches/pair " + at_target,
                         "M_score(" + ns + ") % @T", "M_score(" + ns + ") % " + at_target,
                         "ResM_" + ns + " @T", "ResM_" + ns + " " + at_target});
  for (const std::string& column :
       {std::string("matches/pair @T"), std::string("precision @T %"), std::string("mutual/pair"),
        std::string("precision all %"), "T " + at_target, "matches/pair " + at_target,
        "M_score(" + ns + ") % @T", "M_score(" + ns + ") % " + at_target, "ResM_" + ns + " @T",
        "ResM_" + ns + " " + at_target}) {
    table.SetPrecision(column, 1);
  }
  const double pairs = evaluation.num_frames > 1 ? evaluation.num_frames - 1.0 : 1.0;
  for (const EvaluationRow& row : evaluation.rows) {
    COMIC_CHECK(row.precision.has_value(), kInvalidArgument,
                "precision table: the evaluation had no epipolar ground truth");
    const PrecisionSummary& p = *row.precision;
    io::ReportTable::Cell t_target, matches_target, score_target, res_target;
    if (p.at_target) {
      t_target = p.at_target->max_cost;
      matches_target = p.at_target->accepted / pairs;
      score_target = Percent(p.scores_at_target[k].overall.mean_m_score);
      res_target = p.scores_at_target[k].overall.mean_res_m;
    }
    table.AddRow({row.label, p.at_threshold.accepted / pairs, Percent(p.at_threshold.precision),
                  p.all_mutual.accepted / pairs, Percent(p.all_mutual.precision), t_target,
                  matches_target, Percent(row.scores[k].overall.mean_m_score), score_target,
                  row.scores[k].overall.mean_res_m, res_target});
  }
  return table;
}

io::ReportTable EqualCountPrecisionTable(const TrackEvaluation& evaluation) {
  io::ReportTable table(
      {"detector", "reference", "matches/pair", "precision %", "reference precision @T %"});
  for (const char* column : {"matches/pair", "precision %", "reference precision @T %"}) {
    table.SetPrecision(column, 1);
  }
  const double pairs = evaluation.num_frames > 1 ? evaluation.num_frames - 1.0 : 1.0;
  for (const EvaluationRow& row : evaluation.rows) {
    COMIC_CHECK(row.precision.has_value(), kInvalidArgument,
                "equal-count table: the evaluation had no epipolar ground truth");
    if (!row.precision->at_reference_count) continue;
    const PrecisionPoint& at = *row.precision->at_reference_count;
    for (const EvaluationRow& reference : evaluation.rows) {
      if (reference.label != row.precision->reference_label) continue;
      table.AddRow({row.label, reference.label, at.accepted / pairs, Percent(at.precision),
                    Percent(reference.precision->at_threshold.precision)});
    }
  }
  return table;
}

io::ReportTable ThresholdSweepTable(const TrackEvaluation& evaluation, int n) {
  const size_t k = IndexOfN(evaluation, n);
  const std::string ms = "M_score(" + std::to_string(n) + ") % ";
  const std::string res = "ResM_" + std::to_string(n) + " ";
  io::ReportTable table({"detector", "T", ms + "boundary", ms + "non-boundary", ms + "overall",
                         res + "boundary", res + "non-boundary", res + "overall"});
  for (const char* region : {"boundary", "non-boundary", "overall"}) {
    table.SetPrecision(ms + region, 1);
    table.SetPrecision(res + region, 1);
  }
  table.SetPrecision("T", 0);
  for (const EvaluationRow& row : evaluation.rows) {
    for (size_t t = 0; t < evaluation.options.sweep_costs.size(); ++t) {
      const MatchingScores& s = row.sweep[t][k];
      const auto regional = [&](double value) {
        return evaluation.has_regions ? io::ReportTable::Cell(value) : io::ReportTable::Cell();
      };
      table.AddRow({row.label, evaluation.options.sweep_costs[t],
                    regional(Percent(s.boundary.mean_m_score)),
                    regional(Percent(s.non_boundary.mean_m_score)), Percent(s.overall.mean_m_score),
                    regional(s.boundary.mean_res_m), regional(s.non_boundary.mean_res_m),
                    s.overall.mean_res_m});
    }
  }
  return table;
}

nlohmann::json EvaluationToJson(const TrackEvaluation& evaluation) {
  const TrackEvaluationOptions& o = evaluation.options;
  nlohmann::json costs = nlohmann::json::array();
  for (MatchCost cost : o.comic_costs) costs.push_back(MatchCostName(cost));
  std::vector<std::string> baseline_costs;
  for (MatchCost cost : o.baseline_costs) baseline_costs.push_back(MatchCostName(cost));
  nlohmann::json json = {
      {"frames", evaluation.num_frames},
      {"frame_size", {evaluation.frame_size.width, evaluation.frame_size.height}},
      {"first_frame", evaluation.frame_names.empty() ? "" : evaluation.frame_names.front()},
      {"has_regions", evaluation.has_regions},
      {"reference_count", evaluation.reference_count},
      {"reference_source", evaluation.reference_source},
      {"options",
       {{"detectors", o.detectors},
        {"comic_costs", costs},
        {"baseline_costs", baseline_costs},
        {"num_features", o.num_features},
        {"radius_px", o.matcher.radius},
        {"max_cost", o.matcher.max_cost},
        {"min_side_overlap", o.matcher.min_side_overlap},
        {"ns", o.ns},
        {"frame_step", o.frame_step},
        {"boundary_band_px", o.boundary_band},
        {"epipolar_tolerance_px", o.epipolar_tolerance},
        {"target_precision", o.target_precision},
        {"sweep_costs",
         [&] {
           nlohmann::json costs = nlohmann::json::array();
           for (double t : o.sweep_costs) costs.push_back(NumberOrNull(t));
           return costs;
         }()}}},
  };
  nlohmann::json rows = nlohmann::json::array();
  for (const EvaluationRow& row : evaluation.rows) {
    size_t features = 0, tracks = row.tracking.tracks.tracks.size();
    for (const FeatureSet& f : row.tracking.tracks.features) features += f.size();
    nlohmann::json scores = nlohmann::json::array();
    for (const MatchingScores& s : row.scores) scores.push_back(ScoresJson(s));
    nlohmann::json sweep = nlohmann::json::array();
    for (size_t t = 0; t < row.sweep.size(); ++t) {
      nlohmann::json at_t = nlohmann::json::array();
      for (const MatchingScores& s : row.sweep[t]) at_t.push_back(ScoresJson(s));
      sweep.push_back({{"max_cost", NumberOrNull(o.sweep_costs[t])}, {"scores", at_t}});
    }
    nlohmann::json entry = {
        {"label", row.label},
        {"detector", row.detector},
        {"matcher", MatchCostName(row.cost)},
        {"cut",
         {{"min_response", row.cut.min_response == -std::numeric_limits<float>::max()
                               ? nlohmann::json(nullptr)
                               : nlohmann::json(row.cut.min_response)},
          {"target", row.cut.target},
          {"available", row.cut.available},
          {"count", row.cut.count},
          {"reached", row.cut.reached}}},
        {"features_per_frame", static_cast<double>(features) / evaluation.num_frames},
        {"tracks", tracks},
        {"scores", scores},
        {"threshold_sweep", sweep},
    };
    if (row.precision) {
      const PrecisionSummary& p = *row.precision;
      nlohmann::json at_target_scores = nlohmann::json::array();
      for (const MatchingScores& s : p.scores_at_target) at_target_scores.push_back(ScoresJson(s));
      entry["precision"] = {
          {"at_threshold", PrecisionPointJson(p.at_threshold)},
          {"all_mutual", PrecisionPointJson(p.all_mutual)},
          {"at_target", p.at_target ? PrecisionPointJson(*p.at_target) : nlohmann::json(nullptr)},
          {"scores_at_target", at_target_scores}};
      if (p.at_reference_count) {
        entry["precision"]["at_reference_count"] = PrecisionPointJson(*p.at_reference_count);
        entry["precision"]["reference"] = p.reference_label;
      }
    }
    rows.push_back(entry);
  }
  json["rows"] = rows;
  return json;
}

}  // namespace comic::frontend
