#include "apps/common/list_flags.h"

#include <cerrno>
#include <cstdlib>

#include "io/core/error.h"

namespace comic::apps {

std::vector<std::string> SplitList(const std::string& text, const std::string& flag) {
  std::vector<std::string> items;
  size_t begin = 0;
  while (true) {
    const size_t comma = text.find(',', begin);
    const std::string item = text.substr(begin, comma == std::string::npos ? comma : comma - begin);
    COMIC_CHECK(!text.empty(), kInvalidArgument, "--" << flag << ": the list is empty");
    COMIC_CHECK(!item.empty(), kInvalidArgument,
                "--" << flag << ": empty entry in '" << text << "'");
    items.push_back(item);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return items;
}

std::vector<double> ParseNumberList(const std::string& text, const std::string& flag) {
  std::vector<double> values;
  for (const std::string& item : SplitList(text, flag)) {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    COMIC_CHECK(*end == '\0' && errno == 0, kInvalidArgument,
                "--" << flag << ": expected a number or inf, got '" << item << "'");
    values.push_back(value);
  }
  return values;
}

}  // namespace comic::apps
