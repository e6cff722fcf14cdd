// The flags of a COLMAP database export (sfm/colmap/colmap_export.h), shared by
// `comic_sfm --colmap-db` and comic_export_colmap so that the same folder with the same options
// gives the same database from both: the path, --overwrite, the pair window, the two-view
// verification and the thread count of the printed `colmap mapper` command. They bind to
// sfm::ColmapDatabaseOptions (sfm/run/run_options.h), whose Check() names the bad flag.
#pragma once

#include "apps/common/arg_parser.h"
#include "sfm/run/run_options.h"

namespace comic::apps {

void AddColmapDbFlags(ArgParser& parser, sfm::ColmapDatabaseOptions* options);

}  // namespace comic::apps
