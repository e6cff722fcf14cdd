// JSON reports as text that never fails: nlohmann::json::dump() throws on a string that is not
// UTF-8 (a Latin-1 file name in report.json's frame names or paths), which would end a run after
// all its work; such bytes become U+FFFD instead (issue 29).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace comic::io {

// `json` as text indented by `indent` spaces (-1: one line), followed by a line break unless
// indent is -1.
std::string JsonText(const nlohmann::json& json, int indent = 2);

}  // namespace comic::io
