// One number written as text, the way every reader in io/datasets takes it: the whole field (a NUL
// byte or a trailing letter inside it is not the end of the number), within double's range, and
// finite ("inf" and "nan" are words, not measurements).
#pragma once

#include <string_view>

namespace comic::io {

// True and *value set when `field` is one finite number in full; false otherwise (*value is then
// unspecified).
bool ParseNumberField(std::string_view field, double* value);

}  // namespace comic::io
