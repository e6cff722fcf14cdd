#include "io/core/printable_text.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace comic::io {
namespace {

// The length of the well-formed UTF-8 sequence at text[at] (2 to 4 bytes) of a character that
// may be shown, or 0 (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF).
size_t PrintableUtf8Length(const std::string& text, size_t at) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[at + k]); };
  const unsigned char lead = byte(0);
  size_t length = 0;
  uint32_t code = 0;
  if (lead >= 0xc2 && lead <= 0xdf) {
    length = 2;
    code = lead & 0x1f;
  } else if (lead >= 0xe0 && lead <= 0xef) {
    length = 3;
    code = lead & 0x0f;
  } else if (lead >= 0xf0 && lead <= 0xf4) {
    length = 4;
    code = lead & 0x07;
  } else {
    return 0;
  }
  if (at + length > text.size()) return 0;
  for (size_t k = 1; k < length; ++k) {
    if ((byte(k) & 0xc0) != 0x80) return 0;
    code = (code << 6) | (byte(k) & 0x3f);
  }
  const uint32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < smallest[length] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return 0;
  const bool control = code <= 0x9f || code == 0x2028 || code == 0x2029 ||
                       (code >= 0x202a && code <= 0x202e) || (code >= 0x2066 && code <= 0x2069);
  return control ? 0 : length;
}

std::string Printable(const std::string& text, size_t max_length, bool join_lines) {
  std::string out;
  out.reserve(std::min(text.size(), max_length) + 3);
  for (size_t at = 0; at < text.size();) {
    if (out.size() >= max_length) {
      out += "...";
      break;
    }
    const unsigned char byte = static_cast<unsigned char>(text[at]);
    if (join_lines && (byte == '\n' || byte == '\r' || byte == '\t')) {
      if (!out.empty() && out.back() != ' ') out += ' ';
      ++at;
    } else if (byte >= 0x20 && byte < 0x7f) {
      out += text[at++];
    } else if (const size_t length = PrintableUtf8Length(text, at); length > 0) {
      out.append(text, at, length);
      at += length;
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", byte);
      out += escaped;
      ++at;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace

std::string PrintableOneLine(const std::string& text, size_t max_length) {
  return Printable(text, max_length, /*join_lines=*/true);
}

std::string PrintableMessage(const std::string& text, size_t max_length) {
  const size_t end = text.find_last_not_of("\r\n");
  return Printable(end == std::string::npos ? "" : text.substr(0, end + 1), max_length,
                   /*join_lines=*/false);
}

}  // namespace comic::io
