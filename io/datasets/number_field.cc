#include "io/datasets/number_field.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace comic::io {

bool ParseNumberField(std::string_view field, double* value) {
  // strtod needs a terminated string; a copy also keeps an embedded NUL from ending the field.
  const std::string copy(field);
  // strtod skips leading white space; a field does not start with it.
  if (copy.empty() || std::isspace(static_cast<unsigned char>(copy[0]))) return false;
  errno = 0;
  char* end = nullptr;
  *value = std::strtod(copy.c_str(), &end);
  return end == copy.c_str() + copy.size() && errno == 0 && std::isfinite(*value);
}

std::string QuotedField(std::string_view field) {
  if (field.size() <= kQuotedFieldLength) return "'" + std::string(field) + "'";
  return "'" + std::string(field.substr(0, kQuotedFieldLength)) + "...'";
}

}  // namespace comic::io
