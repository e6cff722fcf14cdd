// The consumer's own io/core/error.h: a name comic-sfm also uses (comic/io/core/error.h). The
// consumer's #include "io/core/error.h" must find this file, not the installed one.
#pragma once

namespace consumer::io {
inline constexpr const char* kWhichErrorHeader = "consumer";
}  // namespace consumer::io
