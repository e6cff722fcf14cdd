#include "apps/common/matching_flags.h"

namespace comic::apps {

void AddMatchingFlag(ArgParser& parser, std::string* matching) {
  parser.AddOption("matching", "M",
                   "frame pairs matched: auto (default: sequential for a video, exhaustive for an "
                   "image set, told apart by how alike consecutive frames look), sequential "
                   "(frame i to i+1), exhaustive (every pair, verified, also turned by 180 "
                   "degrees, coarse-to-fine prediction) or window:K (the next K frames)",
                   matching);
}

}  // namespace comic::apps
