#include "apps/common/colmap_db_flags.h"

namespace comic::apps {

void AddColmapDbFlags(ArgParser& parser, sfm::ColmapDatabaseOptions* options) {
  parser.AddOption("colmap-db", "DB",
                   "write the tracks as a COLMAP 3.8 database and print the `colmap mapper` "
                   "command to run on it (see docs/colmap.md)",
                   &options->colmap_db);
  parser.AddFlag("overwrite", "replace --colmap-db if it exists (otherwise it is refused)",
                 &options->overwrite);
  parser.AddOption("window", "K", "--colmap-db: pair frames at most K apart that share tracks",
                   &options->export_options.pair_window);
  parser.AddOption("max-error", "PX", "--colmap-db: two-view RANSAC inlier threshold, pixels",
                   &options->export_options.two_view.max_error_px);
  parser.AddOption("min-inliers", "N",
                   "--colmap-db: a pair with fewer verified matches is DEGENERATE",
                   &options->export_options.two_view.min_num_inliers);
  parser.AddOption("colmap-threads", "N",
                   "--Mapper.num_threads of COLMAP's mapper (-1 = COLMAP's default, every core)",
                   &options->colmap_threads);
}

}  // namespace comic::apps
