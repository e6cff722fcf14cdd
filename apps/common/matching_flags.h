// --matching (issue 16): which frame pairs the tracker matches, shared by the apps that track a
// sequence (comic_sfm, comic_export_colmap) so that both build the same tracks. `auto` (the
// default) tells a video from an image set (frontend/matching/pairing.h).
#pragma once

#include <optional>
#include <string>

#include "apps/common/arg_parser.h"
#include "apps/common/tracker_flags.h"
#include "frontend/matching/pairing.h"

namespace comic::io {
class ImageSequence;
}

namespace comic::apps {

void AddMatchingFlag(ArgParser& parser, std::string* matching);
// --matcher: auto (descriptors for an image set, the patch tracker for a video), patches or
// descriptors (frontend::FeatureMatcher).
void AddMatcherFlag(ArgParser& parser, std::string* matcher);

// The pairing of this run: `matching` parsed (throws comic::Error(kInvalidArgument) for a bad
// value) and, for auto, chosen from the frames of `sequence` — unless --match-window was given:
// then the pairing was set by hand (the commands of before --matching), and auto leaves the
// tracker flags exactly as given (chosen: sequential, i.e. no set-up).
frontend::PairingChoice ChooseRunPairing(const std::string& matching, const ArgParser& parser,
                                         const io::ImageSequence& sequence);

// The tracker options of this run: the tracker flags' defaults set up for the chosen pairing,
// with every tracker flag given on the command line kept as given (an explicit --match-window or
// --search-radius wins over the pairing's). Check()ed.
frontend::TrackerOptions TrackerOptionsForRun(const ArgParser& parser, const TrackerFlags& flags,
                                              const frontend::PairingChoice& choice,
                                              int num_frames);

// The descriptor matching of this run, or std::nullopt when the patch tracker matches
// (frontend::MatchesByDescriptors): the chosen pairs, the features `tracker` selects, `threads`.
// Throws comic::Error(kInvalidArgument) for a bad --matcher.
std::optional<frontend::ImageSetMatchingOptions> ImageSetMatchingForRun(
    const std::string& matcher, const frontend::PairingChoice& choice,
    const frontend::TrackerOptions& tracker, int threads);

}  // namespace comic::apps
