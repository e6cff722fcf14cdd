// The keywords of comic.match, comic.track, comic.reconstruct and comic.export_colmap, named as
// the apps' flags (--search-radius -> search_radius), each bound to its field of the libraries'
// options. comic.reconstruct's plain options come from the library's table
// (sfm/run/run_option_table.h); the detectors' from theirs (detector_keywords.h).
#pragma once

#include "frontend/matching/patch_matcher.h"
#include "frontend/matching/tracker.h"
#include "io/image/image_sequence.h"
#include "python/keyword_options.h"
#include "sfm/run/colmap_export_run.h"
#include "sfm/run/reconstruction_run.h"

namespace comic::python {

// --search-radius, --cost, --min-side-overlap, --max-cost (apps/common/shared_flags.h).
void AddMatcherOptions(frontend::PatchMatcherOptions* m, OptionTable* table);

// comic.track: the shared tracker options, the matcher's cost, and the tracker's finer fields.
void AddTrackerOptions(frontend::TrackerOptions* t, OptionTable* table);

// --resize-height, --first, --last, --stride.
void AddSequenceOptions(io::ImageSequenceOptions* s, OptionTable* table);

// comic_sfm's options by their flags' names (apps/comic_sfm.cc and sfm/run/run_option_table.h),
// into the run's options; `quiet` receives quiet=.
OptionTable ReconstructOptionTable(sfm::ReconstructionRunOptions* o, bool* quiet);

// comic_export_colmap's options by their flags' names (apps/comic_export_colmap.cc).
OptionTable ExportOptionTable(sfm::ColmapExportRunOptions* o, bool* quiet);

}  // namespace comic::python
