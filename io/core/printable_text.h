// Text from files or libraries made safe for our one line on stderr: control bytes and bytes
// that are not valid UTF-8 are shown as \xNN (binary garbage is never echoed raw into a
// terminal), and the result is cut to a length a reader can take in. Valid UTF-8 (a frame named
// "straße_001.png") is kept as it is, so a user's path reads as they typed it. A library's output
// is lines, joined with spaces; a message of ours names paths, whose tabs and line breaks are
// escaped like any control byte, so that "a\tb.png" never reads as "a b.png".
#pragma once

#include <cstddef>
#include <string>

namespace comic::io {

// `text` as one printable line of at most `max_length` bytes (then "..." is appended; a UTF-8
// character is never split). Printable: ASCII 0x20-0x7e and well-formed UTF-8 sequences of
// characters other than the C1 controls (U+0080-U+009F), the line and paragraph separators
// (U+2028, U+2029) and the bidirectional overrides and isolates (U+202A-U+202E, U+2066-U+2069),
// which could reorder or break the line on a terminal.
// Line breaks and tabs become single spaces (for a library's lines, such as FFmpeg's).
std::string PrintableOneLine(const std::string& text, size_t max_length = 400);

// The same, but line breaks and tabs are escaped as \x0a, \x0d, \x09 like every other control
// byte (for our messages, which name paths), except the line breaks that end `text`.
std::string PrintableMessage(const std::string& text, size_t max_length = 400);

}  // namespace comic::io
