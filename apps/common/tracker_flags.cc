#include "apps/common/tracker_flags.h"

#include "apps/common/shared_flags.h"
#include "frontend/matching/track_builder.h"
#include "sfm/run/tracker_settings.h"

namespace comic::apps {

TrackerFlags::TrackerFlags()
    : options(sfm::DefaultRunTrackerOptions()),
      prediction(frontend::MotionPredictionName(options.prediction)),
      track_conflicts(frontend::TrackConflictRuleName(options.conflict_rule)) {}

void AddTrackerFlags(ArgParser& parser, TrackerFlags* flags) {
  frontend::TrackerOptions& options = flags->options;
  AddMaxFeaturesFlag(parser, &options.max_features);
  AddSearchRadiusFlag(parser, &options.matcher.radius);
  parser.AddOption("unpredicted-radius", "PX",
                   "tracker search radius where no motion predicts a feature (0 = "
                   "--search-radius)",
                   &options.unpredicted_radius);
  parser.AddOption("prediction", "P", "tracker motion prediction: none, velocity, coarse-to-fine",
                   &flags->prediction);
  parser.AddOption("coarse-radius", "PX",
                   "coarse-to-fine prediction: search radius of the coarse pass (pixels of the "
                   "frames as used)",
                   &options.coarse_radius);
  parser.AddOption("match-window", "K",
                   "match each frame to the next K frames, not only the next one, and build the "
                   "tracks from all the matches (sparse image sets: links views across a wide or "
                   "failed step)",
                   &options.match_window);
  parser.AddOption("track-conflicts", "RULE",
                   "--match-window > 1: a set of matches holding two features of one frame is "
                   "'drop'ped whole, or split 'greedy' (nearer frames' matches first, then lower "
                   "cost; a match joining two features of one frame is refused)",
                   &flags->track_conflicts);
  parser.AddOption("verify-min-gap", "G",
                   "verify the matches of frame pairs at least G frames apart with a fundamental "
                   "matrix (RANSAC, 2 px); a pair no epipolar geometry explains loses its matches "
                   "(0 = none)",
                   &options.verify_min_gap);
  parser.AddFlag(
      "match-turned",
      "also match each verified pair with the later frame turned by 180 degrees and keep "
      "the hypothesis with more verified matches (Middlebury rings: views of the other "
      "latitude sign are upside down; needs --verify-min-gap)",
      &options.match_turned_180);
  AddMaxCostFlag(parser, &options.matcher.max_cost);
}

sfm::TrackerSettings ToTrackerSettings(const TrackerFlags& flags, const ArgParser& parser) {
  const frontend::TrackerOptions& o = flags.options;
  sfm::TrackerSettings settings;
  if (parser.WasSet("max-features")) settings.max_features = o.max_features;
  if (parser.WasSet("search-radius")) settings.search_radius = o.matcher.radius;
  if (parser.WasSet("unpredicted-radius")) settings.unpredicted_radius = o.unpredicted_radius;
  if (parser.WasSet("prediction")) settings.prediction = flags.prediction;
  if (parser.WasSet("coarse-radius")) settings.coarse_radius = o.coarse_radius;
  if (parser.WasSet("match-window")) settings.match_window = o.match_window;
  if (parser.WasSet("track-conflicts")) settings.track_conflicts = flags.track_conflicts;
  if (parser.WasSet("verify-min-gap")) settings.verify_min_gap = o.verify_min_gap;
  if (parser.WasSet("match-turned")) settings.match_turned = o.match_turned_180;
  if (parser.WasSet("max-cost")) settings.max_cost = o.matcher.max_cost;
  return settings;
}

}  // namespace comic::apps
