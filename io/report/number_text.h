// A number as a page or a summary line shows it, by a printf format ("%.3g", "%.1f %%"), so that
// every page formats its numbers the same way.
#pragma once

#include <string>

namespace comic::io {

// `value` formatted by `printf_format` (one double conversion; text past 63 characters is cut).
std::string NumberText(const char* printf_format, double value);

}  // namespace comic::io
