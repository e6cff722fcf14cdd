// The options that bound what an app accepts as input, one definition each (issue 19):
// --max-pixels (the work budget per image or frame, io/core/pixel_budget.h) and --allow-truncated
// (a video that stops decoding early is used up to the break, with a warning line).
#pragma once

#include "apps/common/arg_parser.h"

namespace comic::apps {

// --max-pixels N, bound to `max_pixels` (its value when called is the default).
void AddMaxPixelsFlag(ArgParser& parser, int* max_pixels);
// --allow-truncated, bound to `allow` (io::ImageSequenceOptions::allow_truncated).
void AddAllowTruncatedFlag(ArgParser& parser, bool* allow);

}  // namespace comic::apps
