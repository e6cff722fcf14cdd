// The names users know the Options fields by. The libraries' Check() messages name fields
// ("matcher: radius must be > 0 px", "COLMAP export pair_window must be >= 1"); the command line
// names what the user typed (--search-radius, --window), and the Python module gives the command
// line's message. Issue 29: a bad --search-radius was reported as "radius", the name of the flag
// before it was renamed. One table serves both doors, so they cannot drift.
#pragma once

#include <string>

namespace comic::sfm {

// `message` with a leading field phrase ("matcher: radius must ...") replaced by the option's
// flag ("--search-radius must ..."); other messages unchanged.
std::string WithUserOptionNames(const std::string& message);

}  // namespace comic::sfm
