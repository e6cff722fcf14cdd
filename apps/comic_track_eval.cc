// comic_track_eval: the paper's tracking comparison (§5.1, Tables 1–3) on one sequence. Runs
// CoMIC and the baseline detectors under one protocol — threshold equalisation on the object in
// the first frame, frame-to-frame SSD patch matching within r = 20 px, tracks, ResM_n and
// M_score(n) for boundary / non-boundary / overall features — and writes the tables (Markdown,
// CSV, JSON), bar charts and track overlays. With KITTI poses it also reports the epipolar
// precision of the matches and the scores at equal precision.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>

#include "apps/common/arg_parser.h"
#include "apps/common/frame_range_flags.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/list_flags.h"
#include "apps/common/progress_line.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "frontend/evaluation/epipolar_check.h"
#include "frontend/evaluation/evaluation_page.h"
#include "frontend/evaluation/track_drawing.h"
#include "frontend/evaluation/track_evaluation.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/pixel_budget.h"
#include "io/core/protected_inputs.h"
#include "io/core/staged_folder.h"
#include "io/datasets/kitti_odometry.h"
#include "io/datasets/region_annotations.h"
#include "io/image/image_io.h"
#include "io/image/image_sequence.h"
#include "io/image/mask_folder.h"
#include "io/report/bar_chart.h"
#include "io/report/html_page.h"
#include "io/report/json_text.h"

namespace {

using comic::io::ReportTable;
namespace fe = comic::frontend;

// Writes a table as name.md, name.csv and name.json in `out`.
void WriteTable(const std::string& out, const std::string& name, const ReportTable& table) {
  comic::io::WriteFileAtomically(comic::io::JoinPaths(out, name + ".md"), table.ToMarkdown());
  comic::io::WriteFileAtomically(comic::io::JoinPaths(out, name + ".csv"), table.ToCsv());
  comic::io::WriteFileAtomically(comic::io::JoinPaths(out, name + ".json"),
                                 comic::io::JsonText(table.ToJson(), 2));
}

// M_score and ResM panels of one n, stacked.
cv::Mat ScoreChart(const fe::TrackEvaluation& evaluation, size_t k, const std::string& title) {
  const int n = evaluation.options.ns[k];
  const std::vector<std::string> groups =
      evaluation.has_regions ? std::vector<std::string>{"boundary", "non-boundary", "overall"}
                             : std::vector<std::string>{"overall"};
  comic::io::BarChart score_chart, res_chart;
  score_chart.title = title + ": M_score(" + std::to_string(n) + ") %";
  score_chart.y_label = "M_score(" + std::to_string(n) + ") (% of N)";
  res_chart.title = title + ": ResM_" + std::to_string(n);
  res_chart.y_label = "ResM_" + std::to_string(n) + " (features)";
  score_chart.groups = res_chart.groups = groups;
  for (const fe::EvaluationRow& row : evaluation.rows) {
    const fe::MatchingScores& s = row.scores[k];
    comic::io::BarChartSeries score{row.label, {}}, res{row.label, {}};
    if (evaluation.has_regions) {
      score.values = {100 * s.boundary.mean_m_score, 100 * s.non_boundary.mean_m_score,
                      100 * s.overall.mean_m_score};
      res.values = {s.boundary.mean_res_m, s.non_boundary.mean_res_m, s.overall.mean_res_m};
    } else {
      score.values = {100 * s.overall.mean_m_score};
      res.values = {s.overall.mean_res_m};
    }
    score_chart.series.push_back(score);
    res_chart.series.push_back(res);
  }
  cv::Mat chart;
  cv::vconcat(comic::io::DrawBarChart(score_chart), comic::io::DrawBarChart(res_chart), chart);
  return chart;
}

// One tile per detector (its first row) with the tracks through `frame`.
cv::Mat OverlayMosaic(const fe::TrackEvaluation& evaluation, const comic::io::Frame& frame,
                      size_t index, const cv::Mat& region_labels) {
  std::vector<cv::Mat> tiles;
  std::vector<std::string> seen;
  for (const fe::EvaluationRow& row : evaluation.rows) {
    if (std::find(seen.begin(), seen.end(), row.detector) != seen.end()) continue;
    seen.push_back(row.detector);
    const std::vector<fe::RegionLabel> labels =
        row.labels.empty() ? std::vector<fe::RegionLabel>() : row.labels[index];
    cv::Mat tile = fe::DrawTracks(frame.color, row.tracking.tracks, static_cast<int>(index), labels,
                                  region_labels);
    const std::string caption = row.label + "  " + frame.name;
    cv::putText(tile, caption, {8, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.7, {0, 0, 0}, 3, cv::LINE_AA);
    cv::putText(tile, caption, {8, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.7, {255, 255, 255}, 1,
                cv::LINE_AA);
    tiles.push_back(tile);
  }
  const size_t columns = tiles.size() <= 2 ? tiles.size() : (tiles.size() <= 4 ? 2 : 3);
  std::vector<cv::Mat> rows;
  for (size_t start = 0; start < tiles.size(); start += columns) {
    std::vector<cv::Mat> row_tiles(tiles.begin() + start,
                                   tiles.begin() + std::min(tiles.size(), start + columns));
    while (row_tiles.size() < columns) {
      row_tiles.push_back(cv::Mat(tiles[0].size(), CV_8UC3, cv::Scalar(255, 255, 255)));
    }
    cv::Mat row;
    cv::hconcat(row_tiles, row);
    rows.push_back(row);
  }
  cv::Mat mosaic;
  cv::vconcat(rows, mosaic);
  // Keep the file a sensible size.
  if (mosaic.cols > 2400) {
    cv::resize(mosaic, mosaic, cv::Size(), 2400.0 / mosaic.cols, 2400.0 / mosaic.cols,
               cv::INTER_AREA);
  }
  return mosaic;
}

// The command line, bound to the parser by AddFlags; Check() validates it and fills `options`.
struct Flags {
  Flags() {
    sequence_options.resize_height = 700;
    region.boundary_band = options.boundary_band;
  }
  void Check();

  std::string frames_path, region_format = "auto";
  // Both CoMIC searches by default (issue 14): the direct search and Algorithm 1 side by side.
  std::string detector_list = "comic,comic-paper,harris,hessian,mser,fast";
  std::string comic_matchers = "split,like-sides,full,calibrated";
  std::string baseline_matchers = "full";
  std::string poses_file, calib_file, out_dir = "track_eval";
  std::string sweep_list = "100,200,400,800,1600,inf";
  int n = 5, frame_step = 5, num_features = 0, overlay_frames = 4, threads = 0;
  bool quiet = false;
  int max_pixels = static_cast<int>(comic::io::kDefaultMaxPixels);
  comic::io::ImageSequenceOptions sequence_options;
  fe::TrackEvaluationOptions options;
  double radius = options.matcher.radius, max_cost = options.matcher.max_cost;
  int min_side_overlap = options.matcher.min_side_overlap;
  comic::apps::ObjectRegionFlags region;
  double epipolar_tolerance = options.epipolar_tolerance;
  double target_precision = options.target_precision;
  comic::io::RegionFileFormat region_file_format{};  // parsed from region_format by Check()
};

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("FRAMES", "folder of images (or a video file) of the sequence",
                       &flags.frames_path);
  comic::apps::AddObjectRegionFlags(parser, &flags.region);
  parser.AddDeprecatedAlias("boxes", "regions");
  parser.AddDeprecatedAlias("band", "boundary-band");
  parser.AddOption("region-format", "F",
                   "format of --regions: auto (8 numbers = VOT, 4 = OTB), vot or otb; both 1-based",
                   &flags.region_format);
  comic::apps::AddDetectorListFlag(parser, &flags.detector_list);
  parser.AddOption("comic-matchers", "LIST",
                   "matchers for CoMIC's features, one row each: split (Algorithm 2), "
                   "like-sides, full, calibrated, track-sides",
                   &flags.comic_matchers);
  parser.AddOption("baseline-matchers", "LIST",
                   "matchers for the other detectors' features, one row each: full, calibrated "
                   "(side-aware, issue 15), track-sides (calibrated with a memory along the "
                   "track), split, like-sides",
                   &flags.baseline_matchers);
  parser.AddOption("n", "N",
                   "frames a feature must be matched through (M_score(n)); n = 1 is "
                   "always reported too",
                   &flags.n);
  parser.AddOption("frame-step", "K", "score every K-th start frame (paper: 5)", &flags.frame_step);
  parser.AddOption("count", "N",
                   "target count N: features on the object in frame 0 for every detector (0 = "
                   "CoMIC's count)",
                   &flags.num_features);
  parser.AddDeprecatedAlias("num-features", "count");
  comic::apps::AddResizeHeightFlag(parser, &flags.sequence_options.resize_height);
  comic::apps::AddFrameRangeFlags(parser, &flags.sequence_options,
                                  comic::apps::StrideFlag::kWithout);
  comic::apps::AddSearchRadiusFlag(parser, &flags.radius);
  parser.AddDeprecatedAlias("radius", "search-radius");
  comic::apps::AddMaxCostFlag(parser, &flags.max_cost);
  comic::apps::AddMinSideOverlapFlag(parser, &flags.min_side_overlap);
  comic::apps::AddCalibratedCostFlags(parser, &flags.options.matcher.min_side_fraction,
                                      &flags.options.matcher.side_noise_sigma,
                                      &flags.options.matcher.side_noise_from_pair);
  parser.AddOption("poses", "FILE", "KITTI poses.txt (camera-to-world per frame) for precision",
                   &flags.poses_file);
  parser.AddOption("calib", "FILE", "KITTI calib.txt (P0 gives the intrinsics) for precision",
                   &flags.calib_file);
  parser.AddOption("epipolar-tolerance", "PX",
                   "a match is consistent within PX pixels of its epipolar line",
                   &flags.epipolar_tolerance);
  parser.AddOption("target-precision", "P",
                   "also compare the methods at this matched precision (see below)",
                   &flags.target_precision);
  parser.AddOption("sweep", "LIST",
                   "also score every row at these SSD thresholds (inf = every mutual-best match)",
                   &flags.sweep_list);
  parser.AddOption("overlay-frames", "K", "write track overlays of K frames (0 = none)",
                   &flags.overlay_frames);
  comic::apps::AddThreadsFlag(parser, &flags.threads);
  comic::apps::AddOutputFolderFlag(parser, &flags.out_dir);
  comic::apps::AddQuietFlag(parser, &flags.quiet);
  comic::apps::AddAllowTruncatedFlag(parser, &flags.sequence_options.allow_truncated);
  comic::apps::AddMaxPixelsFlag(parser, &flags.max_pixels);
  parser.AddEpilog(
      "Outputs in DIR: scores_n<n>.{md,csv,json} (Table 1/2 layout), scores_n<n>.png (bar\n"
      "charts), threshold_sweep_n<n>.{md,csv,json} (the scores at every --sweep threshold),\n"
      "precision_n<n>.{md,csv,json} with --poses, precision_equal_count.{md,csv,json} with\n"
      "--poses and a matcher other than full, evaluation.json (everything, with\n"
      "every start frame's counts), report.md (all tables and the command), tracks_<frame>.png,\n"
      "report.html (tables, charts and overlays with their legends, one self-contained page).\n"
      "--target-precision: with --poses, the matchers are also compared at this epipolar\n"
      "precision (0-1). --resize-height: the paper works at 700.\n\n"
      "Example:\n"
      "  comic_track_eval ../shared/data/otb_Crossing/img --regions "
      "../shared/data/otb_Crossing/groundtruth_rect.txt -o crossing\n");
}

void Flags::Check() {
  // Everything is checked before any detection runs.
  const std::string& masks_dir = region.masks;
  const std::string& boxes_file = region.regions;
  const double band = region.boundary_band;
  COMIC_CHECK(masks_dir.empty() || boxes_file.empty(), kInvalidArgument,
              "give either --masks or --regions, not both");
  COMIC_CHECK(poses_file.empty() == calib_file.empty(), kInvalidArgument,
              "--poses and --calib go together");
  comic::io::CheckOutputsAvoidInputs({{"--output", out_dir}}, {{"FRAMES", frames_path},
                                                               {"--regions", boxes_file},
                                                               {"--masks", masks_dir},
                                                               {"--poses", poses_file},
                                                               {"--calib", calib_file}});
  COMIC_CHECK(n >= 1, kInvalidArgument, "--n must be >= 1, got " << n);
  COMIC_CHECK(overlay_frames >= 0, kInvalidArgument, "--overlay-frames must be >= 0");
  comic::apps::CheckThreadCount("--threads", threads);
  comic::io::CheckMaxPixels(max_pixels);
  comic::io::CheckResizeHeight(sequence_options.resize_height);  // by its flag's name
  sequence_options.max_pixels = max_pixels;
  options.detectors = detector_list.empty() ? comic::frontend::DetectorNames()
                                            : comic::frontend::ParseDetectorList(detector_list);
  options.baseline_costs.clear();
  for (const std::string& name : comic::apps::SplitList(baseline_matchers, "baseline-matchers")) {
    options.baseline_costs.push_back(fe::ParseMatchCost(name));
  }
  options.comic_costs.clear();
  for (const std::string& name : comic::apps::SplitList(comic_matchers, "comic-matchers")) {
    options.comic_costs.push_back(fe::ParseMatchCost(name));
  }
  options.detector_options.comic.num_threads = threads;
  options.detector_options.comic_paper.num_threads = threads;
  options.num_features = num_features;
  options.matcher.radius = radius;
  options.matcher.max_cost = max_cost;
  options.matcher.min_side_overlap = min_side_overlap;
  options.ns = n == 1 ? std::vector<int>{1} : std::vector<int>{1, n};
  options.frame_step = frame_step;
  options.boundary_band = band;
  options.epipolar_tolerance = epipolar_tolerance;  // in stored pixels until the size is known
  options.target_precision = target_precision;
  options.sweep_costs = comic::apps::ParseNumberList(sweep_list, "sweep");
  options.Check();
  region_file_format = comic::io::ParseRegionFileFormat(region_format);
  // --out is checked, not created: the outputs are staged beside it and moved into place when
  // the whole evaluation has succeeded (issue 19: a rejected run left an empty folder).
  comic::io::CheckCreatableFolder(out_dir);
}

// Fits the options to the opened sequence: --n needs n + 1 frames, and the epipolar tolerance
// is given in stored pixels.
void FitToSequence(const comic::io::ImageSequence& sequence, Flags& flags) {
  const size_t num_frames = sequence.NumFrames();
  COMIC_CHECK(static_cast<size_t>(flags.n) < num_frames, kInvalidArgument,
              "--n " << flags.n << " needs at least " << flags.n + 1 << " frames, "
                     << flags.frames_path << " gives " << num_frames);
  const cv::Size source_size = sequence.SourceFrameSize();
  const cv::Size frame_size = sequence.FrameSize();
  // The ground truth's accuracy is a property of the stored images: scale the tolerance with them.
  flags.options.epipolar_tolerance =
      flags.epipolar_tolerance * static_cast<double>(frame_size.height) / source_size.height;
}

// The object region of each evaluated frame, from --masks or --regions (none without either).
fe::RegionMaskSource ReadRegions(const Flags& flags, const comic::io::ImageSequence& sequence) {
  const std::string& masks_dir = flags.region.masks;
  const std::string& boxes_file = flags.region.regions;
  const size_t num_frames = sequence.NumFrames();
  const cv::Size source_size = sequence.SourceFrameSize();
  const cv::Size frame_size = sequence.FrameSize();
  const size_t first_source = static_cast<size_t>(flags.sequence_options.first_frame);
  const size_t last_source = first_source + num_frames - 1;
  fe::RegionMaskSource regions;
  if (!masks_dir.empty()) {
    const auto masks =
        std::make_shared<comic::io::MaskFolder>(comic::io::MaskFolder::Open(masks_dir));
    // One mask per frame of the whole sequence, each the size of the frames.
    masks->CheckCount(comic::io::ImageSequence::Open(flags.frames_path).NumFrames());
    for (size_t i = 0; i < num_frames; ++i) masks->Read(first_source + i, source_size);
    regions = [masks, first_source, source_size, frame_size](size_t frame) {
      cv::Mat mask = masks->Read(first_source + frame, source_size);
      if (mask.size() != frame_size) {
        cv::resize(mask, mask, frame_size, 0, 0, cv::INTER_NEAREST);
      }
      return mask;
    };
  } else if (!boxes_file.empty()) {
    const auto annotations = std::make_shared<comic::io::RegionAnnotations>(
        comic::io::ReadRegionFile(boxes_file, flags.region_file_format));
    COMIC_CHECK(annotations->polygons.size() > last_source, kInvalidData,
                boxes_file << ": " << annotations->polygons.size() << " regions, but frame "
                           << last_source << " needs line " << last_source + 1);
    regions = [annotations, first_source, source_size, frame_size](size_t frame) {
      return comic::io::RasterizeRegion(annotations->polygons[first_source + frame], source_size,
                                        frame_size);
    };
  }
  return regions;
}

// With --poses and --calib: the true cameras of the evaluated frames, at the evaluated size.
std::optional<fe::EpipolarGroundTruth> ReadGroundTruth(const Flags& flags,
                                                       const comic::io::ImageSequence& sequence) {
  const std::string& poses_file = flags.poses_file;
  const std::string& calib_file = flags.calib_file;
  const size_t num_frames = sequence.NumFrames();
  const cv::Size source_size = sequence.SourceFrameSize();
  const cv::Size frame_size = sequence.FrameSize();
  const size_t first_source = static_cast<size_t>(flags.sequence_options.first_frame);
  const size_t last_source = first_source + num_frames - 1;
  std::optional<fe::EpipolarGroundTruth> ground_truth;
  if (!poses_file.empty()) {
    const auto poses = comic::io::ReadKittiPoses(poses_file);
    COMIC_CHECK(poses.size() > last_source, kInvalidData,
                poses_file << ": " << poses.size() << " poses, but frame " << last_source
                           << " needs line " << last_source + 1);
    fe::EpipolarGroundTruth truth;
    truth.K =
        fe::ScaleIntrinsics(comic::io::ReadKittiIntrinsics(calib_file, 0), source_size, frame_size);
    truth.world_from_camera.assign(poses.begin() + first_source,
                                   poses.begin() + first_source + num_frames);
    ground_truth = truth;
  }
  return ground_truth;
}

// Per n: the score table and chart, the threshold sweep and, with ground truth, the precision;
// each written to the folder and appended to the report.
void WriteScoreTables(const std::string& folder, const Flags& flags,
                      const fe::TrackEvaluation& evaluation, bool has_ground_truth,
                      std::ostringstream& report) {
  const fe::TrackEvaluationOptions& options = flags.options;
  const std::string& frames_path = flags.frames_path;
  const double epipolar_tolerance = flags.epipolar_tolerance;
  for (size_t k = 0; k < options.ns.size(); ++k) {
    const int nk = options.ns[k];
    const ReportTable table = fe::ScoreTable(evaluation, nk);
    const std::string name = "scores_n" + std::to_string(nk);
    WriteTable(folder, name, table);
    comic::io::WriteImageAtomically(comic::io::JoinPaths(folder, name + ".png"),
                                    ScoreChart(evaluation, k, comic::io::FileName(frames_path)));
    report << "## M_score(" << nk << ") and ResM_" << nk << "\n\n" << table.ToMarkdown() << "\n";
    const ReportTable sweep = fe::ThresholdSweepTable(evaluation, nk);
    WriteTable(folder, "threshold_sweep_n" + std::to_string(nk), sweep);
    report << "## M_score(" << nk << ") and ResM_" << nk
           << " at other SSD thresholds T (same matches, re-thresholded)\n\n"
           << sweep.ToMarkdown() << "\n";
    if (has_ground_truth) {
      const ReportTable precision = fe::PrecisionTable(evaluation, nk);
      WriteTable(folder, "precision_n" + std::to_string(nk), precision);
      report << "## Epipolar precision (tolerance " << epipolar_tolerance << " px), n = " << nk
             << "\n\n"
             << precision.ToMarkdown() << "\n";
    }
  }
  if (has_ground_truth) {
    const ReportTable equal_count = fe::EqualCountPrecisionTable(evaluation);
    if (equal_count.NumRows() > 0) {
      WriteTable(folder, "precision_equal_count", equal_count);
      report << "## Epipolar precision at the full patch's number of accepted matches per pair "
                "(tolerance "
             << epipolar_tolerance << " px)\n\n"
             << equal_count.ToMarkdown() << "\n";
    }
  }
}

// Overlays on frames spread over the sequence, late enough to show some history; written to the
// folder and returned for report.html.
std::vector<fe::EvaluationFigure> WriteOverlays(const std::string& folder, const Flags& flags,
                                                const comic::io::ImageSequence& sequence,
                                                const fe::RegionMaskSource& regions,
                                                const fe::TrackEvaluation& evaluation) {
  const size_t num_frames = sequence.NumFrames();
  const double band = flags.region.boundary_band;
  const int overlay_frames = flags.overlay_frames;
  std::vector<fe::EvaluationFigure> figures;
  const size_t overlays = std::min<size_t>(overlay_frames, num_frames);
  for (size_t o = 0; o < overlays; ++o) {
    const size_t first_shown = std::min<size_t>(5, num_frames - 1);
    const size_t index = overlays == 1
                             ? first_shown
                             : first_shown + o * (num_frames - 1 - first_shown) / (overlays - 1);
    const comic::io::Frame frame = sequence.ReadFrame(index);
    const cv::Mat labels = regions ? fe::LabelRegion(regions(index), band) : cv::Mat();
    const std::string stem = frame.name.substr(0, frame.name.find_last_of('.'));
    figures.push_back({"tracks_" + stem + ".png", OverlayMosaic(evaluation, frame, index, labels)});
    comic::io::WriteImageAtomically(comic::io::JoinPaths(folder, figures.back().caption),
                                    figures.back().image);
  }
  return figures;
}

// Tables, charts, overlays, evaluation.json, report.md and report.html.
void WriteOutputs(const std::string& folder, const Flags& flags, const std::string& command,
                  const comic::io::ImageSequence& sequence, const fe::RegionMaskSource& regions,
                  bool has_ground_truth, const fe::TrackEvaluation& evaluation) {
  const size_t num_frames = sequence.NumFrames();
  const cv::Size frame_size = sequence.FrameSize();
  const std::string& masks_dir = flags.region.masks;
  const std::string& boxes_file = flags.region.regions;
  const double band = flags.region.boundary_band;
  std::ostringstream report;
  report << "# comic_track_eval report\n\n```\n"
         << command << "\n```\n\n"
         << "- frames: " << num_frames << " (" << evaluation.frame_names.front() << " .. "
         << evaluation.frame_names.back() << "), evaluated at " << frame_size.width << "x"
         << frame_size.height << "\n"
         << "- object region: "
         << (!masks_dir.empty() ? "masks " + masks_dir
                                : (!boxes_file.empty() ? "regions " + boxes_file : "none"))
         << "; boundary band " << band << " px\n"
         << "- N = " << evaluation.reference_count << " features in frame 0's object region ("
         << (evaluation.reference_source == "comic" ? "CoMIC's count" : "requested") << ")\n"
         << "- matching: r = " << flags.radius << " px, T = " << flags.max_cost
         << " (mean squared difference), min side overlap " << flags.min_side_overlap << " px\n\n";
  WriteScoreTables(folder, flags, evaluation, has_ground_truth, report);
  nlohmann::json json = fe::EvaluationToJson(evaluation);
  json["command"] = command;
  comic::io::WriteFileAtomically(comic::io::JoinPaths(folder, "evaluation.json"),
                                 comic::io::JsonText(json, 2));

  const std::vector<fe::EvaluationFigure> figures =
      WriteOverlays(folder, flags, sequence, regions, evaluation);
  const std::string region_words = !masks_dir.empty()
                                       ? "masks " + masks_dir
                                       : (!boxes_file.empty() ? "regions " + boxes_file : "none");
  comic::io::WriteHtmlPage(comic::io::JoinPaths(folder, "report.html"),
                           fe::TrackEvaluationPage(evaluation, {command, region_words, figures}));
  comic::io::WriteFileAtomically(comic::io::JoinPaths(folder, "report.md"), report.str());
}

int Run(int argc, char** argv) {
  Flags flags;
  comic::apps::ArgParser parser(
      "comic_track_eval", "FRAMES [--masks DIR | --regions FILE] [options]",
      "Compares CoMIC with Harris, Hessian, MSER and FAST-9 on one sequence under the paper's\n"
      "protocol (§5.1): every detector's threshold is set to give the same number N of features\n"
      "on the object in the first frame; features are detected on every frame and matched frame\n"
      "to frame by 23x23 SSD within r pixels, one-to-one, at one SSD threshold; ResM_n and\n"
      "M_score(n) = ResM_n / N_{i-n} (Eq. 2) are computed every frame-step frames and averaged,\n"
      "for boundary, non-boundary and all features of the object region (features off the\n"
      "object are left out). CoMIC is matched with its split patch (Algorithm 2), with like\n"
      "sides only, and with the full patch, one row each.");
  AddFlags(parser, flags);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  flags.Check();

  const auto sequence = comic::io::ImageSequence::Open(flags.frames_path, flags.sequence_options);
  FitToSequence(sequence, flags);
  const fe::RegionMaskSource regions = ReadRegions(flags, sequence);
  const std::optional<fe::EpipolarGroundTruth> ground_truth = ReadGroundTruth(flags, sequence);

  comic::apps::PrintWarning("comic_track_eval", sequence.warning());
  comic::io::StagedFolder out(flags.out_dir);
  std::cout << "comic_track_eval: " << sequence.NumFrames() << " frames of " << flags.frames_path
            << " at " << sequence.FrameSize().width << "x" << sequence.FrameSize().height
            << ", detectors " << flags.detector_list << std::endl;
  // Per frame (of all detectors' passes) with elapsed time and an estimate of what remains,
  // on stdout (issue 17); --quiet silences it.
  comic::apps::ProgressLine progress("comic_track_eval: detection and tracking", flags.quiet);
  const fe::TrackEvaluation evaluation =
      fe::EvaluateTracking(sequence, regions, ground_truth, flags.options, progress.Callback());

  // Errors while writing (a full disk) name --output, not the staging folder.
  out.NamingTarget([&] {
    WriteOutputs(out.path(), flags, comic::apps::CommandLine("comic_track_eval", argc, argv),
                 sequence, regions, ground_truth.has_value(), evaluation);
  });
  out.Commit();
  std::cout << fe::ScoreTable(evaluation, flags.n).ToMarkdown() << "wrote " << flags.out_dir
            << "/\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_track_eval", [&] { return Run(argc, argv); });
}
