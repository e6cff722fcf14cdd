// Comma-separated list values of flags (--detectors comic,harris  --sweep 100,200,inf), parsed
// the same way in every app: no empty entries, numbers in full (strtod: "inf" allowed).
#pragma once

#include <string>
#include <vector>

namespace comic::apps {

// The entries of `text`. Throws comic::Error(kInvalidArgument) naming --`flag` for an empty list
// or an empty entry ("a,,b", "a,").
std::vector<std::string> SplitList(const std::string& text, const std::string& flag);

// The entries of `text` as numbers. Throws comic::Error(kInvalidArgument) naming --`flag` for an
// entry that is not a number in full.
std::vector<double> ParseNumberList(const std::string& text, const std::string& flag);

}  // namespace comic::apps
