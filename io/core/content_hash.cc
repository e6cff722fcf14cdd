#include "io/core/content_hash.h"

#include <fstream>
#include <vector>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/input_file.h"

namespace comic::io {

void ContentHash::Add(const void* data, size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    hash_ ^= bytes[i];
    hash_ *= 1099511628211ull;  // FNV-1a 64's prime
  }
}

void ContentHash::AddFile(const std::string& path) {
  CheckInputFile(path);
  std::ifstream in(path, std::ios::binary);
  COMIC_CHECK(in.good(), kIo, path << ": cannot open for reading");
  // Blocks, so that a video of gigabytes is hashed without holding it.
  std::vector<char> block(1 << 20);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    Add(block.data(), static_cast<size_t>(in.gcount()));
  }
  COMIC_CHECK(!in.bad(), kIo, path << ": read failed");
}

uint64_t HashBytes(const std::string& bytes) {
  ContentHash hash;
  hash.Add(bytes);
  return hash.value();
}

std::string HexDigits(uint64_t value) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4) text[i] = kDigits[value & 0xf];
  return text;
}

}  // namespace comic::io
