// The flags of a COLMAP database export (sfm/colmap/colmap_export.h), shared by
// `comic_sfm --colmap-db` and comic_export_colmap so that the same folder with the same options
// gives the same database from both: the path, --overwrite, the pair window, the two-view
// verification and the thread count of the printed `colmap mapper` command.
#pragma once

#include <string>

#include "apps/common/arg_parser.h"
#include "sfm/colmap/colmap_export.h"

namespace comic::apps {

struct ColmapDbFlags {
  std::string database;                     // --colmap-db; empty = none
  bool overwrite = false;                   // replace an existing database
  sfm::ColmapExportOptions export_options;  // --window, --max-error, --min-inliers
  int colmap_threads = -1;                  // --Mapper.num_threads (-1: COLMAP's default)
};

void AddColmapDbFlags(ArgParser& parser, ColmapDbFlags* flags);

// Throws comic::Error(kInvalidArgument) naming the bad flag (the export options, the thread
// count, --overwrite without --colmap-db); does not touch the file system.
void CheckColmapDbFlags(const ColmapDbFlags& flags);

}  // namespace comic::apps
