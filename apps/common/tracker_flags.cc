#include "apps/common/tracker_flags.h"

#include "apps/common/shared_flags.h"
#include "frontend/matching/track_builder.h"
#include "sfm/sequence_reconstruction.h"

namespace comic::apps {

TrackerFlags::TrackerFlags()
    : options(sfm::SequenceReconstructionOptions().tracker),
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

frontend::TrackerOptions ToTrackerOptions(const TrackerFlags& flags) {
  frontend::TrackerOptions options = flags.options;
  options.prediction = frontend::ParseMotionPrediction(flags.prediction);
  options.conflict_rule = frontend::ParseTrackConflictRule(flags.track_conflicts);
  options.Check();
  return options;
}

}  // namespace comic::apps
