// --matching (issue 16): which frame pairs the tracker matches, shared by the apps that track a
// sequence (comic_sfm, comic_export_colmap) so that both build the same tracks. `auto` (the
// default) tells a video from an image set (frontend/matching/pairing.h); the run resolves it
// with the tracker flags (sfm/run/tracker_settings.h).
#pragma once

#include <string>

#include "apps/common/arg_parser.h"

namespace comic::apps {

void AddMatchingFlag(ArgParser& parser, std::string* matching);
// --matcher: auto (the default), descriptors or patches: frontend::FeatureMatcher. One text for
// every app that takes it, saying what auto does in each.
void AddMatcherFlag(ArgParser& parser, std::string* matcher);

}  // namespace comic::apps
