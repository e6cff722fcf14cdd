// Natural ("human") ordering of file names, so that frame_2 sorts before frame_10.
#pragma once

#include <string>
#include <vector>

namespace comic::io {

// Compares runs of decimal digits by their numeric value (then by length, so "01" < "1" never
// ties with a different string) and everything else byte by byte. A strict weak ordering.
bool NaturalLess(const std::string& a, const std::string& b);

// Sorts in place with NaturalLess.
void NaturalSort(std::vector<std::string>* names);

}  // namespace comic::io
