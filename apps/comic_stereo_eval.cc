// comic_stereo_eval: the paper's Middlebury stereo experiment (§5.2.2, Tables 1 and 2, stereo
// rows) for CoMIC and the baselines, boundary vs non-boundary, with precision, matched-precision
// and repeatability tables. Flags -> StereoEvaluationOptions -> EvaluateStereoPair -> files.
#include <cctype>
#include <iostream>
#include <iterator>
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

// The CSV files, one per table of the report, in the order WriteOutputs writes them.
constexpr const char* kTables[] = {
    "protocol",          "pairs",         "detections",      "scores",
    "matched_precision", "repeatability", "paper_comparison"};

std::string Safe(const std::string& name) {
  std::string safe = name.empty() ? "pair" : name;
  for (char& c : safe) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return safe;
}

// The command line, bound to the parser by AddFlags; Check() validates it and fills `options`.
struct Flags {
  Flags() {
    options.detectors.comic.num_threads = 0;
  }  // one per core: the output does not
     // depend on it
  void Check();

  std::string left, right, disparity, disc, nonocc, middlebury;
  std::string out_dir = "stereo_eval";
  double scale = 0.0;
  bool scale_set = false;  // --disparity-scale given
  fe::StereoEvaluationOptions options;
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
  std::vector<fe::StereoMethod> drawn;  // parsed from figure_methods
};

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("LEFT", "left (reference) image", &flags.left, false);
  parser.AddPositional("RIGHT", "right image", &flags.right, false);
  parser.AddOption("disparity", "GT", "ground-truth disparity of the left image (stored x S)",
                   &flags.disparity);
  parser.AddOption("disparity-scale", "S",
                   "disparity = stored value / S (Tsukuba 16, 2003 quarter-size pairs 4); "
                   "0 = from the left file name (im3.png: 16, im2.png: 4)",
                   &flags.scale);
  parser.AddDeprecatedAlias("scale", "disparity-scale");
  parser.AddOption("disc", "MASK",
                   "depth-discontinuity mask (255 = boundary, 128 = other visible pixels); "
                   "without it no boundary split",
                   &flags.disc);
  parser.AddOption("nonocc", "MASK",
                   "non-occluded mask (255 = evaluated); without it nothing counts as occluded",
                   &flags.nonocc);
  parser.AddOption("middlebury", "DIRS",
                   "comma-separated folders laid out like ../shared/data/middlebury2003_cones "
                   "(im2/im6 or im3/im4, groundtruth, nonocc, disc)",
                   &flags.middlebury);
  comic::apps::AddOutputFolderFlag(parser, &flags.out_dir);
  comic::apps::AddResizeHeightFlag(parser, &flags.options.working_height);
  parser.AddDeprecatedAlias("height", "resize-height");
  parser.AddOption("methods", "LIST",
                   "detector/matcher pairs (matchers: full, split, like-sides, calibrated)",
                   &flags.methods);
  parser.AddOption("counts", "LIST",
                   "target counts N of valid left features, one run each; 0 = the count "
                   "reference's own count at its default threshold",
                   &flags.counts);
  parser.AddOption("count-reference", "DET", "detector defining N = 0",
                   &flags.options.count_reference);
  comic::apps::AddMaxCostFlag(parser, &flags.options.max_cost);
  parser.AddOption("sensitivity", "LIST", "further thresholds T reported (inf always is)",
                   &flags.sensitivity);
  parser.AddOption("tolerance", "PX", "a match is correct within this distance of the truth",
                   &flags.options.correct_tolerance);
  parser.AddOption("row-tolerance", "PX", "stereo gate: largest row difference",
                   &flags.options.row_tolerance);
  parser.AddOption("min-disparity", "PX", "stereo gate: smallest disparity",
                   &flags.options.min_disparity);
  parser.AddOption("max-disparity", "PX",
                   "stereo gate: largest disparity; 0 = max GT disparity + --disparity-margin",
                   &flags.options.max_disparity);
  parser.AddOption("disparity-margin", "PX", "added to the max GT disparity for the gate",
                   &flags.options.disparity_margin);
  comic::apps::AddMinSideOverlapFlag(parser, &flags.options.min_side_overlap);
  comic::apps::AddCalibratedCostFlags(parser, &flags.options.min_side_fraction,
                                      &flags.options.side_noise_sigma,
                                      &flags.options.side_noise_from_pair);
  parser.AddOption("repeatability", "LIST", "repeatability tolerances in px", &flags.repeatability);
  parser.AddOption("precision-reference", "METHOD",
                   "matched precision target = this method's overall precision at T",
                   &flags.precision_reference);
  parser.AddOption("target-precision", "P",
                   "also compare the methods at this matched precision (see below)",
                   &flags.options.target_precision);
  parser.AddOption("mser-merge-radius", "PX", "MSER centroids closer than this are merged",
                   &flags.options.detectors.mser.merge_radius);
  comic::apps::AddThreadsFlag(parser, &flags.options.detectors.comic.num_threads);
  parser.AddOption("figure-methods", "LIST", "methods drawn side by side in matches_<pair>.png",
                   &flags.figure_methods);
  comic::apps::AddQuietFlag(parser, &flags.quiet);
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
}

// Options first: a bad flag fails before any file is read.
void Flags::Check() {
  options.detectors.comic_paper.num_threads = options.detectors.comic.num_threads;
  options.methods = fe::ParseStereoMethods(methods);
  options.target_counts = ParseCountList(counts);
  options.sensitivity_costs = comic::apps::ParseNumberList(sensitivity, "sensitivity");
  options.repeatability_tolerances = comic::apps::ParseNumberList(repeatability, "repeatability");
  const std::vector<fe::StereoMethod> precision_methods =
      fe::ParseStereoMethods(precision_reference);
  COMIC_CHECK(precision_methods.size() == 1, kInvalidArgument,
              "--precision-reference: expected one method, got '" << precision_reference << "'");
  options.precision_reference = precision_methods.front();
  drawn = fe::ParseStereoMethods(figure_methods);
  options.Check();
  comic::apps::CheckThreadCount("--threads", options.detectors.comic.num_threads);
  io::CheckResizeHeight(options.working_height);
}

// Inputs next: every pair is loaded (and so checked) before any output is touched.
std::vector<io::MiddleburyPair> LoadPairs(const Flags& flags) {
  const bool scale_set = flags.scale_set;
  const bool pair_mode = !flags.left.empty() || !flags.right.empty();
  COMIC_CHECK(pair_mode != !flags.middlebury.empty(), kInvalidArgument,
              (pair_mode ? "give either LEFT RIGHT or --middlebury, not both"
                         : "missing input: LEFT RIGHT --disparity GT, or --middlebury DIR"));
  std::vector<io::MiddleburyPair> pairs;
  if (pair_mode) {
    COMIC_CHECK(!flags.right.empty(), kInvalidArgument, "missing argument RIGHT");
    COMIC_CHECK(!flags.disparity.empty(), kInvalidArgument,
                "missing --disparity GT (the left image's ground-truth disparity)");
    io::MiddleburyPairPaths paths;
    paths.left = flags.left;
    paths.right = flags.right;
    paths.disparity = flags.disparity;
    paths.disparity_scale = scale_set ? flags.scale : ScaleFromLeftName(flags.left);
    COMIC_CHECK(scale_set || paths.disparity_scale > 0, kInvalidArgument,
                "--disparity-scale is required: " << io::FileName(flags.left)
                                                  << " does not say which Middlebury pair it is");
    paths.nonocc = flags.nonocc;
    paths.disc = flags.disc;
    pairs.push_back(io::LoadMiddleburyPair(paths, flags.options.working_height));
  } else {
    COMIC_CHECK(flags.disparity.empty() && flags.disc.empty() && flags.nonocc.empty(),
                kInvalidArgument,
                "--disparity, --disc and --nonocc go with LEFT RIGHT; --middlebury folders hold "
                "their own");
    COMIC_CHECK(!scale_set || flags.scale > 0, kInvalidArgument,
                "--disparity-scale must be > 0, got " << flags.scale);
    for (const std::string& folder : comic::apps::SplitList(flags.middlebury, "middlebury")) {
      pairs.push_back(io::LoadMiddleburyFolder(folder, flags.options.working_height, flags.scale));
    }
  }
  return pairs;
}

void CheckOutputAvoidsInputs(const Flags& flags) {
  std::vector<io::NamedPath> inputs = {{"LEFT", flags.left},
                                       {"RIGHT", flags.right},
                                       {"--disparity", flags.disparity},
                                       {"--disc", flags.disc},
                                       {"--nonocc", flags.nonocc}};
  if (!flags.middlebury.empty()) {
    for (const std::string& folder : comic::apps::SplitList(flags.middlebury, "middlebury")) {
      inputs.push_back({"--middlebury", folder});
    }
  }
  io::CheckOutputsAvoidInputs({{"--output", flags.out_dir}}, inputs);
}

// The files the run writes into `folder`: stereo_eval.md and .json, one CSV per table, one figure
// per pair, and report.html last.
std::vector<std::string> OutputPaths(const std::string& folder,
                                     const std::vector<io::MiddleburyPair>& pairs) {
  std::vector<std::string> outputs = {io::JoinPaths(folder, "stereo_eval.md"),
                                      io::JoinPaths(folder, "stereo_eval.json")};
  for (const char* table : kTables) {
    outputs.push_back(io::JoinPaths(folder, std::string(table) + ".csv"));
  }
  for (const io::MiddleburyPair& pair : pairs) {
    outputs.push_back(io::JoinPaths(folder, "matches_" + Safe(pair.name) + ".png"));
  }
  outputs.push_back(io::JoinPaths(folder, "report.html"));
  return outputs;
}

// Writes the report, the tables and the figures to the paths OutputPaths gave.
void WriteOutputs(const std::vector<std::string>& outputs, const fe::StereoReport& report,
                  const std::vector<fe::StereoPairEvaluation>& results,
                  const std::vector<cv::Mat>& figures, const fe::StereoEvaluationOptions& options,
                  const std::string& command) {
  const size_t num_tables = std::size(kTables);
  const std::string& page = outputs.back();
  io::WriteFileAtomically(outputs[0], fe::StereoReportMarkdown(report, results, options));
  io::WriteFileAtomically(outputs[1], io::JsonText(report.ToJson(), 2));
  const io::ReportTable* csv[] = {
      &report.protocol,          &report.pairs,         &report.detections,      &report.scores,
      &report.matched_precision, &report.repeatability, &report.paper_comparison};
  for (size_t t = 0; t < num_tables; ++t) io::WriteFileAtomically(outputs[2 + t], csv[t]->ToCsv());
  std::vector<fe::EvaluationFigure> page_figures;
  for (size_t p = 0; p < figures.size(); ++p) {
    io::WriteImageAtomically(outputs[2 + num_tables + p], figures[p]);
    page_figures.push_back({io::FileName(outputs[2 + num_tables + p]), figures[p]});
  }
  io::WriteHtmlPage(page,
                    fe::StereoEvaluationPage(report, results, options, page_figures, command));
}

int Run(int argc, char** argv) {
  Flags flags;
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
  AddFlags(parser, flags);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  flags.scale_set = parser.WasSet("disparity-scale");
  flags.Check();
  const std::vector<io::MiddleburyPair> pairs = LoadPairs(flags);
  CheckOutputAvoidsInputs(flags);

  // Outputs: checked up front, written into a staging folder beside --out and moved into place
  // together at the end (all or nothing; --out itself is created only then).
  io::StagedFolder out(flags.out_dir);
  const std::vector<std::string> outputs = OutputPaths(out.path(), pairs);
  for (const std::string& path : outputs) io::CheckWritableFile(path);

  const fe::StereoProgress progress = [quiet = flags.quiet](const std::string& message) {
    if (!quiet) std::cout << message << std::endl;
  };
  std::vector<fe::StereoPairEvaluation> results;
  std::vector<cv::Mat> figures;
  for (const io::MiddleburyPair& pair : pairs) {
    results.push_back(fe::EvaluateStereoPair(pair, flags.options, progress));
    figures.push_back(fe::DrawStereoMatchFigure(pair, results.back().runs.front(), flags.drawn,
                                                flags.options.max_cost));
  }

  const fe::StereoReport report = fe::BuildStereoReport(results, flags.options);
  // Errors while writing (a full disk) name --output, not the staging folder.
  out.NamingTarget([&] {
    WriteOutputs(outputs, report, results, figures, flags.options,
                 comic::apps::CommandLine("comic_stereo_eval", argc, argv));
  });
  out.Commit();
  if (!flags.quiet) {
    std::cout << "wrote " << outputs.size() << " files to " << flags.out_dir << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_stereo_eval", [&] { return Run(argc, argv); });
}
