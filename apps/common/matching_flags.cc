#include "apps/common/matching_flags.h"

#include "io/image/image_sequence.h"

namespace comic::apps {

void AddMatchingFlag(ArgParser& parser, std::string* matching) {
  parser.AddOption("matching", "M",
                   "frame pairs matched: auto (default: sequential for a video, exhaustive for an "
                   "image set, told apart by how alike consecutive frames look), sequential "
                   "(frame i to i+1), exhaustive (every pair, verified, also turned by 180 "
                   "degrees, coarse-to-fine prediction) or window:K (the next K frames)",
                   matching);
}

void AddMatcherFlag(ArgParser& parser, std::string* matcher) {
  parser.AddOption("matcher", "M",
                   "how the pairs are matched: auto (default: SIFT descriptors of every feature "
                   "for an image set, with ratio test, cross check and fundamental-matrix "
                   "verification as COLMAP's exhaustive matcher; the patch tracker for a video), "
                   "descriptors or patches",
                   matcher);
}

std::optional<frontend::ImageSetMatchingOptions> ImageSetMatchingForRun(
    const std::string& matcher, const frontend::PairingChoice& choice,
    const frontend::TrackerOptions& tracker, int threads) {
  if (!frontend::MatchesByDescriptors(frontend::ParseFeatureMatcher(matcher), choice)) {
    return std::nullopt;
  }
  return frontend::ImageSetMatchingOptionsForPairing(choice.chosen, tracker, threads);
}

frontend::PairingChoice ChooseRunPairing(const std::string& matching, const ArgParser& parser,
                                         const io::ImageSequence& sequence) {
  const frontend::Pairing requested = frontend::ParsePairing(matching);
  if (requested.mode != frontend::PairingMode::kAuto) {
    return frontend::ChoosePairing({}, requested);
  }
  if (parser.WasSet("match-window")) {
    frontend::PairingChoice choice;
    choice.requested = requested;
    choice.chosen = {frontend::PairingMode::kSequential, 0};
    choice.reason = "--match-window given: the tracker flags as given decide the pairs";
    return choice;
  }
  return frontend::ChoosePairing(frontend::ThumbnailsOf(sequence), requested);
}

frontend::TrackerOptions TrackerOptionsForRun(const ArgParser& parser, const TrackerFlags& flags,
                                              const frontend::PairingChoice& choice,
                                              int num_frames) {
  const frontend::TrackerOptions given = ToTrackerOptions(flags);
  frontend::TrackerOptions options =
      frontend::TrackerOptionsForPairing(choice.chosen, num_frames, given);
  // The fields a pairing sets, by the flag that sets them.
  if (parser.WasSet("match-window")) options.match_window = given.match_window;
  if (parser.WasSet("verify-min-gap")) options.verify_min_gap = given.verify_min_gap;
  if (parser.WasSet("match-turned")) options.match_turned_180 = given.match_turned_180;
  if (parser.WasSet("prediction")) options.prediction = given.prediction;
  if (parser.WasSet("coarse-radius")) options.coarse_radius = given.coarse_radius;
  if (parser.WasSet("search-radius")) options.matcher.radius = given.matcher.radius;
  if (parser.WasSet("max-cost")) options.matcher.max_cost = given.matcher.max_cost;
  options.Check();
  return options;
}

}  // namespace comic::apps
