// Text from files or libraries made safe for our one line on stderr: bytes that are not printable
// ASCII are shown as \xNN (binary garbage is never echoed raw into a terminal), line breaks and
// tabs become spaces, and the result is cut to a length a reader can take in.
#pragma once

#include <cstddef>
#include <string>

namespace comic::io {

// `text` as one printable line of at most `max_length` characters (then "..." is appended).
// UTF-8 sequences count as non-printable: an error message is about bytes, not glyphs.
std::string PrintableOneLine(const std::string& text, size_t max_length = 400);

}  // namespace comic::io
