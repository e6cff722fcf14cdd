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

void AddMatcherFlag(ArgParser& parser, std::string* matcher) {
  parser.AddOption("matcher", "M",
                   "how the pairs are matched: patches (default: the patch tracker), descriptors "
                   "(SIFT descriptors of every feature, with ratio test, cross check and "
                   "fundamental-matrix verification as COLMAP's exhaustive matcher) or auto "
                   "(descriptors for an image set, the patch tracker for a video)",
                   matcher);
}

}  // namespace comic::apps
