// One number written as text, the way every reader in io/datasets takes it: the whole field (a NUL
// byte or a trailing letter inside it is not the end of the number), within double's range, and
// finite ("inf" and "nan" are words, not measurements).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace comic::io {

// True and *value set when `field` is one finite number in full; false otherwise (*value is then
// unspecified).
bool ParseNumberField(std::string_view field, double* value);

// A field that is not a number, as a message quotes it: its first kQuotedFieldLength bytes and
// "..." when longer, so a file that fails to parse (any file a path names) is never echoed beyond
// a short prefix. Control bytes are escaped where the message is printed.
inline constexpr size_t kQuotedFieldLength = 24;
std::string QuotedField(std::string_view field);

}  // namespace comic::io
