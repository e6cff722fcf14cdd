// The tracker's flags, one per entry of the library's tracker table
// (sfm/run/tracker_option_table.h), shared by the apps that track a sequence (comic_sfm,
// comic_export_colmap, comic_render_eval, comic_track_survival) so that all take the same
// options with the same defaults and so build the same tracks from the same folder.
#pragma once

#include <map>
#include <string>

#include "apps/common/arg_parser.h"
#include "frontend/matching/tracker.h"
#include "sfm/run/tracker_settings.h"

namespace comic::apps {

struct TrackerFlags {
  // Starts from sfm::DefaultRunTrackerOptions(): 2000 features, constant-velocity prediction,
  // 60 px where nothing predicts (the defaults of the apps that track).
  TrackerFlags();

  frontend::TrackerOptions options;          // the numeric fields and switches are bound directly
  std::map<std::string, std::string> names;  // a named field's value, by flag (--prediction)
  std::map<std::string, int> numbered;       // a bool given as 1 or 0, by flag (--align-patches)
};

void AddTrackerFlags(ArgParser& parser, TrackerFlags* flags);

// The tracker flags given on the command line (parser.WasSet), as the run's settings: the others
// keep the run's defaults, set up for the pairing --matching chooses (sfm/run/tracker_settings.h).
// Throws comic::Error(kInvalidArgument) naming a bad value.
sfm::TrackerSettings ToTrackerSettings(const TrackerFlags& flags, const ArgParser& parser);

// Every tracker flag as given or defaulted, parsed and Check()ed (comic_track_survival, which
// tracks without a pairing choice).
frontend::TrackerOptions ToTrackerOptions(const TrackerFlags& flags);

}  // namespace comic::apps
