// The project's version, defined once: project(comic_sfm VERSION ...) in the top-level
// CMakeLists.txt, passed to this file's .cc as the compile definition COMIC_VERSION. Every app
// prints it for --version.
#pragma once

#include <string>

namespace comic {

// "MAJOR.MINOR.PATCH", e.g. "0.1.0".
const std::string& Version();

}  // namespace comic
