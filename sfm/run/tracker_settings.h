// The tracker options of a run (paper §4: frame-to-frame SSD patch matching within a radius, with
// the motion prediction real driving video needs), by comic_sfm's and comic_export_colmap's flag
// names, and the frame pairs matched (--matching, docs/sfm.md). A field left unset takes the
// default of video SfM (SequenceReconstructionOptions' tracker: 2000 features, constant-velocity
// prediction, 60 px where nothing predicts) as set up for the chosen pairing; a field given is
// kept as given, so an explicit --match-window or --search-radius wins over the pairing's.
//
//   TrackerSettings settings;  settings.search_radius = 30.0;
//   PairingChoice pairing = ChooseRunPairing("auto", settings, sequence);
//   TrackerOptions tracker = TrackerOptionsForRun(settings, pairing, sequence.NumFrames());
#pragma once

#include <optional>
#include <string>

#include "frontend/matching/image_set_matching.h"
#include "frontend/matching/pairing.h"
#include "frontend/matching/tracker.h"

namespace comic::io {
class ImageSequence;
}

namespace comic::sfm {

struct TrackerSettings {
  std::optional<int> max_features;              // --max-features N (0 = all)
  std::optional<double> search_radius;          // --search-radius PX
  std::optional<double> unpredicted_radius;     // --unpredicted-radius PX (0 = --search-radius)
  std::optional<std::string> prediction;        // --prediction none|velocity|coarse-to-fine
  std::optional<double> coarse_radius;          // --coarse-radius PX
  std::optional<int> match_window;              // --match-window K
  std::optional<std::string> track_conflicts;   // --track-conflicts drop|greedy
  std::optional<int> verify_min_gap;            // --verify-min-gap G
  std::optional<bool> match_turned;             // --match-turned
  std::optional<double> max_cost;               // --max-cost T
  std::optional<bool> align_patches;            // --align-patches 1|0
  std::optional<double> min_window_eigenvalue;  // --min-window-eigenvalue E
  // --max-continued-frames, --bridge-frames and the alignment flags (track_continuation.h).
  std::optional<frontend::TrackContinuationOptions> continuation;

  // The defaults with every given field applied, names parsed, Check()ed. Throws
  // comic::Error(kInvalidArgument) naming the bad option.
  frontend::TrackerOptions ToTrackerOptions() const;
  // The --track-conflicts name in force (the default's when unset).
  std::string TrackConflictsName() const;
};

// The tracker options a run starts from (SequenceReconstructionOptions' tracker), so that both
// apps and Python take the same defaults.
frontend::TrackerOptions DefaultRunTrackerOptions();

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
