#include "io/core/error.h"

namespace comic {

const char* ErrorKindName(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kInvalidArgument:
      return "invalid argument";
    case ErrorKind::kNotFound:
      return "not found";
    case ErrorKind::kInvalidData:
      return "invalid data";
    case ErrorKind::kIo:
      return "I/O error";
    case ErrorKind::kExternal:
      return "external program failed";
  }
  return "error";
}

}  // namespace comic
