// comic_stereo_eval: the paper's Middlebury stereo experiment (§5.2.2, Tables 1 and 2, stereo
// rows) for CoMIC and the baselines, boundary vs non-boundary, with precision, matched-precision
// and repeatability tables. Flags -> StereoEvaluationOptions -> EvaluateStereoPair -> files.
#include <cctype>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "apps/common/arg_parser.h"
#include "apps/common/list_flags.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "frontend/evaluation/evaluation_page.h"
#include "frontend/evaluation/stereo_evaluation.h"
#include "frontend/evaluation/stereo_evaluation_report.h"
#include "frontend/evaluation/stereo_match_figure.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/protected_inputs.h"
#include "io/core/staged_folder.h"
#include "io/datasets/middlebury.h"
#include "io/image/image_io.h"
#include "io/report/html_page.h"
#include "io/report/json_text.h"

namespace {

namespace fe = comic::frontend;
namespace io = comic::io;

std::vector<int> ParseCountList(const std::string& text) {
  std::vector<int> counts;
  for (double v : comic::apps::ParseNumberList(text, "counts")) {
    COMIC_CHECK(v >= 0 && v == static_cast<int>(v), kInvalidArgument,
                "--counts: expected whole numbers >= 0, got " << v);
    counts.push_back(static_cast<int>(v));
  }
  return counts;
}

// The scale implied by a Middlebury file name, as LoadMiddleburyFolder does: im3.png (Tsukuba,
// ×16) or im2.png (2003 pairs, ×4); 0 when the name says nothing.
double ScaleFromLeftName(const std::string& left) {
  const std::string name = io::FileName(left);
  if (name == "im3.png") return 16.0;
  if (name == "im2.png") return 4.0;
  return 0.0;
}

std::string Safe(const std::string& name) {
  std::string safe = name.empty() ? "pair" : name;
  for (char& c : safe) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return safe;
}

int Run(int argc, char** argv) {
  std::string left, right, disparity, disc, nonocc, middlebury;
  std::string out_dir = "stereo_eval";
  double scale = 0.0;
  fe::StereoEvaluationOptions options;
  options.detectors.comic.num_threads = 0;  // one per core: the output does not depend on it
  std::string methods =
      "comic/split,comic/like-sides,comic/full,comic/calibrated,comic-paper/split,comic-paper/full,"
      "harris/full,harris/calibrated,hessian/full,hessian/calibrated,mser/full,fast/full,"
      "fast/calibrated";
  std::string counts = "0,1000";
  std::string sensitivity = "200,400,800";
  std::string repeatability = "1,1.5,2.5";
  std::string precision_reference = options.precision_reference.Label();
  std::string figure_methods = "comic/split,harris/full";
  bool quiet = false;

  comic::apps::ArgParser parser(
      "comic_stereo_eval",
      "LEFT RIGHT --disparity GT [--disparity-scale S] [--disc MASK] [--nonocc MASK] [-o DIR] | "
      "--middlebury DIR[,DIR...] [-o DIR]",
      "Evaluates CoMIC and the baseline detectors on rectified stereo pairs with ground-truth\n"
      "disparity (paper §5.2.2, Tables 1 and 2): thresholds equalised on the left image, SSD\n"
      "matching along the row, one-to-one; M_score(1), ResM_1 and precision for the boundary\n"
      "(disc = 255), non-boundary and overall regions, at a fixed T, over a T sweep, at matched\n"
      "precision and at T = inf, plus repeatability. Writes Markdown, CSV, JSON and a PNG of\n"
      "correct and wrong matches per pair.");
  parser.AddPositional("LEFT", "left (reference) image", &left, false);
  parser.AddPositional("RIGHT", "right image", &right, false);
  parser.AddOption("disparity", "GT", "ground-truth disparity of the left image (stored x S)",
                   &disparity);
  parser.AddOption("disparity-scale", "S",
                   "disparity = stored value / S (Tsukuba 16, 2003 quarter-size pairs 4); "
                   "0 = from the left file name (im3.png: 16, im2.png: 4)",
                   &scale);
  parser.AddDeprecatedAlias("scale", "disparity-scale");
  parser.AddOption("disc", "MASK",
                   "depth-discontinuity mask (255 = boundary, 128 = other visible pixels); "
                   "without it no boundary split",
                   &disc);
  parser.AddOption("nonocc", "MASK",
                   "non-occluded mask (255 = evaluated); without it nothing counts as occluded",
                   &nonocc);
  parser.AddOption("middlebury", "DIRS",
                   "comma-separated folders laid out like ../shared/data/middlebury2003_cones "
                   "(im2/im6 or im3/im4, groundtruth, nonocc, disc)",
                   &middlebury);
  comic::apps::AddOutputFolderFlag(parser, &out_dir);
  comic::apps::AddResizeHeightFlag(parser, &options.working_height);
  parser.AddDeprecatedAlias("height", "resize-height");
  parser.AddOption("methods", "LIST",
                   "detector/matcher pairs (matchers: full, split, like-sides, calibrated)",
                   &methods);
  parser.AddOption("counts", "LIST",
                   "target counts N of valid left features, one run each; 0 = the count "
                   "reference's own count at its default threshold",
                   &counts);
  parser.AddOption("count-reference", "DET", "detector defining N = 0", &options.count_reference);
  comic::apps::AddMaxCostFlag(parser, &options.max_cost);
  parser.AddOption("sensitivity", "LIST", "further thresholds T reported (inf always is)",
                   &sensitivity);
  parser.AddOption("tolerance", "PX", "a match is correct within this distance of the truth",
                   &options.correct_tolerance);
  parser.AddOption("row-tolerance", "PX", "stereo gate: largest row difference",
                   &options.row_tolerance);
  parser.AddOption("min-disparity", "PX", "stereo gate: smallest disparity",
                   &options.min_disparity);
  parser.AddOption("max-disparity", "PX",
                   "stereo gate: largest disparity; 0 = max GT disparity + --disparity-margin",
                   &options.max_disparity);
  parser.AddOption("disparity-margin", "PX", "added to the max GT disparity for the gate",
                   &options.disparity_margin);
  comic::apps::AddMinSideOverlapFlag(parser, &options.min_side_overlap);
  comic::apps::AddCalibratedCostFlags(parser, &options.min_side_fraction, &options.side_noise_sigma,
                                      &options.side_noise_from_pair);
  parser.AddOption("repeatability", "LIST", "repeatability tolerances in px", &repeatability);
  parser.AddOption("precision-reference", "METHOD",
                   "matched precision target = this method's overall precision at T",
                   &precision_reference);
  parser.AddOption("target-precision", "P",
                   "also compare the methods at this matched precision (see below)",
                   &options.target_precision);
  parser.AddOption("mser-merge-radius", "PX", "MSER centroids closer than this are merged",
                   &options.detectors.mser.merge_radius);
  comic::apps::AddThreadsFlag(parser, &options.detectors.comic.num_threads);
  parser.AddOption("figure-methods", "LIST", "methods drawn side by side in matches_<pair>.png",
                   &figure_methods);
  comic::apps::AddQuietFlag(parser, &quiet);
  parser.AddEpilog(
      "Outputs in DIR: stereo_eval.md (every table, readable), stereo_eval.json, protocol.csv,\n"
      "pairs.csv, detections.csv, scores.csv, matched_precision.csv, repeatability.csv,\n"
      "paper_comparison.csv, matches_<pair>.png (first count of --counts) and report.html (the\n"
      "tables, charts and figures with their legends, one self-contained page).\n"
      "--target-precision P in (0, 1] fixes the matched-precision target; 0 (the default) takes\n"
      "--precision-reference's overall precision at T. --resize-height is the working height\n"
      "(paper: 700).\n\n"
      "Example:\n"
      "  comic_stereo_eval --middlebury ../shared/data/middlebury2001_tsukuba,"
      "../shared/data/middlebury2003_cones -o stereo\n");
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  options.detectors.comic_paper.num_threads = options.detectors.comic.num_threads;

  // Options first: a bad flag fails before any file is read.
  options.methods = fe::ParseStereoMethods(methods);
  options.target_counts = ParseCountList(counts);
  options.sensitivity_costs = comic::apps::ParseNumberList(sensitivity, "sensitivity");
  options.repeatability_tolerances = comic::apps::ParseNumberList(repeatability, "repeatability");
  const std::vector<fe::StereoMethod> precision_methods =
      fe::ParseStereoMethods(precision_reference);
  COMIC_CHECK(precision_methods.size() == 1, kInvalidArgument,
              "--precision-reference: expected one method, got '" << precision_reference << "'");
  options.precision_reference = precision_methods.front();
  const std::vector<fe::StereoMethod> drawn = fe::ParseStereoMethods(figure_methods);
  options.Check();
  comic::apps::CheckThreadCount("--threads", options.detectors.comic.num_threads);
  io::CheckResizeHeight(options.working_height);

  // Inputs next: every pair is loaded (and so checked) before any output is touched.
  const bool pair_mode = !left.empty() || !right.empty();
  COMIC_CHECK(pair_mode != !middlebury.empty(), kInvalidArgument,
              (pair_mode ? "give either LEFT RIGHT or --middlebury, not both"
                         : "missing input: LEFT RIGHT --disparity GT, or --middlebury DIR"));
  std::vector<io::MiddleburyPair> pairs;
  if (pair_mode) {
    COMIC_CHECK(!right.empty(), kInvalidArgument, "missing argument RIGHT");
    COMIC_CHECK(!disparity.empty(), kInvalidArgument,
                "missing --disparity GT (the left image's ground-truth disparity)");
    io::MiddleburyPairPaths paths;
    paths.left = left;
    paths.right = right;
    paths.disparity = disparity;
    paths.disparity_scale = parser.WasSet("disparity-scale") ? scale : ScaleFromLeftName(left);
    COMIC_CHECK(parser.WasSet("disparity-scale") || paths.disparity_scale > 0, kInvalidArgument,
                "--disparity-scale is required: " << io::FileName(left)
                                                  << " does not say which Middlebury pair it is");
    paths.nonocc = nonocc;
    paths.disc = disc;
    pairs.push_back(io::LoadMiddleburyPair(paths, options.working_height));
  } else {
    COMIC_CHECK(disparity.empty() && disc.empty() && nonocc.empty(), kInvalidArgument,
                "--disparity, --disc and --nonocc go with LEFT RIGHT; --middlebury folders hold "
                "their own");
    COMIC_CHECK(!parser.WasSet("disparity-scale") || scale > 0, kInvalidArgument,
                "--disparity-scale must be > 0, got " << scale);
    for (const std::string& folder : comic::apps::SplitList(middlebury, "middlebury")) {
      pairs.push_back(io::LoadMiddleburyFolder(folder, options.working_height, scale));
    }
  }

  std::vector<io::NamedPath> inputs = {{"LEFT", left},
                                       {"RIGHT", right},
                                       {"--disparity", disparity},
                                       {"--disc", disc},
                                       {"--nonocc", nonocc}};
  if (!middlebury.empty()) {
    for (const std::string& folder : comic::apps::SplitList(middlebury, "middlebury")) {
      inputs.push_back({"--middlebury", folder});
    }
  }
  io::CheckOutputsAvoidInputs({{"--output", out_dir}}, inputs);

  // Outputs: checked up front, written into a staging folder beside --out and moved into place
  // together at the end (all or nothing; --out itself is created only then).
  io::StagedFolder out(out_dir);
  const std::vector<std::string> tables = {
      "protocol",          "pairs",         "detections",      "scores",
      "matched_precision", "repeatability", "paper_comparison"};
  std::vector<std::string> outputs = {io::JoinPaths(out.path(), "stereo_eval.md"),
                                      io::JoinPaths(out.path(), "stereo_eval.json")};
  for (const std::string& table : tables)
    outputs.push_back(io::JoinPaths(out.path(), table + ".csv"));
  for (const io::MiddleburyPair& pair : pairs) {
    outputs.push_back(io::JoinPaths(out.path(), "matches_" + Safe(pair.name) + ".png"));
  }
  const std::string page = io::JoinPaths(out.path(), "report.html");
  outputs.push_back(page);
  for (const std::string& path : outputs) io::CheckWritableFile(path);

  const fe::StereoProgress progress = [quiet](const std::string& message) {
    if (!quiet) std::cout << message << std::endl;
  };
  std::vector<fe::StereoPairEvaluation> results;
  std::vector<cv::Mat> figures;
  for (const io::MiddleburyPair& pair : pairs) {
    results.push_back(fe::EvaluateStereoPair(pair, options, progress));
    figures.push_back(
        fe::DrawStereoMatchFigure(pair, results.back().runs.front(), drawn, options.max_cost));
  }

  const fe::StereoReport report = fe::BuildStereoReport(results, options);
  // Errors while writing (a full disk) name --output, not the staging folder.
  out.NamingTarget([&] {
    io::WriteFileAtomically(outputs[0], fe::StereoReportMarkdown(report, results, options));
    io::WriteFileAtomically(outputs[1], io::JsonText(report.ToJson(), 2));
    const io::ReportTable* csv[] = {
        &report.protocol,          &report.pairs,         &report.detections,      &report.scores,
        &report.matched_precision, &report.repeatability, &report.paper_comparison};
    for (size_t t = 0; t < tables.size(); ++t)
      io::WriteFileAtomically(outputs[2 + t], csv[t]->ToCsv());
    std::vector<fe::EvaluationFigure> page_figures;
    for (size_t p = 0; p < pairs.size(); ++p) {
      io::WriteImageAtomically(outputs[2 + tables.size() + p], figures[p]);
      page_figures.push_back({io::FileName(outputs[2 + tables.size() + p]), figures[p]});
    }
    io::WriteHtmlPage(
        page, fe::StereoEvaluationPage(report, results, options, page_figures,
                                       comic::apps::CommandLine("comic_stereo_eval", argc, argv)));
  });
  out.Commit();
  if (!quiet) std::cout << "wrote " << outputs.size() << " files to " << out_dir << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_stereo_eval", [&] { return Run(argc, argv); });
}
