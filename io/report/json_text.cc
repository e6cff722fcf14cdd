#include "io/report/json_text.h"

namespace comic::io {

std::string JsonText(const nlohmann::json& json, int indent) {
  const std::string text = json.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
  return indent < 0 ? text : text + "\n";
}

}  // namespace comic::io
