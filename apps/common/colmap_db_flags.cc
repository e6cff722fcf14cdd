#include "apps/common/colmap_db_flags.h"

#include "apps/common/thread_count.h"
#include "io/core/error.h"
#include "sfm/colmap/colmap_runner.h"

namespace comic::apps {

void AddColmapDbFlags(ArgParser& parser, ColmapDbFlags* flags) {
  parser.AddOption("colmap-db", "DB",
                   "write the tracks as a COLMAP 3.8 database and print the `colmap mapper` "
                   "command to run on it (see docs/colmap.md)",
                   &flags->database);
  parser.AddFlag("overwrite", "replace --colmap-db if it exists (otherwise it is refused)",
                 &flags->overwrite);
  parser.AddOption("window", "K", "--colmap-db: pair frames at most K apart that share tracks",
                   &flags->export_options.pair_window);
  parser.AddOption("max-error", "PX", "--colmap-db: two-view RANSAC inlier threshold, pixels",
                   &flags->export_options.two_view.max_error_px);
  parser.AddOption("min-inliers", "N",
                   "--colmap-db: a pair with fewer verified matches is DEGENERATE",
                   &flags->export_options.two_view.min_num_inliers);
  parser.AddOption("colmap-threads", "N",
                   "--Mapper.num_threads of COLMAP's mapper (-1 = COLMAP's default, every core)",
                   &flags->colmap_threads);
}

void CheckColmapDbFlags(const ColmapDbFlags& flags) {
  COMIC_CHECK(!flags.overwrite || !flags.database.empty(), kInvalidArgument,
              "--overwrite needs --colmap-db");
  COMIC_CHECK(flags.colmap_threads == -1 || flags.colmap_threads >= 1, kInvalidArgument,
              "--colmap-threads must be -1 or >= 1, got " << flags.colmap_threads);
  // At most the machine's threads (issue 19: absurd counts were accepted).
  COMIC_CHECK(flags.colmap_threads <= HardwareThreads(), kInvalidArgument,
              "--colmap-threads must be at most the " << HardwareThreads()
                                                      << " hardware threads of this machine, got "
                                                      << flags.colmap_threads);
  flags.export_options.Check();
  sfm::ColmapMapperOptions mapper;
  mapper.num_threads = flags.colmap_threads;
  mapper.Check();
}

}  // namespace comic::apps
