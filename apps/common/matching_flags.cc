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
  parser.AddOption(
      "matcher", "M",
      "how the pairs are matched: auto (default; comic_sfm: the patch tracker with every frame "
      "pair verified, then descriptors when it leaves frames out, the better model kept, for a "
      "video and for an image set (there the tracker's image-set set-up); comic_export_colmap: "
      "descriptors for a video, the tracker's image-set set-up for an image set), descriptors "
      "(SIFT descriptors of every "
      "feature, ratio test, cross check and fundamental-matrix verification of every pair; a "
      "video's frames each with the next 10 and those 2^k after it, as COLMAP's sequential "
      "matcher; an image set's every pair) or patches (the patch tracker: faster, for clean "
      "video)",
      matcher);
}

}  // namespace comic::apps
