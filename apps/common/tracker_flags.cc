#include "apps/common/tracker_flags.h"

#include "apps/common/shared_flags.h"
#include "frontend/matching/track_builder.h"
#include "io/core/error.h"
#include "sfm/run/tracker_settings.h"

namespace comic::apps {

TrackerFlags::TrackerFlags()
    : options(sfm::DefaultRunTrackerOptions()),
      prediction(frontend::MotionPredictionName(options.prediction)),
      track_conflicts(frontend::TrackConflictRuleName(options.conflict_rule)),
      align_patches(options.align_patches ? 1 : 0) {}

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
  parser.AddOption("align-patches", "BOOL",
                   "align each feature's patch into the next frame (pyramidal, gain and bias) and "
                   "search detections near where it aligned: 1 or 0",
                   &flags->align_patches);
  parser.AddOption("max-continued-frames", "N",
                   "with --align-patches 1: a track whose feature is not re-detected continues at "
                   "its aligned position for up to N consecutive frames (0 = never)",
                   &options.continuation.max_continued_frames);
  parser.AddOption("max-alignment-residual", "T",
                   "an alignment is trusted if its mean squared difference after gain and bias "
                   "is at most T (grey levels squared)",
                   &options.continuation.max_residual);
  parser.AddOption("aligned-radius", "PX",
                   "search radius for detections around a trusted alignment",
                   &options.continuation.aligned_radius);
  parser.AddOption("min-alignment-correlation", "C",
                   "an alignment is trusted if its normalised cross-correlation is at least C",
                   &options.continuation.min_correlation);
  parser.AddOption("alignment-min-eigenvalue", "E",
                   "windows with a weaker gradient moment are not aligned",
                   &options.continuation.alignment.min_eigenvalue);
  parser.AddOption("min-window-eigenvalue", "E",
                   "track only features whose 23x23 window has a gradient moment with both "
                   "eigenvalues >= E (grey levels squared per pixel squared; 0 = all)",
                   &options.min_window_eigenvalue);
  parser.AddOption("bridge-frames", "G",
                   "with --align-patches 1: a track lost at frame i is looked for again in frames "
                   "i+2 .. i+G (re-association after a gap; 0 = none)",
                   &options.continuation.bridge_frames);
  parser.AddOption("alignment-max-fb", "PX",
                   "an alignment counts only if aligning back returns within PX of the start (0 = "
                   "no check)",
                   &options.continuation.alignment.max_forward_backward_px);
  parser.AddOption("alignment-iterations", "N", "iterations per level of the patch alignment",
                   &options.continuation.alignment.max_iterations);
  parser.AddOption("alignment-levels", "N", "pyramid levels of the patch alignment",
                   &options.continuation.alignment.levels);
}

frontend::TrackerOptions ToTrackerOptions(const TrackerFlags& flags) {
  frontend::TrackerOptions options = flags.options;
  options.prediction = frontend::ParseMotionPrediction(flags.prediction);
  options.conflict_rule = frontend::ParseTrackConflictRule(flags.track_conflicts);
  COMIC_CHECK(flags.align_patches == 0 || flags.align_patches == 1, kInvalidArgument,
              "--align-patches must be 1 or 0, got " << flags.align_patches);
  options.align_patches = flags.align_patches == 1;
  options.Check();
  return options;
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
  if (parser.WasSet("align-patches")) {
    COMIC_CHECK(flags.align_patches == 0 || flags.align_patches == 1, kInvalidArgument,
                "--align-patches must be 1 or 0, got " << flags.align_patches);
    settings.align_patches = flags.align_patches == 1;
  }
  if (parser.WasSet("min-window-eigenvalue")) {
    settings.min_window_eigenvalue = o.min_window_eigenvalue;
  }
  for (const char* name : {"max-continued-frames", "max-alignment-residual", "aligned-radius",
                           "min-alignment-correlation", "alignment-min-eigenvalue", "bridge-frames",
                           "alignment-max-fb", "alignment-iterations", "alignment-levels"}) {
    if (parser.WasSet(name)) settings.continuation = o.continuation;
  }
  return settings;
}

}  // namespace comic::apps
