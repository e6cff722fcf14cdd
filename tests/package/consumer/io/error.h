// The consumer's own io/error.h: a name comic-sfm also uses (comic/io/error.h). The consumer's
// #include "io/error.h" must find this file, not the installed one.
#pragma once

namespace consumer::io {
inline constexpr const char* kWhichErrorHeader = "consumer";
}  // namespace consumer::io
