// The names users know the Options fields by. The libraries' Check() messages name fields
// ("matcher: radius must be > 0 px", "COLMAP export pair_window must be >= 1"); the two doors
// name what the user typed: the apps' flags (--search-radius, --window) and the Python keywords
// (search_radius, window). Issue 29: a bad --search-radius was reported as "radius", the name of
// the flag before it was renamed. One table serves both doors, so they cannot drift.
#pragma once

#include <string>

namespace comic::sfm {

enum class OptionStyle {
  kFlag,     // --search-radius
  kKeyword,  // search_radius
};

// `message` with a leading field phrase ("matcher: radius must ...") replaced by the option's
// user-facing name in `style` ("--search-radius must ..."); other messages unchanged.
std::string WithUserOptionNames(const std::string& message, OptionStyle style);

}  // namespace comic::sfm
