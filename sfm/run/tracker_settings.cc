#include "sfm/run/tracker_settings.h"

#include "frontend/matching/track_builder.h"
#include "io/core/error.h"
#include "sfm/sequence_reconstruction.h"

namespace comic::sfm {

namespace {

// Parses `value` with `parse`, its error message prefixed with the option's name.
template <typename Parse>
auto ParseNamed(const std::string& option, const std::string& value, Parse parse) {
  try {
    return parse(value);
  } catch (const Error& e) {
    throw Error(e.kind(), option + ": " + e.what());
  }
}

}  // namespace

frontend::TrackerOptions DefaultRunTrackerOptions() {
  return SequenceReconstructionOptions().tracker;
}

frontend::TrackerOptions TrackerSettings::ToTrackerOptions() const {
  frontend::TrackerOptions options = DefaultRunTrackerOptions();
  if (max_features) options.max_features = *max_features;
  if (search_radius) options.matcher.radius = *search_radius;
  if (unpredicted_radius) options.unpredicted_radius = *unpredicted_radius;
  if (prediction) {
    options.prediction = ParseNamed("--prediction", *prediction, frontend::ParseMotionPrediction);
  }
  if (coarse_radius) options.coarse_radius = *coarse_radius;
  if (match_window) options.match_window = *match_window;
  if (track_conflicts) {
    options.conflict_rule =
        ParseNamed("--track-conflicts", *track_conflicts, frontend::ParseTrackConflictRule);
  }
  if (verify_min_gap) options.verify_min_gap = *verify_min_gap;
  if (match_turned) options.match_turned_180 = *match_turned;
  if (max_cost) options.matcher.max_cost = *max_cost;
  if (align_patches) options.align_patches = *align_patches;
  if (min_window_eigenvalue) options.min_window_eigenvalue = *min_window_eigenvalue;
  if (continuation) options.continuation = *continuation;
  options.Check();
  return options;
}

std::string TrackerSettings::TrackConflictsName() const {
  return track_conflicts.value_or(
      frontend::TrackConflictRuleName(DefaultRunTrackerOptions().conflict_rule));
}

frontend::PairingChoice ChooseRunPairing(const std::string& matching,
                                         const TrackerSettings& settings,
                                         const io::ImageSequence& sequence) {
  const frontend::Pairing requested = frontend::ParsePairing(matching);
  if (requested.mode != frontend::PairingMode::kAuto) {
    return frontend::ChoosePairing({}, requested);
  }
  if (settings.match_window) {
    frontend::PairingChoice choice;
    choice.requested = requested;
    choice.chosen = {frontend::PairingMode::kSequential, 0};
    choice.reason = "--match-window given: the tracker flags as given decide the pairs";
    return choice;
  }
  return frontend::ChoosePairing(frontend::ThumbnailsOf(sequence), requested);
}

frontend::TrackerOptions TrackerOptionsForRun(const TrackerSettings& settings,
                                              const frontend::PairingChoice& choice,
                                              int num_frames) {
  const frontend::TrackerOptions given = settings.ToTrackerOptions();
  frontend::TrackerOptions options =
      frontend::TrackerOptionsForPairing(choice.chosen, num_frames, given);
  // The fields a pairing sets, kept where they were given.
  if (settings.match_window) options.match_window = given.match_window;
  if (settings.verify_min_gap) options.verify_min_gap = given.verify_min_gap;
  if (settings.match_turned) options.match_turned_180 = given.match_turned_180;
  if (settings.prediction) options.prediction = given.prediction;
  if (settings.coarse_radius) options.coarse_radius = given.coarse_radius;
  if (settings.search_radius) options.matcher.radius = given.matcher.radius;
  if (settings.max_cost) options.matcher.max_cost = given.matcher.max_cost;
  if (settings.align_patches) options.align_patches = given.align_patches;
  if (settings.min_window_eigenvalue) options.min_window_eigenvalue = given.min_window_eigenvalue;
  if (settings.continuation) options.continuation = given.continuation;
  options.Check();
  return options;
}

std::optional<frontend::ImageSetMatchingOptions> ImageSetMatchingForRun(
    const std::string& matcher, const frontend::PairingChoice& choice,
    const frontend::TrackerOptions& tracker, int threads) {
  const frontend::FeatureMatcher chosen = frontend::ParseFeatureMatcher(matcher);
  if (!frontend::MatchesByDescriptors(chosen, choice)) return std::nullopt;
  // --match-window is the patch tracker's: given with auto, the tracker matches as it says.
  if (chosen == frontend::FeatureMatcher::kAuto && tracker.match_window > 1) return std::nullopt;
  return frontend::ImageSetMatchingOptionsForPairing(choice.chosen, tracker, threads);
}

}  // namespace comic::sfm
