#include "apps/common/frame_range_flags.h"

namespace comic::apps {

void AddFrameRangeFlags(ArgParser& parser, io::ImageSequenceOptions* options, StrideFlag stride) {
  parser.AddOption("first", "N", "first frame index to use (0-based, in the sorted folder)",
                   &options->first_frame);
  parser.AddOption("last", "N", "last frame index to use, inclusive (-1 = end)",
                   &options->last_frame);
  if (stride == StrideFlag::kWith) {
    parser.AddOption("stride", "N", "use every N-th frame from --first on", &options->stride);
  }
}

}  // namespace comic::apps
