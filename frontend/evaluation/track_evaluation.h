// The paper's tracking comparison (§5.1, Tables 1–3) on one sequence: every detector under the
// same protocol — threshold equalisation on the object in the first frame, detection on every
// frame, frame-to-frame patch matching within r = 20 px at one SSD threshold, tracks, ResM and
// M_score for n = 1 and n = 5 split into boundary / non-boundary / overall — plus, where ground
// truth poses exist (KITTI), the epipolar precision of the frame-to-frame matches and the scores
// at equal precision.
//
//   TrackEvaluationOptions options;                       // paper defaults
//   TrackEvaluation evaluation = EvaluateTracking(sequence, region_masks, std::nullopt, options,
//                                                 progress);
//   io::ReportTable table = ScoreTable(evaluation, 5);    // Table 1/2 layout
//
// Rows. Every detector is one row with the full-patch matcher, except CoMIC, which has one row
// per entry of comic_costs: "comic/split" (Algorithm 2, the paper's matcher), "comic/like-sides"
// and "comic/full" (CoMIC points, baseline matcher: separates the detector's contribution from
// the matcher's). The other detectors have one row per entry of baseline_costs ("harris" for the
// full patch, "harris/calibrated" for issue 15's side-aware cost on Harris's points, ...).
//
// Threshold equalisation (threshold_equalisation.h). N is options.num_features, or, when that is
// 0, the number of CoMIC features (at CoMIC's own options, every candidate by default) in the
// object region of frame 0. Each other detector's response cut-off is chosen to give N features
// there and then used on every frame. "Object region" = the pixels labelled boundary or interior
// (region_labels.h: the region grown by the boundary band); without a region, the whole frame.
// Features whose 23x23 patch does not fit are never counted or matched.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "frontend/detector_factory.h"
#include "frontend/evaluation/match_precision.h"
#include "frontend/evaluation/matching_evaluation.h"
#include "frontend/evaluation/threshold_equalisation.h"
#include "frontend/matching/tracker.h"
#include "io/report/report_table.h"

namespace comic::io {
class ImageSequence;
}

namespace comic::frontend {

struct TrackEvaluationOptions {
  // Detectors to compare, in row order (names of DetectorNames()).
  std::vector<std::string> detectors = {"comic",   "comic-paper", "harris",
                                        "hessian", "mser",        "fast"};
  // Options of every detector (DetectorOptions::name is ignored).
  DetectorOptions detector_options;
  // Matchers evaluated on CoMIC's features, one row each (see above).
  std::vector<MatchCost> comic_costs = {MatchCost::kSplitMinOfFourPairings,
                                        MatchCost::kSplitLikeSides, MatchCost::kFullPatch};
  // Matchers evaluated on every other detector's features, one row each (see above).
  std::vector<MatchCost> baseline_costs = {MatchCost::kFullPatch};
  // N, the feature count every detector is equalised to in frame 0's object region; 0 = CoMIC's
  // count (then "comic" must be among the detectors).
  int num_features = 0;
  // Gate radius r (paper §4: 20 px), SSD threshold T (mean squared difference) and minimum side
  // overlap; the cost mode is set per row. The radius gate is required.
  PatchMatcherOptions matcher;
  // The n of ResM_{i,n} / M_score(i, n), each evaluated (paper: 5; 1 for stereo).
  std::vector<int> ns = {1, 5};
  // Start frames i − n every frame_step frames (paper: 5).
  int frame_step = 5;
  // Width in pixels of the boundary band on either side of the region's edge (region_labels.h).
  double boundary_band = 11.0;
  // Epipolar ground truth only: a match is consistent within this distance (pixels) of the
  // epipolar line, and matchers are also compared at this precision (0–1).
  double epipolar_tolerance = 1.0;
  double target_precision = 0.85;
  // SSD thresholds at which every row is also scored (tracks rebuilt from the stored mutual-best
  // matches, no re-matching): how the comparison depends on T, which the paper does not give.
  // +infinity = every mutual-best match accepted.
  std::vector<double> sweep_costs = {100, 200,  400,
                                     800, 1600, std::numeric_limits<double>::infinity()};

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// Camera ground truth of the frames as evaluated: K at the evaluated frame size (ScaleIntrinsics
// when frames are resized) and one camera-to-world pose per frame of the sequence.
struct EpipolarGroundTruth {
  cv::Matx33d K;
  std::vector<cv::Matx34d> world_from_camera;
};

// A CV_8UC1 object mask (non-zero = object) of frame `frame` at the evaluated frame size.
using RegionMaskSource = std::function<cv::Mat(size_t frame)>;

// Progress: (frames processed, total frames).
using EvaluationProgress = std::function<void(size_t frames_done, size_t num_frames)>;

// Epipolar precision of one row's frame-to-frame matches over all frame pairs.
struct PrecisionSummary {
  PrecisionPoint at_threshold;  // the mutual-best matches with cost <= T (what the tracks use)
  PrecisionPoint all_mutual;    // every mutual-best match (T = infinity)
  std::optional<PrecisionPoint> at_target;       // the largest T reaching target_precision
  std::vector<MatchingScores> scores_at_target;  // per n, tracks rebuilt at that T
  // Rows other than the full patch: the same detector's full-patch row accepts k_p matches in
  // frame pair p at T; this row's k_p cheapest mutual-best matches of each pair (ties by index1),
  // so two matchers are compared at equal numbers of accepted matches (issue 15).
  std::optional<PrecisionPoint> at_reference_count;
  std::string reference_label;  // the full-patch row, e.g. "comic/full", "harris"
};

struct EvaluationRow {
  std::string label;     // "comic/split", "harris", ...
  std::string detector;  // "comic", "harris", ...
  MatchCost cost = MatchCost::kFullPatch;
  ThresholdCut cut;                              // the response cut-off and its frame-0 count
  TrackingResult tracking;                       // features (after the cut), matches and tracks
  std::vector<std::vector<RegionLabel>> labels;  // per frame and feature; empty without regions
  std::vector<MatchingScores> scores;            // per options.ns
  // sweep[t][k]: the scores at options.sweep_costs[t] for options.ns[k].
  std::vector<std::vector<MatchingScores>> sweep;
  std::optional<PrecisionSummary> precision;  // with epipolar ground truth only
};

struct TrackEvaluation {
  TrackEvaluationOptions options;
  size_t num_frames = 0;
  cv::Size frame_size;
  std::vector<std::string> frame_names;
  bool has_regions = false;
  int reference_count = 0;       // N
  std::string reference_source;  // "comic" or "requested"
  std::vector<EvaluationRow> rows;
};

// Runs the comparison on `sequence` (frames as opened, e.g. resized to height 700). `regions` may
// be empty (no object region: every feature is "overall"). Throws comic::Error: kInvalidArgument
// for bad options, an n not smaller than the number of frames, fewer poses than frames, or a
// CoMIC reference count of 0 (asking for num_features); kInvalidData for a region mask of the
// wrong size or type.
TrackEvaluation EvaluateTracking(const io::ImageSequence& sequence, const RegionMaskSource& regions,
                                 const std::optional<EpipolarGroundTruth>& ground_truth,
                                 const TrackEvaluationOptions& options,
                                 const EvaluationProgress& progress = {});

// The paper's Table 1/2 layout for one n (which must be in options.ns): per row the cut-off, the
// frame-0 count N_0, M_score(n) in % and ResM_n, each for boundary / non-boundary / overall.
io::ReportTable ScoreTable(const TrackEvaluation& evaluation, int n);

// Epipolar precision per row (needs ground truth): matches per frame pair and precision at T,
// for every mutual-best match, and at the target precision with M_score(n) / ResM_n there.
io::ReportTable PrecisionTable(const TrackEvaluation& evaluation, int n);

// Epipolar precision at equal numbers of accepted matches per frame pair (needs ground truth): one
// line per row that has a full-patch row of the same detector, with that row's precision at T.
io::ReportTable EqualCountPrecisionTable(const TrackEvaluation& evaluation);

// M_score(n) and ResM_n per row at every threshold of options.sweep_costs: one line per row and
// threshold.
io::ReportTable ThresholdSweepTable(const TrackEvaluation& evaluation, int n);

// Everything as JSON: options, N, per row the cut-off, per-n scores with every start frame's
// counts, and precision.
nlohmann::json EvaluationToJson(const TrackEvaluation& evaluation);

}  // namespace comic::frontend
