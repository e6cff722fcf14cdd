// comic_export_colmap: tracks features through a folder of frames or a video and writes a COLMAP
// 3.8 database (cameras, images, keypoints, raw and verified matches) for `colmap mapper`, then
// prints the exact mapper command the sequence needs. A video's frames are written as PNGs
// (--write-frames), since COLMAP reads image files.
#include <iostream>
#include <memory>
#include <string>

#include "apps/common/arg_parser.h"
#include "apps/common/colmap_db_flags.h"
#include "apps/common/frame_range_flags.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/matching_flags.h"
#include "apps/common/progress_line.h"
#include "apps/common/shared_flags.h"
#include "apps/common/tracker_flags.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/pixel_budget.h"
#include "sfm/run/colmap_export_run.h"

namespace {

namespace sfm = comic::sfm;

// The command line, bound to the parser by AddFlags.
struct Flags {
  sfm::ColmapExportRunOptions options;
  int max_pixels = static_cast<int>(comic::io::kDefaultMaxPixels);
  comic::apps::TrackerFlags tracker_flags;  // comic_sfm's defaults: the same tracks as it builds
  bool quiet = false;
};

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("FRAMES",
                       "folder of images, or video file (its frames are written as images, see "
                       "--write-frames)",
                       &flags.options.frames);
  comic::apps::AddColmapDbFlags(parser, &flags.options.colmap);
  parser.AddDeprecatedAlias("output", "colmap-db");
  comic::apps::AddIntrinsicsFlag(parser, &flags.options.camera.intrinsics);
  comic::apps::AddCameraModelFlag(parser, &flags.options.camera.camera_model);
  comic::apps::AddDetectorFlag(parser, &flags.options.detector);
  comic::apps::AddMatchingFlag(parser, &flags.options.matching);
  comic::apps::AddMatcherFlag(parser, &flags.options.matcher);
  comic::apps::AddTrackerFlags(parser, &flags.tracker_flags);
  parser.AddDeprecatedAlias("radius", "search-radius");
  comic::apps::AddFrameRangeFlags(parser, &flags.options.sequence);
  comic::apps::AddThreadsFlag(parser, &flags.options.threads);
  parser.AddOption("image-path", "DIR",
                   "COLMAP's --image_path: FRAMES (default) or a folder above it; image names "
                   "are relative to it",
                   &flags.options.image_path);
  parser.AddOption("sparse", "DIR",
                   "output folder in the printed mapper command (default: DB's folder/sparse)",
                   &flags.options.sparse);
  comic::apps::AddMaxPixelsFlag(parser, &flags.max_pixels);
  comic::apps::AddResizeHeightFlag(parser, &flags.options.sequence.resize_height);
  parser.AddOptionalValueOption(
      "write-frames", "DIR",
      "video input: write each frame once as DIR/frame_000000.png ..., the names the database "
      "uses, and use DIR as COLMAP's --image_path (default, and alone: images/ beside DB)",
      sfm::kFramesBesideDatabase, &flags.options.write_frames);
  comic::apps::AddQuietFlag(parser, &flags.quiet);
  parser.AddEpilog(
      "Without --intrinsics the camera is COLMAP's SIMPLE_RADIAL guess (or --camera-model's).\n"
      "Example (the bundled KITTI clip):\n"
      "  comic_export_colmap examples/data/kitti06_000-011/image_l --colmap-db kitti.db \\\n"
      "      --intrinsics examples/data/kitti06_000-011/calib.txt\n"
      "prints, among its report, the command to run, e.g.\n"
      "  mkdir -p sparse && colmap mapper --database_path kitti.db --image_path ... \\\n"
      "      --output_path sparse --Mapper.init_max_forward_motion 1 ...\n"
      "For forward motion COLMAP's default --Mapper.init_max_forward_motion 0.95 and\n"
      "--Mapper.init_min_tri_angle 16 reject every initial pair; the printed values let it start.\n"
      "Known intrinsics are held fixed (--Mapper.ba_refine_* 0).\n"
      "Python: comic.export_colmap(FRAMES, DB, ...) runs the same (python/README.md).\n");
}

int Run(int argc, char** argv) {
  Flags flags;
  comic::apps::ArgParser parser(
      "comic_export_colmap", "FRAMES --colmap-db DB [options]",
      "Detects and tracks features through FRAMES (a folder of images or a video) and writes\n"
      "them as a COLMAP 3.8 database: one camera, one image per frame with its features as\n"
      "keypoints and descriptors, and for every pair of frames at most --window apart that share\n"
      "tracks the raw\n"
      "matches and the matches verified by two-view geometry (essential matrix with --intrinsics, "
      "fundamental\n"
      "matrix without). Then prints the `colmap mapper` command to run on it, with the options\n"
      "the sequence needs. The database is written completely or not at all. With the same\n"
      "options `comic_sfm FRAMES --colmap-db DB` writes the same database. A video's frames are\n"
      "written as PNGs (--write-frames) and are COLMAP's --image_path.");
  AddFlags(parser, flags);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  flags.options.sequence.max_pixels = flags.max_pixels;
  flags.options.tracker = comic::apps::ToTrackerSettings(flags.tracker_flags, parser);

  std::unique_ptr<comic::apps::ProgressLine> progress;
  sfm::RunCallbacks callbacks;
  callbacks.stage_started = [&](sfm::RunStage stage, const std::string& detector) {
    progress = std::make_unique<comic::apps::ProgressLine>(
        stage == sfm::RunStage::kTracking
            ? "comic_export_colmap: [" + detector + "] detection and tracking"
            : "comic_export_colmap: writing frames",
        flags.quiet);
  };
  callbacks.frame_done = [&](size_t done, size_t total) {
    if (progress) progress->Update(done, total);
  };
  const sfm::ColmapExportRunResult result = sfm::RunColmapExport(flags.options, callbacks);
  comic::apps::PrintWarning("comic_export_colmap", result.warning);
  for (const std::string& line : sfm::ColmapExportReportLines(flags.options, result)) {
    std::cout << line << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_export_colmap", [&] { return Run(argc, argv); });
}
