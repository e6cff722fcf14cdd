#include "sfm/run/tracker_settings.h"

#include "frontend/matching/track_builder.h"
#include "io/core/error.h"
#include "sfm/run/tracker_option_table.h"
#include "sfm/sequence_reconstruction.h"

namespace comic::sfm {

frontend::TrackerOptions DefaultRunTrackerOptions() {
  return SequenceReconstructionOptions().tracker;
}

void TrackerSettings::MarkGiven(const std::string& flag) {
  given.insert(FindTrackerOption(flag).flag);  // throws for a flag the table lacks
}

void TrackerSettings::GiveName(const std::string& flag, const std::string& name) {
  const TrackerOption entry = FindTrackerOption(flag);
  const auto* named = std::get_if<TrackerOption::Named>(&entry.field);
  COMIC_CHECK(named != nullptr, kInvalidArgument, "--" << flag << " is not given by a name");
  named->set(values, name);
  given.insert(flag);
}

frontend::TrackerOptions TrackerSettings::ToTrackerOptions() const {
  for (const std::string& flag : given) FindTrackerOption(flag);  // each one the table's
  values.Check();
  return values;
}

std::string TrackerSettings::TrackConflictsName() const {
  return frontend::TrackConflictRuleName(values.conflict_rule);
}

frontend::PairingChoice ChooseRunPairing(const std::string& matching,
                                         const TrackerSettings& settings,
                                         const io::ImageSequence& sequence) {
  const frontend::Pairing requested = frontend::ParsePairing(matching);
  if (requested.mode != frontend::PairingMode::kAuto) {
    return frontend::ChoosePairing({}, requested);
  }
  if (settings.Given("match-window")) {
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
  for (const TrackerOption& entry : TrackerOptionTable()) {
    if (settings.Given(entry.flag)) CopyTrackerOption(entry, given, options);
  }
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
