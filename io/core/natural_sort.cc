#include "io/core/natural_sort.h"

#include <algorithm>
#include <cctype>

namespace comic::io {
namespace {

bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

}  // namespace

bool NaturalLess(const std::string& a, const std::string& b) {
  size_t i = 0;
  size_t j = 0;
  while (i < a.size() && j < b.size()) {
    if (IsDigit(a[i]) && IsDigit(b[j])) {
      // Compare the digit runs by value: skip leading zeros, then the longer run is larger,
      // then compare digit by digit.
      size_t ia = i;
      size_t jb = j;
      while (ia < a.size() && a[ia] == '0') ++ia;
      while (jb < b.size() && b[jb] == '0') ++jb;
      size_t ea = ia;
      size_t eb = jb;
      while (ea < a.size() && IsDigit(a[ea])) ++ea;
      while (eb < b.size() && IsDigit(b[eb])) ++eb;
      const size_t len_a = ea - ia;
      const size_t len_b = eb - jb;
      if (len_a != len_b) return len_a < len_b;
      const int cmp = a.compare(ia, len_a, b, jb, len_b);
      if (cmp != 0) return cmp < 0;
      // Same value: fewer leading zeros first, so the order stays strict ("1" < "01").
      const size_t run_a = ea - i;
      const size_t run_b = eb - j;
      if (run_a != run_b) return run_a < run_b;
      i = ea;
      j = eb;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  return (a.size() - i) < (b.size() - j);
}

void NaturalSort(std::vector<std::string>* names) {
  std::sort(names->begin(), names->end(), NaturalLess);
}

}  // namespace comic::io
