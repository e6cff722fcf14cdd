// The project's one exception type, for broken preconditions, bad options and bad input.
// Expected failures of an algorithm (no initial pair, too few matches) are not errors: they are
// returned as a Status or std::optional by the code that meets them (see ../shared/STYLE.md).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace comic {

enum class ErrorKind {
  kInvalidArgument,  // bad option value or API misuse
  kNotFound,         // a path that does not exist
  kInvalidData,      // a file or image that exists but cannot be used (corrupt, wrong size/type)
  kIo,               // reading or writing failed (unwritable output, existing file, disk full)
  kExternal,         // an external program (e.g. colmap) failed
};

const char* ErrorKindName(ErrorKind kind);

class Error : public std::runtime_error {
 public:
  // A NUL byte in `message` (quoted from a file) is stored as the four characters "\x00":
  // what() is a C string, and would otherwise end the message there.
  Error(ErrorKind kind, const std::string& message);
  ErrorKind kind() const { return kind_; }

 private:
  ErrorKind kind_;
};

// Throws comic::Error(kind, message) when `condition` is false. `message` is built from the
// streamed arguments only on failure:  COMIC_CHECK(x > 0, kInvalidArgument, "x must be > 0, got "
// << x);
#define COMIC_CHECK(condition, kind, message)                                    \
  do {                                                                           \
    if (!(condition)) {                                                          \
      std::ostringstream comic_check_stream_;                                    \
      comic_check_stream_ << message;                                            \
      throw ::comic::Error(::comic::ErrorKind::kind, comic_check_stream_.str()); \
    }                                                                            \
  } while (false)

}  // namespace comic
