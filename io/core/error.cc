#include "io/core/error.h"

namespace comic {
namespace {

std::string WithoutNulBytes(const std::string& message) {
  if (message.find('\0') == std::string::npos) return message;
  std::string out;
  for (const char c : message) {
    if (c == '\0') {
      out += "\\x00";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

Error::Error(ErrorKind kind, const std::string& message)
    : std::runtime_error(WithoutNulBytes(message)), kind_(kind) {}

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
