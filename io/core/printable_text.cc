#include "io/core/printable_text.h"

#include <algorithm>
#include <cstdio>

namespace comic::io {

std::string PrintableOneLine(const std::string& text, size_t max_length) {
  std::string out;
  out.reserve(std::min(text.size(), max_length) + 3);
  for (const char c : text) {
    if (out.size() >= max_length) {
      out += "...";
      break;
    }
    const unsigned char byte = static_cast<unsigned char>(c);
    if (byte == '\n' || byte == '\r' || byte == '\t') {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else if (byte >= 0x20 && byte < 0x7f) {
      out += c;
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", byte);
      out += escaped;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace comic::io
