// comic_sfm: structure from motion on a frame sequence. Detects and tracks features with the
// chosen detector, reconstructs the cameras and points incrementally (two-view initialisation,
// PnP, triangulation, Ceres bundle adjustment), and writes a COLMAP model (text, and binary under
// sparse/0/), a coloured PLY point cloud, report.json and a top-view trajectory plot; with
// ground-truth cameras it also reports the Sim(3)-aligned trajectory error. --compare runs several
// detectors on the same frames and writes one table. The run is the library's
// (sfm/run/reconstruction_run.h), the one comic.reconstruct calls; this file only turns flags into
// its options and prints its progress.
#include <iostream>
#include <memory>
#include <string>
#include <type_traits>
#include <variant>

#include "apps/common/arg_parser.h"
#include "apps/common/colmap_db_flags.h"
#include "apps/common/frame_range_flags.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/matching_flags.h"
#include "apps/common/progress_line.h"
#include "apps/common/shared_flags.h"
#include "apps/common/tracker_flags.h"
#include "io/core/error.h"
#include "io/core/interrupt_cleanup.h"
#include "sfm/bundle_adjuster.h"
#include "sfm/run/reconstruction_run.h"
#include "sfm/run/run_messages.h"
#include "sfm/run/run_option_table.h"

namespace {

namespace apps = comic::apps;
namespace sfm = comic::sfm;

// The flags that do not bind to a field of sfm::ReconstructionRunOptions as they are.
struct CommandLine {
  std::string detector = "harris";
  int max_pixels = static_cast<int>(comic::io::kDefaultMaxPixels);
  apps::TrackerFlags tracker;
  apps::ObjectRegionFlags region{"", "", sfm::ReconstructionRunOptions().boundary_band};
  bool mask_keeps_nonzero = false;  // --mask-keeps-nonzero: COLMAP's mask convention
  bool quiet = false;
};

// One flag per entry of the library's option table, bound to its field in `o`.
void AddTableFlags(apps::ArgParser& parser, sfm::ReconstructionRunOptions* o) {
  for (const sfm::RunOption& entry : sfm::RunOptionTable()) {
    std::visit(
        [&](auto field) {
          auto* value = &field(*o);
          if constexpr (std::is_same_v<decltype(value), bool*>) {
            parser.AddFlag(entry.flag, entry.help, value);
          } else {
            parser.AddOption(entry.flag, entry.metavar, entry.help, value);
          }
        },
        entry.field);
  }
}

// The flags shared with other apps (apps/common/) or needing more than a field, then the table's.
void AddRunFlags(apps::ArgParser& parser, sfm::ReconstructionRunOptions* o, CommandLine* c) {
  parser.AddPositional("FRAMES", "folder of images, or video file", &o->frames);
  apps::AddDetectorFlag(parser, &c->detector);
  apps::AddScaleLevelsFlag(parser, &o->detector_options.scale_space.num_levels);
  apps::AddDetectorListFlag(parser, &o->detectors);
  apps::AddIntrinsicsFlag(parser, &o->camera.intrinsics);
  apps::AddCameraModelFlag(parser, &o->camera.camera_model);
  apps::AddAllowTruncatedFlag(parser, &o->sequence.allow_truncated);
  apps::AddMaxPixelsFlag(parser, &c->max_pixels);
  apps::AddOutputFolderFlag(parser, &o->output);
  apps::AddResizeHeightFlag(parser, &o->sequence.resize_height);
  apps::AddFrameRangeFlags(parser, &o->sequence);
  apps::AddMatchingFlag(parser, &o->matching);
  apps::AddMatcherFlag(parser, &o->matcher);
  apps::AddTrackerFlags(parser, &c->tracker);
  apps::AddThreadsFlag(parser, &o->threads);
  apps::AddObjectRegionFlags(parser, &c->region);
  parser.AddFlag("mask-keeps-nonzero",
                 "--masks in COLMAP's convention (ImageReader.mask_path): features are removed "
                 "where a mask is zero; by default (DAVIS annotations) where it is non-zero",
                 &c->mask_keeps_nonzero);
  apps::AddQuietFlag(parser, &c->quiet);
  apps::AddColmapDbFlags(parser, &o->colmap);
  parser.AddOptionalValueOption(
      "write-frames", "DIR",
      "video input: write each frame once as DIR/frame_000000.png ..., the names the model and "
      "--colmap-db use, so that COLMAP's image tools find them (alone: images/ in --output)",
      sfm::kFramesInOutput, &o->write_frames);
  AddTableFlags(parser, o);
}

// The flags that need the parser (which were given) or a conversion, into the options.
void FinishOptions(const apps::ArgParser& parser, const CommandLine& c,
                   sfm::ReconstructionRunOptions* o) {
  if (parser.WasSet("detector")) o->detector = c.detector;
  o->sequence.max_pixels = c.max_pixels;
  o->tracker = apps::ToTrackerSettings(c.tracker, parser);
  o->masks = c.region.masks;
  o->mask_drops_nonzero = !c.mask_keeps_nonzero;
  o->regions = c.region.regions;
  o->boundary_band = c.region.boundary_band;
}

// Progress on stdout as the run goes: the inputs (even with --quiet: which intrinsics),
// per-frame progress lines, each registered frame, each detector's summary (even with --quiet).
class ConsoleProgress {
 public:
  explicit ConsoleProgress(bool quiet) : quiet_(quiet) {}

  sfm::RunCallbacks Callbacks() {
    sfm::RunCallbacks callbacks;
    callbacks.inputs_resolved = [](const sfm::RunInputs& inputs) {
      apps::PrintWarning("comic_sfm", inputs.sequence->warning());
      for (const std::string& line : sfm::RunInputsLines(inputs, "comic_sfm")) {
        std::cout << line << std::endl;
      }
    };
    callbacks.stage_started = [this](sfm::RunStage stage, const std::string& detector) {
      if (stage == sfm::RunStage::kTracksFromCache) {
        line_.reset();
        if (!quiet_) std::cout << "[" << detector << "] tracks read from --cache" << std::endl;
        return;
      }
      // Detection and tracking are most of a run's time.
      line_ = std::make_unique<apps::ProgressLine>(stage == sfm::RunStage::kTracking
                                                       ? "[" + detector + "] detection and tracking"
                                                       : "comic_sfm: writing frames",
                                                   quiet_);
    };
    callbacks.frame_done = [this](size_t done, size_t total) {
      if (line_) line_->Update(done, total);
    };
    callbacks.warning = [](const std::string& message) {
      apps::PrintWarning("comic_sfm", message);
    };
    callbacks.note = [](const std::string& message) {
      std::cout << "comic_sfm: " << message << std::endl;
    };
    callbacks.frame_registered = [this](const std::string& detector,
                                        const sfm::MapperProgress& progress) {
      if (!quiet_) std::cout << sfm::FrameRegisteredLine(detector, progress) << std::endl;
    };
    callbacks.adjustment_progress = [this](const std::string& detector,
                                           const sfm::BundleAdjustmentProgress& progress) {
      // A solve reports every iteration once it has run a second: one line a second at most.
      if (progress.first) last_adjustment_second_ = 0;
      const int second = static_cast<int>(progress.elapsed_s);
      if (quiet_ || second <= last_adjustment_second_) return;
      last_adjustment_second_ = second;
      std::cout << sfm::AdjustmentProgressLine(detector, progress) << std::endl;
    };
    callbacks.detector_finished = [](const sfm::DetectorRun& run) {
      std::cout << sfm::DetectorSummaryLine(run) << std::endl;
    };
    return callbacks;
  }

 private:
  bool quiet_;
  std::unique_ptr<apps::ProgressLine> line_;
  int last_adjustment_second_ = 0;
};

int Run(int argc, char** argv) {
  sfm::ReconstructionRunOptions options;
  options.output = "out/sfm";
  CommandLine command_line;
  apps::ArgParser parser(
      "comic_sfm", "FRAMES [options]",
      "Structure from motion on a frame sequence (folder of images or video): tracks features\n"
      "with the chosen detector, reconstructs cameras and points incrementally with Ceres bundle\n"
      "adjustment, and writes into --output: cameras.txt, images.txt, points3D.txt (a COLMAP text\n"
      "model of the largest model; --model-format), sparse/<k>/{cameras,images,points3D}.bin\n"
      "(every model in COLMAP's binary format, sparse/0 the largest), points.ply (coloured point\n"
      "cloud; --ply-format), report.json\n"
      "(every number and the options), trajectory.png (top view; with --gt, ours Sim(3)-aligned\n"
      "against the ground truth).");
  AddRunFlags(parser, &options, &command_line);
  parser.AddEpilog(
      "Example (the bundled KITTI clip, calibrated from its calib.txt, measured against\n"
      "its poses.txt):\n"
      "  comic_sfm examples/data/kitti06_000-011/image_l \\\n"
      "      --gt examples/data/kitti06_000-011/poses.txt --output out/example --compare\n"
      "--regions/--masks add boundary and interior point statistics. --colmap-db writes what\n"
      "comic_export_colmap writes with the same options; for a folder of images it needs\n"
      "--resize-height 0, a video's frames it writes as --write-frames does (the folder given,\n"
      "or images/ in --output), and COLMAP's --image_path is that folder.\n"
      "--masks DIR (one mask per frame, non-zero = a moving object, as DAVIS annotations;\n"
      "COLMAP's convention with --mask-keeps-nonzero) also removes every feature a mask covers,\n"
      "or that lies within 2 px of it, before tracking or matching (report.json:\n"
      "masked_features).\n"
      "--threads: detection and the export; the bundle adjustments run on one thread (Ceres'\n"
      "multi-threaded sums are not bit-for-bit repeatable). Progress goes to stdout (-q: off);\n"
      "a failed run writes report.json with a diagnosis, tracks.db and, when the camera only\n"
      "turned, rotation_only/ (a camera path without points).\n"
      "Python: comic.reconstruct(FRAMES, ...) runs the same, with these options as keywords\n"
      "(--max-features -> max_features; python/README.md).\n"
      "Status: success when the largest model holds >= 95 % of the frames, else partial (the\n"
      "unregistered ranges and the check each failed are in the summary line and report.json).\n"
      "Exit codes: 0 a model holding at least --min-registered of the frames (default 0.5),\n"
      "2 usage error, 1 anything else (including a sequence that cannot be reconstructed or a\n"
      "smaller model, without --compare; the models are written all the same).");
  if (parser.Parse(argc, argv) == apps::ArgParser::Result::kHelpShown) return 0;
  FinishOptions(parser, command_line, &options);

  ConsoleProgress progress(command_line.quiet);
  const sfm::ReconstructionRunResult result = sfm::RunReconstruction(options, progress.Callbacks());
  for (const std::string& line :
       sfm::RunOutcomeLines(result, options.output, "comic_sfm", command_line.quiet)) {
    std::cout << line << std::endl;
  }
  COMIC_CHECK(result.success(), kInvalidData, result.failure);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Errors go to stderr as one line; Ceres' recoverable-trouble warnings would add noise there.
  comic::sfm::ShowOnlySolverErrors();
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_sfm", [&] { return Run(argc, argv); });
}
