// The flags that choose which frames of a sequence an app uses, the same in every app that reads
// one: --first, --last and (where the app supports it) --stride, bound to
// io::ImageSequenceOptions (whose Check() validates them when the sequence is opened).
// --resize-height is apps/common/shared_flags.h's AddResizeHeightFlag.
#pragma once

#include "apps/common/arg_parser.h"
#include "io/image/image_sequence.h"

namespace comic::apps {

enum class StrideFlag { kWith, kWithout };

// The defaults are `options`' values when called.
void AddFrameRangeFlags(ArgParser& parser, io::ImageSequenceOptions* options,
                        StrideFlag stride = StrideFlag::kWith);

}  // namespace comic::apps
