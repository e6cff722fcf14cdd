// comic_detect: runs a CoMIC detector (the direct search "comic", or Algorithm 1 "comic-paper")
// on one image, draws the features and their maximally
// stable iso-curve segments (both polarities in different colours) and writes them as JSON.
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <type_traits>
#include <variant>

#include "apps/common/arg_parser.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/pixel_budget.h"
#include "io/core/protected_inputs.h"
#include "io/core/staged_files.h"
#include "io/image/image_io.h"
#include "io/report/json_text.h"
#include "sfm/run/detect_run.h"
#include "sfm/run/detector_option_table.h"

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

// The command line, bound to the parser by AddFlags; Check() validates it. The detector's options
// are the library's (sfm/run/detect_run.h), one flag per entry of its table.
struct Flags {
  void Check() const;

  std::string input;
  std::string overlay_path;
  std::string json_path;
  int resize_height = 0;
  int max_pixels = static_cast<int>(comic::io::kDefaultMaxPixels);
  comic::sfm::DetectRunOptions run;
};

// One flag per entry of the detector option table, bound to its field in `run`.
void AddTableFlags(comic::apps::ArgParser& parser, comic::sfm::DetectRunOptions* run) {
  for (const comic::sfm::DetectorOption& entry : comic::sfm::DetectorOptionTable()) {
    std::visit(
        [&](auto field) {
          auto* value = &field(*run);
          if constexpr (std::is_same_v<decltype(value), bool*>) {
            parser.AddFlag(entry.flag, entry.help, value);
          } else {
            parser.AddOption(entry.flag, entry.metavar, entry.help, value);
          }
        },
        entry.field);
  }
}

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("IMAGE", "input image (any format OpenCV reads)", &flags.input);
  parser.AddOption("overlay", "PNG", "write an overlay: features and their MSICS on the image",
                   &flags.overlay_path);
  parser.AddDeprecatedAlias("out", "overlay");
  comic::apps::AddJsonFlag(parser, &flags.json_path);
  comic::apps::AddResizeHeightFlag(parser, &flags.resize_height);
  // The shared --detector flag; comic_detect runs the two CoMIC searches only: comic (the direct
  // search of the paper's definition) or comic-paper (Algorithm 1).
  comic::apps::AddDetectorFlag(parser, &flags.run.detector);
  AddTableFlags(parser, &flags.run);
  comic::apps::AddThreadsFlag(parser, &flags.run.threads);
  comic::apps::AddMaxFeaturesFlag(parser, &flags.run.max_features);
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
      "the darker side; the line through each circle is its maximally stable iso-curve segment.\n"
      "Python: comic.detect(image, detector, **options) takes these options as keywords (the\n"
      "flag's name with '_' for '-') and gives the same features.\n");
}

void Flags::Check() const {
  comic::io::CheckResizeHeight(resize_height);
  comic::io::CheckMaxPixels(max_pixels);
  COMIC_CHECK(comic::sfm::IsComicSearch(run.detector), kInvalidArgument,
              "--detector: comic_detect runs comic or comic-paper (CoMIC's two searches), got '"
                  << run.detector << "'");
  run.Check();
  // Inputs are sacred: `--json img.png` must not replace the image.
  comic::io::CheckOutputsAvoidInputs({{"--overlay", overlay_path}, {"--json", json_path}},
                                     {{"IMAGE", input}});
}

// The options of the search that ran, as the JSON output records them (the search's own names).
nlohmann::json OptionsToJson(const comic::sfm::DetectRunOptions& run) {
  const comic::frontend::DetectorOptions searches = run.ToDetectorOptions();
  const comic::frontend::ComicDetectorOptions& options = searches.comic_paper;
  const comic::frontend::ComicDirectDetectorOptions& direct = searches.comic;
  return run.detector == "comic-paper"
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

void WriteJson(const Flags& flags, const comic::io::LoadedImage& image,
               const comic::sfm::DetectRunResult& result, comic::io::StagedFiles& outputs) {
  nlohmann::json features_json = nlohmann::json::array();
  for (const Feature& f : result.features) features_json.push_back(FeatureToJson(f));
  const nlohmann::json root = {{"image", flags.input},
                               {"width", image.gray.cols},
                               {"height", image.gray.rows},
                               {"detector", result.detector_name},
                               {"options", OptionsToJson(flags.run)},
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
  const comic::sfm::DetectRunResult result = comic::sfm::RunDetect(flags.run, image.gray);
  const FeatureSet& features = result.features;

  int bright = 0;
  for (const Feature& f : features) bright += f.polarity == Polarity::kBright;
  std::cout << "image:    " << flags.input << " (" << image.gray.cols << "x" << image.gray.rows
            << ")\n"
            << "features: " << features.size() << " (" << bright << " bright, "
            << features.size() - bright << " dark)\n"
            << "time:     " << result.milliseconds << " ms\n";
  if (!flags.overlay_path.empty()) {
    outputs.WriteImage(flags.overlay_path, DrawOverlay(image.color, features));
  }
  if (!flags.json_path.empty()) WriteJson(flags, image, result, outputs);
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
