#include "io/core/version.h"

#ifndef COMIC_VERSION
#error "COMIC_VERSION must be defined by io/CMakeLists.txt from the project's VERSION"
#endif

namespace comic {

const std::string& Version() {
  static const std::string version = COMIC_VERSION;
  return version;
}

}  // namespace comic
