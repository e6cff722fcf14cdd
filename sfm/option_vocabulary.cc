#include "sfm/option_vocabulary.h"

#include <vector>

namespace comic::sfm {
namespace {

struct Entry {
  const char* phrase;  // how a Check() message starts, before " must"
  const char* option;  // the flag without "--"
};

// Fields whose Check() message starts with a name other than the option's.
const Entry kEntries[] = {
    {"matcher: radius", "search-radius"},
    {"matcher: max_cost", "max-cost"},
    {"matcher: min_side_overlap", "min-side-overlap"},
    {"COLMAP export pair_window", "window"},
    {"two-view max_error_px", "max-error"},
    {"two-view min_num_inliers", "min-inliers"},
    {"tracker: max_features", "max-features"},
    {"tracker: unpredicted_radius", "unpredicted-radius"},
    {"tracker: coarse_radius", "coarse-radius"},
    {"tracker: match_window", "match-window"},
    {"tracker: verify_min_gap", "verify-min-gap"},
    {"first_frame", "first"},
    {"last_frame", "last"},
    {"stride", "stride"},
    {"resize_height", "resize-height"},
};

// CoMIC's fields, in either search's messages ("comic: half_length must ...").
const Entry kDetectorEntries[] = {
    {"scale", "scale"},
    {"delta", "delta"},
    {"half_length", "half-length"},
    {"block_size", "block-size"},
    {"num_threads", "threads"},
    {"min_cornerness", "min-cornerness"},
    {"max_iterations", "max-iterations"},
    {"merge_radius", "merge-radius"},
    {"level_radius", "level-radius"},
    {"link_radius", "link-radius"},
    {"consensus_fraction", "consensus-fraction"},
    {"presmoothing_sigma", "presmoothing-sigma"},
    {"min_stability", "min-stability"},
    {"convergence_tolerance", "convergence-tolerance"},
    {"stop_tolerance", "stop-tolerance"},
};

// `message` starts with `phrase` followed by " must".
bool StartsWithField(const std::string& message, const std::string& phrase) {
  return message.compare(0, phrase.size(), phrase) == 0 &&
         message.compare(phrase.size(), 5, " must") == 0;
}

}  // namespace

std::string WithUserOptionNames(const std::string& message) {
  for (const Entry& entry : kEntries) {
    if (StartsWithField(message, entry.phrase)) {
      return "--" + std::string(entry.option) + message.substr(std::string(entry.phrase).size());
    }
  }
  for (const char* detector : {"comic: ", "comic-paper: "}) {
    for (const Entry& entry : kDetectorEntries) {
      const std::string phrase = detector + std::string(entry.phrase);
      if (StartsWithField(message, phrase)) {
        return "--" + std::string(entry.option) + message.substr(phrase.size());
      }
    }
  }
  return message;
}

}  // namespace comic::sfm
