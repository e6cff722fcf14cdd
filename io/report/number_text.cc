#include "io/report/number_text.h"

#include <cstdio>

namespace comic::io {

std::string NumberText(const char* printf_format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), printf_format, value);
  return text;
}

}  // namespace comic::io
