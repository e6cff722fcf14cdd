// The tracker's flags (paper §4: frame-to-frame SSD patch matching within a radius, with the
// motion prediction real driving video needs), shared by the apps that track a sequence
// (comic_sfm, comic_export_colmap) so that both take the same options with the same defaults
// and so build the same tracks from the same folder.
#pragma once

#include <string>

#include "apps/common/arg_parser.h"
#include "frontend/matching/tracker.h"
#include "sfm/run/tracker_settings.h"

namespace comic::apps {

struct TrackerFlags {
  // Starts from sfm::SequenceReconstructionOptions' tracker: 2000 features, constant-velocity
  // prediction, 60 px where nothing predicts (the defaults of both apps).
  TrackerFlags();

  frontend::TrackerOptions options;  // the numeric and boolean fields are bound directly
  std::string prediction;            // MotionPredictionName
  std::string track_conflicts;       // TrackConflictRuleName
  int align_patches;                 // options.align_patches as 1 or 0 (a default-on switch)
};

void AddTrackerFlags(ArgParser& parser, TrackerFlags* flags);

// The tracker flags given on the command line (parser.WasSet), as the run's settings: the others
// keep the run's defaults, set up for the pairing --matching chooses (sfm/run/tracker_settings.h).
sfm::TrackerSettings ToTrackerSettings(const TrackerFlags& flags, const ArgParser& parser);

// Every tracker flag as given or defaulted, parsed and Check()ed (comic_track_survival, which
// tracks without a pairing choice).
frontend::TrackerOptions ToTrackerOptions(const TrackerFlags& flags);

}  // namespace comic::apps
