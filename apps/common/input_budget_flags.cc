#include "apps/common/input_budget_flags.h"

namespace comic::apps {

void AddMaxPixelsFlag(ArgParser& parser, int* max_pixels) {
  parser.AddOption("max-pixels", "N",
                   "refuse an image or frame with more pixels than N (after resizing; read from "
                   "an image's header before decoding, from a scene's camera before rendering; "
                   "docs/robustness.md gives time and memory per size)",
                   max_pixels);
}

void AddAllowTruncatedFlag(ArgParser& parser, bool* allow) {
  parser.AddFlag("allow-truncated",
                 "use a video whose frames stop decoding before its end up to the break, with a "
                 "warning line (otherwise an error naming the last good frame)",
                 allow);
}

}  // namespace comic::apps
