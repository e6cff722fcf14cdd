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

int Run(int argc, char** argv) {
  sfm::ColmapExportRunOptions options;
  int max_pixels = static_cast<int>(comic::io::kDefaultMaxPixels);
  comic::apps::TrackerFlags tracker_flags;  // comic_sfm's defaults: the same tracks as it builds
  bool quiet = false;

  comic::apps::ArgParser parser(
      "comic_export_colmap", "FRAMES --colmap-db DB [options]",
      "Detects and tracks features through FRAMES (a folder of images or a video) and writes\n"
      "them as a COLMAP 3.8 database: one camera, one image per frame with its features as\n"
      "keypoints, and for every pair of frames at most --window apart that share tracks the raw\n"
      "matches and the matches verified by two-view geometry (essential matrix with --intrinsics, "
      "fundamental\n"
      "matrix without). Then prints the `colmap mapper` command to run on it, with the options\n"
      "the sequence needs. The database is written completely or not at all. With the same\n"
      "options `comic_sfm FRAMES --colmap-db DB` writes the same database. A video's frames are\n"
      "written as PNGs (--write-frames) and are COLMAP's --image_path.");
  parser.AddPositional("FRAMES",
                       "folder of images, or video file (its frames are written as images, see "
                       "--write-frames)",
                       &options.frames);
  comic::apps::AddColmapDbFlags(parser, &options.colmap);
  parser.AddDeprecatedAlias("output", "colmap-db");
  comic::apps::AddIntrinsicsFlag(parser, &options.camera.intrinsics);
  comic::apps::AddCameraModelFlag(parser, &options.camera.camera_model);
  comic::apps::AddDetectorFlag(parser, &options.detector);
  comic::apps::AddMatchingFlag(parser, &options.matching);
  comic::apps::AddTrackerFlags(parser, &tracker_flags);
  parser.AddDeprecatedAlias("radius", "search-radius");
  comic::apps::AddFrameRangeFlags(parser, &options.sequence);
  comic::apps::AddThreadsFlag(parser, &options.threads);
  parser.AddOption("image-path", "DIR",
                   "COLMAP's --image_path: FRAMES (default) or a folder above it; image names "
                   "are relative to it",
                   &options.image_path);
  parser.AddOption("sparse", "DIR",
                   "output folder in the printed mapper command (default: DB's folder/sparse)",
                   &options.sparse);
  comic::apps::AddMaxPixelsFlag(parser, &max_pixels);
  comic::apps::AddResizeHeightFlag(parser, &options.sequence.resize_height);
  parser.AddOptionalValueOption(
      "write-frames", "DIR",
      "video input: write each frame once as DIR/frame_000000.png ..., the names the database "
      "uses, and use DIR as COLMAP's --image_path (default, and alone: images/ beside DB)",
      sfm::kFramesBesideDatabase, &options.write_frames);
  comic::apps::AddQuietFlag(parser, &quiet);
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
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  options.sequence.max_pixels = max_pixels;
  options.tracker = comic::apps::ToTrackerSettings(tracker_flags, parser);

  std::unique_ptr<comic::apps::ProgressLine> progress;
  sfm::RunCallbacks callbacks;
  callbacks.stage_started = [&](sfm::RunStage stage, const std::string& detector) {
    progress = std::make_unique<comic::apps::ProgressLine>(
        stage == sfm::RunStage::kTracking
            ? "comic_export_colmap: [" + detector + "] detection and tracking"
            : "comic_export_colmap: writing frames",
        quiet);
  };
  callbacks.frame_done = [&](size_t done, size_t total) {
    if (progress) progress->Update(done, total);
  };
  const sfm::ColmapExportRunResult result = sfm::RunColmapExport(options, callbacks);
  comic::apps::PrintWarning("comic_export_colmap", result.warning);
  for (const std::string& line : sfm::ColmapExportReportLines(options, result)) {
    std::cout << line << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_export_colmap", [&] { return Run(argc, argv); });
}
