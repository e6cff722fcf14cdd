// comic_detect: runs a CoMIC detector (the direct search "comic", or Algorithm 1 "comic-paper")
// on one image, draws the features and their maximally
// stable iso-curve segments (both polarities in different colours) and writes them as JSON.
#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "apps/common/arg_parser.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "frontend/comic/comic_detector.h"
#include "frontend/comic/comic_direct_detector.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/pixel_budget.h"
#include "io/core/protected_inputs.h"
#include "io/core/staged_files.h"
#include "io/image/image_io.h"
#include "io/report/json_text.h"

namespace {

using comic::frontend::Feature;
using comic::frontend::FeatureSet;
using comic::frontend::PatchSide;
using comic::frontend::Polarity;

// BGR colours: features whose corner points into the brighter region, and into the darker one.
const cv::Scalar kBrightColour(0, 0, 255);
const cv::Scalar kDarkColour(255, 255, 0);

const char* PolarityName(Polarity polarity) {
  switch (polarity) {
    case Polarity::kBright:
      return "bright";
    case Polarity::kDark:
      return "dark";
    default:
      return "none";
  }
}

cv::Mat DrawOverlay(const cv::Mat& color, const FeatureSet& features) {
  cv::Mat overlay = color.clone();
  constexpr int kShift = 4;  // sub-pixel drawing: coordinates in 1/16 px
  constexpr double kUnit = 1 << kShift;
  auto fixed = [&](const cv::Point2f& p) {
    return cv::Point(static_cast<int>(std::lround(p.x * kUnit)),
                     static_cast<int>(std::lround(p.y * kUnit)));
  };
  // Weakest first so that the strongest features end up on top.
  for (auto it = features.rbegin(); it != features.rend(); ++it) {
    const Feature& f = *it;
    const cv::Scalar colour = f.polarity == Polarity::kBright ? kBrightColour : kDarkColour;
    std::vector<cv::Point> curve;
    for (const cv::Point2f& p : f.curve) curve.push_back(fixed(p));
    if (curve.size() >= 2) cv::polylines(overlay, curve, false, colour, 1, cv::LINE_AA, kShift);
    cv::circle(overlay, fixed(f.Position()), static_cast<int>(2.5 * kUnit), colour, 1, cv::LINE_AA,
               kShift);
  }
  const std::string legend = std::to_string(features.size()) +
                             " CoMIC features  red: corner into the brighter side  cyan: into the "
                             "darker side";
  cv::putText(overlay, legend, {6, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 3, cv::LINE_AA);
  cv::putText(overlay, legend, {6, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {255, 255, 255}, 1,
              cv::LINE_AA);
  return overlay;
}

nlohmann::json FeatureToJson(const Feature& f) {
  nlohmann::json curve = nlohmann::json::array();
  for (const cv::Point2f& p : f.curve) curve.push_back({p.x, p.y});
  // The side mask as kPatchSize rows of '+' (ic+, bright side), '-' (ic-, dark side), '.' (none).
  nlohmann::json mask = nlohmann::json::array();
  if (f.HasSideMask()) {
    for (int v = 0; v < comic::frontend::kPatchSize; ++v) {
      std::string row;
      for (int u = 0; u < comic::frontend::kPatchSize; ++u) {
        const PatchSide side = f.side_mask[v * comic::frontend::kPatchSize + u];
        row += side == PatchSide::kPlus ? '+' : side == PatchSide::kMinus ? '-' : '.';
      }
      mask.push_back(row);
    }
  }
  return {{"x", f.x},
          {"y", f.y},
          {"scale", f.scale},
          {"response", f.response},
          {"cornerness", f.cornerness},
          {"level", f.level},
          {"polarity", PolarityName(f.polarity)},
          {"curve", curve},
          {"side_mask", mask}};
}

// The command line, bound to the parser by AddFlags; Check() validates it and completes both
// searches' options.
struct Flags {
  // All cores: the output does not depend on the thread count.
  Flags() { options.num_threads = 0; }
  void Check();

  std::string input;
  std::string overlay_path;
  std::string json_path;
  int resize_height = 0;
  int max_features = 0;
  bool full_resolution_init = false;
  bool no_neighbour_seeds = false;
  bool every_path = false;
  std::string detector_name = "comic";
  int max_pixels = static_cast<int>(comic::io::kDefaultMaxPixels);
  // Options shared by both searches are parsed into `options` (Algorithm 1's) and copied to
  // `direct`; the others belong to one search only.
  comic::frontend::ComicDetectorOptions options;
  comic::frontend::ComicDirectDetectorOptions direct;
  bool paper = false;  // --detector comic-paper
};

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("IMAGE", "input image (any format OpenCV reads)", &flags.input);
  parser.AddOption("overlay", "PNG", "write an overlay: features and their MSICS on the image",
                   &flags.overlay_path);
  parser.AddDeprecatedAlias("out", "overlay");
  comic::apps::AddJsonFlag(parser, &flags.json_path);
  comic::apps::AddResizeHeightFlag(parser, &flags.resize_height);
  // The shared --detector flag; comic_detect runs the two CoMIC searches only: comic (the direct
  // search of the paper's definition) or comic-paper (Algorithm 1).
  comic::apps::AddDetectorFlag(parser, &flags.detector_name);
  parser.AddOption("scale", "S", "detection scale s in px (paper: 8.4; initialisation at 2s)",
                   &flags.options.scale);
  parser.AddOption("block-size", "B",
                   "comic-paper: block size B in px (paper: 100): B x B initialisation blocks, B/2 "
                   "convergence blocks",
                   &flags.options.block_size);
  parser.AddOption("delta", "D", "intensity offset delta of the Up/Down iso-curves, grey levels",
                   &flags.options.delta);
  parser.AddOption("half-length", "K", "points on either side of the corner in a segment, k",
                   &flags.options.half_length);
  parser.AddOption("max-iterations", "N",
                   "comic-paper: feature-convergence iterations before a corner is dropped",
                   &flags.options.max_iterations);
  parser.AddOption("convergence-tolerance", "PX",
                   "comic-paper: a corner has settled when it moves at most this",
                   &flags.options.convergence_tolerance);
  parser.AddOption("stop-tolerance", "PX",
                   "comic-paper: convergence iterations stop once a corner moves at most this",
                   &flags.options.stop_tolerance);
  parser.AddOption("merge-radius", "PX", "features closer than this are merged (higher rho kept)",
                   &flags.options.merge_radius);
  parser.AddOption("min-stability", "RHO", "stability threshold on rho = len / dA, 1/px (0 = all)",
                   &flags.options.min_stability);
  parser.AddOption("min-cornerness", "KAPPA", "cornerness threshold on kappa, in [0, 0.25]",
                   &flags.options.min_cornerness);
  parser.AddFlag(
      "no-neighbour-seeds",
      "comic-paper: do not converge again from the other corners found on each MSICS (corners\n"
      "                              closer than the initialisation scale 2s may be missed)",
      &flags.no_neighbour_seeds);
  parser.AddFlag(
      "every-path",
      "comic-paper: converge every seed to the end (default: a seed that reaches another\n"
      "                              seed's state waits for that seed's outcome)",
      &flags.every_path);
  parser.AddFlag(
      "full-resolution-init",
      "comic-paper: run the initialisation stage at full resolution (default: on the image\n"
      "                              halved, same physical scale, 4x fewer pixels)",
      &flags.full_resolution_init);
  parser.AddOption("presmoothing-sigma", "PX",
                   "comic: Gaussian pre-smoothing of the image, px (0 = none)",
                   &flags.direct.presmoothing_sigma);
  parser.AddOption("level-radius", "N",
                   "comic: levels traced on either side of each stable maximum of the tree",
                   &flags.direct.level_radius);
  parser.AddOption("link-radius", "PX",
                   "comic: corners of consecutive levels closer than this form one run",
                   &flags.direct.link_radius);
  parser.AddOption("consensus-fraction", "F",
                   "comic: run members with rho >= F x the peak's vote for the position",
                   &flags.direct.consensus_fraction);
  comic::apps::AddThreadsFlag(parser, &flags.options.num_threads);
  comic::apps::AddMaxFeaturesFlag(parser, &flags.max_features);
  comic::apps::AddMaxPixelsFlag(parser, &flags.max_pixels);
  parser.AddEpilog(
      "Example:\n"
      "  comic_detect ../shared/data/middlebury2003_cones/im2.png --resize-height 700 \\\n"
      "      --overlay cones_comic.png --json cones_comic.json\n"
      "--json: position, scale, response = stability rho, cornerness kappa, level, polarity,\n"
      "curve and 23x23 side mask of every feature (strongest = most stable first). The paper\n"
      "worked at --resize-height 700.\n"
      "Overlay colours: red = corner pointing into the brighter side of its iso-curve, cyan = "
      "into\n"
      "the darker side; the line through each circle is its maximally stable iso-curve segment.\n");
}

void Flags::Check() {
  comic::io::CheckResizeHeight(resize_height);
  comic::io::CheckMaxPixels(max_pixels);
  COMIC_CHECK(max_features >= 0, kInvalidArgument, "--max-features must be >= 0");
  options.coarse_initialisation = !full_resolution_init;
  options.seed_neighbouring_corners = !no_neighbour_seeds;
  options.skip_duplicate_paths = !every_path;
  COMIC_CHECK(detector_name == "comic" || detector_name == "comic-paper", kInvalidArgument,
              "--detector: comic_detect runs comic or comic-paper (CoMIC's two searches), got '"
                  << detector_name << "'");
  direct.scale = options.scale;
  direct.delta = options.delta;
  direct.half_length = options.half_length;
  direct.merge_radius = options.merge_radius;
  direct.min_stability = options.min_stability;
  direct.min_cornerness = options.min_cornerness;
  direct.num_threads = options.num_threads;
  paper = detector_name == "comic-paper";
  // Both searches' options are checked whichever runs: a bad value is an error, not ignored.
  options.Check();
  if (!paper) direct.Check();
  comic::apps::CheckThreadCount("--threads", options.num_threads);
  // Inputs are sacred: `--json img.png` must not replace the image (issue 29).
  comic::io::CheckOutputsAvoidInputs({{"--overlay", overlay_path}, {"--json", json_path}},
                                     {{"IMAGE", input}});
}

// The options of the search that ran, as the JSON output records them.
nlohmann::json OptionsToJson(const Flags& flags) {
  const comic::frontend::ComicDetectorOptions& options = flags.options;
  const comic::frontend::ComicDirectDetectorOptions& direct = flags.direct;
  return flags.paper
             ? nlohmann::json{{"scale", options.scale},
                              {"block_size", options.block_size},
                              {"delta", options.delta},
                              {"half_length", options.half_length},
                              {"max_iterations", options.max_iterations},
                              {"convergence_tolerance", options.convergence_tolerance},
                              {"stop_tolerance", options.stop_tolerance},
                              {"seed_neighbouring_corners", options.seed_neighbouring_corners},
                              {"skip_duplicate_paths", options.skip_duplicate_paths},
                              {"merge_radius", options.merge_radius},
                              {"min_stability", options.min_stability},
                              {"min_cornerness", options.min_cornerness},
                              {"coarse_initialisation", options.coarse_initialisation}}
             : nlohmann::json{{"scale", direct.scale},
                              {"delta", direct.delta},
                              {"half_length", direct.half_length},
                              {"min_cornerness", direct.min_cornerness},
                              {"level_radius", direct.level_radius},
                              {"link_radius", direct.link_radius},
                              {"consensus_fraction", direct.consensus_fraction},
                              {"presmoothing_sigma", direct.presmoothing_sigma},
                              {"merge_radius", direct.merge_radius},
                              {"min_stability", direct.min_stability}};
}

std::unique_ptr<comic::frontend::Detector> MakeDetector(const Flags& flags) {
  if (flags.paper) return std::make_unique<comic::frontend::ComicDetector>(flags.options);
  return std::make_unique<comic::frontend::ComicDirectDetector>(flags.direct);
}

// Detects, times and keeps the --max-features strongest.
FeatureSet DetectStrongest(const comic::frontend::Detector& detector, const cv::Mat& gray,
                           int max_features, double& ms) {
  const auto start = std::chrono::steady_clock::now();
  FeatureSet features = detector.Detect(gray);
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (max_features > 0 && static_cast<int>(features.size()) > max_features) {
    features.resize(max_features);
  }
  return features;
}

void WriteJson(const Flags& flags, const comic::io::LoadedImage& image,
               const comic::frontend::Detector& detector, const FeatureSet& features,
               comic::io::StagedFiles& outputs) {
  nlohmann::json features_json = nlohmann::json::array();
  for (const Feature& f : features) features_json.push_back(FeatureToJson(f));
  const nlohmann::json root = {{"image", flags.input},
                               {"width", image.gray.cols},
                               {"height", image.gray.rows},
                               {"detector", detector.Name()},
                               {"options", OptionsToJson(flags)},
                               {"features", features_json}};
  outputs.WriteFile(flags.json_path, comic::io::JsonText(root, 1));
}

int Run(int argc, char** argv) {
  Flags flags;
  comic::apps::ArgParser parser(
      "comic_detect", "IMAGE [--overlay overlay.png] [--json features.json] [options]",
      "Detects CoMIC features (Corners on Maximally-stable Iso-intensity Curves, Ravindran &\n"
      "Mittal) in IMAGE (colour and 16-bit images are converted to 8-bit grey), draws them with\n"
      "their maximally stable iso-curve segments, and writes them as JSON. Prints a summary.");
  AddFlags(parser, flags);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  flags.Check();

  // Both outputs are checked now and renamed into place together at the end (all or nothing).
  comic::io::StagedFiles outputs;
  if (!flags.overlay_path.empty()) {
    outputs.Stage(flags.overlay_path);
    comic::io::CheckImageOutputFormat(flags.overlay_path, "--overlay");
  }
  if (!flags.json_path.empty()) outputs.Stage(flags.json_path);

  const comic::io::LoadedImage image =
      comic::io::LoadImage(flags.input, flags.resize_height, flags.max_pixels);
  const std::unique_ptr<comic::frontend::Detector> detector = MakeDetector(flags);
  double ms = 0.0;
  const FeatureSet features = DetectStrongest(*detector, image.gray, flags.max_features, ms);

  int bright = 0;
  for (const Feature& f : features) bright += f.polarity == Polarity::kBright;
  std::cout << "image:    " << flags.input << " (" << image.gray.cols << "x" << image.gray.rows
            << ")\n"
            << "features: " << features.size() << " (" << bright << " bright, "
            << features.size() - bright << " dark)\n"
            << "time:     " << ms << " ms\n";
  if (!flags.overlay_path.empty()) {
    outputs.WriteImage(flags.overlay_path, DrawOverlay(image.color, features));
  }
  if (!flags.json_path.empty()) WriteJson(flags, image, *detector, features, outputs);
  outputs.Commit();
  if (!flags.overlay_path.empty()) std::cout << "overlay:  " << flags.overlay_path << "\n";
  if (!flags.json_path.empty()) std::cout << "json:     " << flags.json_path << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_detect", [&] { return Run(argc, argv); });
}
