// FNV-1a 64: a small, stable, non-cryptographic hash of bytes, for keys that must be the same on
// every run and every build (the track cache's key, sfm/run/track_cache.h). Not for security: it
// detects changed content, not a crafted collision.
//
//   ContentHash hash;
//   hash.Add("detector=harris\n");
//   hash.AddFile("frames/000000.png");
//   std::string name = "tracks-" + HexDigits(hash.value()) + ".bin";
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace comic::io {

class ContentHash {
 public:
  void Add(const void* data, size_t size);
  void Add(const std::string& bytes) { Add(bytes.data(), bytes.size()); }
  // Adds the bytes of the file at `path`, read in blocks. Throws comic::Error (kNotFound, kIo)
  // naming the path.
  void AddFile(const std::string& path);
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 14695981039346656037ull;  // FNV-1a 64's offset basis
};

// FNV-1a 64 of `bytes`.
uint64_t HashBytes(const std::string& bytes);

// 16 lower-case hexadecimal digits, most significant first ("00000000000000ff").
std::string HexDigits(uint64_t value);

}  // namespace comic::io
