// The tracker options of a run (paper §4: frame-to-frame SSD patch matching within a radius, with
// the motion prediction real driving video needs), by the tracker table's flags
// (sfm/run/tracker_option_table.h), and the frame pairs matched (--matching, docs/sfm.md). A
// field not given takes the default of video SfM (SequenceReconstructionOptions' tracker: 2000
// features, constant-velocity prediction, 60 px where nothing predicts) as set up for the chosen
// pairing; a field given is kept as given, so an explicit --match-window or --search-radius wins
// over the pairing's.
//
//   TrackerSettings settings;
//   settings.Give("search-radius", [](TrackerOptions& o) { o.matcher.radius = 30.0; });
//   PairingChoice pairing = ChooseRunPairing("auto", settings, sequence);
//   TrackerOptions tracker = TrackerOptionsForRun(settings, pairing, sequence.NumFrames());
#pragma once

#include <optional>
#include <set>
#include <string>

#include "frontend/matching/image_set_matching.h"
#include "frontend/matching/pairing.h"
#include "frontend/matching/tracker.h"

namespace comic::io {
class ImageSequence;
}

namespace comic::sfm {

// The tracker options a run starts from (SequenceReconstructionOptions' tracker), so that both
// apps and Python take the same defaults.
frontend::TrackerOptions DefaultRunTrackerOptions();

struct TrackerSettings {
  // Every tracker option's value, the run's defaults where none was given.
  frontend::TrackerOptions values = DefaultRunTrackerOptions();
  // The flags given (sfm/run/tracker_option_table.h): their values win over the pairing's.
  std::set<std::string> given;

  // Gives `flag` (an entry of the tracker table; throws comic::Error(kInvalidArgument) for
  // another) with `set` applied to the values.
  template <typename Set>
  void Give(const std::string& flag, Set set) {
    MarkGiven(flag);
    set(values);
  }
  // Gives a named option (--prediction, --track-conflicts) by its name; throws
  // comic::Error(kInvalidArgument) naming the flag for an unknown name.
  void GiveName(const std::string& flag, const std::string& name);
  void MarkGiven(const std::string& flag);
  bool Given(const std::string& flag) const { return given.count(flag) > 0; }

  // The values, Check()ed. Throws comic::Error(kInvalidArgument) naming the bad option.
  frontend::TrackerOptions ToTrackerOptions() const;
  // The --track-conflicts name in force.
  std::string TrackConflictsName() const;
};

// The pairing of a run: `matching` parsed (throws comic::Error(kInvalidArgument) naming
// --matching) and, for auto, chosen from the frames of `sequence` — unless --match-window was
// given: then the pairing was set by hand and auto leaves the tracker options as given (chosen:
// sequential, i.e. no set-up).
frontend::PairingChoice ChooseRunPairing(const std::string& matching,
                                         const TrackerSettings& settings,
                                         const io::ImageSequence& sequence);

// The tracker options of a run: the defaults with the given fields, set up for the chosen
// pairing, with every given field kept as given. Check()ed.
frontend::TrackerOptions TrackerOptionsForRun(const TrackerSettings& settings,
                                              const frontend::PairingChoice& choice,
                                              int num_frames);

// The descriptor matching of a run, or std::nullopt when the patch tracker matches
// (`matcher`: --matcher, frontend::MatchesByDescriptors; auto with the patch tracker's
// --match-window given leaves the tracker to it): the chosen pairs, the features
// `tracker` selects, `threads`. Throws comic::Error(kInvalidArgument) for a bad --matcher.
std::optional<frontend::ImageSetMatchingOptions> ImageSetMatchingForRun(
    const std::string& matcher, const frontend::PairingChoice& choice,
    const frontend::TrackerOptions& tracker, int threads);

}  // namespace comic::sfm
