#include "io/image/image_header.h"

#include <cctype>
#include <fstream>

#include "io/core/file_utils.h"
#include "io/core/input_file.h"

namespace comic::io {
namespace {

// Random access to a file's bytes or a string's, read in 4 kB blocks: a JPEG's segments are
// walked and a TIFF's first IFD (often written after the pixel data) is reached by seeking, so
// only a few blocks are read, never the pixel data. A read past the end (or beyond 16 MB, where
// no header of ours lies) marks the reader as failed instead of returning garbage.
class Bytes {
 public:
  explicit Bytes(const std::string& bytes) : string_(&bytes) {}
  explicit Bytes(std::ifstream* file) : file_(file) {}
  bool ok() const { return ok_; }
  uint32_t U8(size_t at) {
    constexpr size_t kMaxOffset = 16 << 20;
    if (!ok_ || at >= kMaxOffset) return Fail();
    if (string_ != nullptr) {
      return at < string_->size() ? static_cast<unsigned char>((*string_)[at]) : Fail();
    }
    const size_t block = at / kBlockSize;
    if (block != block_) {
      file_->clear();
      file_->seekg(static_cast<std::streamoff>(block * kBlockSize));
      file_->read(buffer_, kBlockSize);
      block_size_ = file_->gcount() > 0 ? static_cast<size_t>(file_->gcount()) : 0;
      block_ = block;
    }
    const size_t offset = at % kBlockSize;
    return offset < block_size_ ? static_cast<unsigned char>(buffer_[offset]) : Fail();
  }
  uint32_t U16(size_t at, bool big_endian) {
    const uint32_t a = U8(at), b = U8(at + 1);
    return big_endian ? (a << 8) | b : (b << 8) | a;
  }
  uint32_t U32(size_t at, bool big_endian) {
    const uint32_t a = U16(at, big_endian), b = U16(at + 2, big_endian);
    return big_endian ? (a << 16) | b : (b << 16) | a;
  }
  bool StartsWith(const std::string& prefix) {
    for (size_t k = 0; k < prefix.size(); ++k) {
      if (U8(k) != static_cast<unsigned char>(prefix[k])) return false;
    }
    return ok_;
  }
  // Up to `n` bytes from the start, as text (a PNM header).
  std::string Prefix(size_t n) {
    std::string text;
    for (size_t k = 0; k < n; ++k) {
      const uint32_t c = U8(k);
      if (!ok_) break;
      text += static_cast<char>(c);
    }
    ok_ = true;
    return text;
  }

 private:
  static constexpr size_t kBlockSize = 4096;
  uint32_t Fail() {
    ok_ = false;
    return 0;
  }
  const std::string* string_ = nullptr;
  std::ifstream* file_ = nullptr;
  char buffer_[kBlockSize];
  size_t block_ = static_cast<size_t>(-1);
  size_t block_size_ = 0;
  bool ok_ = true;
};

std::optional<ImageHeader> Done(Bytes& bytes, const char* format, int64_t width, int64_t height) {
  if (!bytes.ok()) return std::nullopt;
  return ImageHeader{format, width, height};
}

// PNG: the signature, then the IHDR chunk: length, "IHDR", width, height (big-endian).
std::optional<ImageHeader> ParsePng(Bytes& bytes) {
  return Done(bytes, "PNG", bytes.U32(16, true), bytes.U32(20, true));
}

// JPEG: segments FF xx [length] up to a start-of-frame (SOF0-SOF15 but DHT C4, JPG C8, DAC CC):
// precision, height, width.
std::optional<ImageHeader> ParseJpeg(Bytes& bytes) {
  size_t at = 2;
  while (bytes.ok()) {
    if (bytes.U8(at) != 0xff) return std::nullopt;
    const uint32_t marker = bytes.U8(at + 1);
    if (marker == 0xff) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd8)) {  // no length
      at += 2;
      continue;
    }
    if (marker == 0xda || marker == 0xd9) return std::nullopt;  // scan or end before any frame
    const uint32_t length = bytes.U16(at + 2, true);
    if (length < 2) return std::nullopt;
    if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc) {
      return Done(bytes, "JPEG", bytes.U16(at + 7, true), bytes.U16(at + 5, true));
    }
    at += 2 + length;
  }
  return std::nullopt;
}

// BMP: "BM", the DIB header's size at 14; a 12-byte core header holds 16-bit sizes, the others
// 32-bit signed ones (a negative height is a top-down image).
std::optional<ImageHeader> ParseBmp(Bytes& bytes) {
  if (bytes.U32(14, false) == 12) {
    return Done(bytes, "BMP", bytes.U16(18, false), bytes.U16(20, false));
  }
  const int64_t width = static_cast<int32_t>(bytes.U32(18, false));
  const int64_t height = static_cast<int32_t>(bytes.U32(22, false));
  return Done(bytes, "BMP", width < 0 ? -width : width, height < 0 ? -height : height);
}

// TIFF: byte order, 42, the first IFD's offset; its entries (tag, type, count, value) hold
// ImageWidth (256) and ImageLength (257) as SHORT (3) or LONG (4).
std::optional<ImageHeader> ParseTiff(Bytes& bytes) {
  const bool big_endian = bytes.U8(0) == 'M';
  const uint32_t ifd = bytes.U32(4, big_endian);
  const uint32_t count = bytes.U16(ifd, big_endian);
  int64_t width = -1;
  int64_t height = -1;
  for (uint32_t k = 0; k < count && bytes.ok(); ++k) {
    const size_t entry = ifd + 2 + 12 * static_cast<size_t>(k);
    const uint32_t tag = bytes.U16(entry, big_endian);
    const uint32_t type = bytes.U16(entry + 2, big_endian);
    if (tag != 256 && tag != 257) continue;
    if (type != 3 && type != 4) return std::nullopt;
    const int64_t value =
        type == 3 ? bytes.U16(entry + 8, big_endian) : bytes.U32(entry + 8, big_endian);
    (tag == 256 ? width : height) = value;
  }
  if (width < 0 || height < 0) return std::nullopt;
  return Done(bytes, "TIFF", width, height);
}

// PNM P1-P6: the magic, then width and height as decimal numbers among whitespace and # comments.
std::optional<ImageHeader> ParsePnm(const std::string& text) {
  size_t at = 2;
  int64_t values[2] = {0, 0};
  for (int64_t& value : values) {
    while (at < text.size()) {
      if (std::isspace(static_cast<unsigned char>(text[at]))) {
        ++at;
      } else if (text[at] == '#') {
        while (at < text.size() && text[at] != '\n') ++at;
      } else {
        break;
      }
    }
    const size_t start = at;
    while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at])) &&
           at - start < 12) {
      value = value * 10 + (text[at++] - '0');
    }
    if (at == start || at >= text.size()) return std::nullopt;
  }
  return ImageHeader{"PNM", values[0], values[1]};
}

std::optional<ImageHeader> ParseHeader(Bytes& bytes) {
  if (bytes.StartsWith("\x89PNG\r\n\x1a\n") && bytes.U32(12, true) == 0x49484452) {  // IHDR
    return ParsePng(bytes);
  }
  if (bytes.StartsWith("\xff\xd8")) return ParseJpeg(bytes);
  if (bytes.StartsWith("BM")) return ParseBmp(bytes);
  if (bytes.StartsWith(std::string("II*\0", 4)) || bytes.StartsWith(std::string("MM\0*", 4))) {
    return ParseTiff(bytes);
  }
  if (bytes.U8(0) == 'P' && bytes.U8(1) >= '1' && bytes.U8(1) <= '6' && bytes.ok()) {
    return ParsePnm(bytes.Prefix(4096));
  }
  return std::nullopt;
}

}  // namespace

std::optional<ImageHeader> ParseImageHeader(const std::string& data) {
  Bytes bytes(data);
  return ParseHeader(bytes);
}

std::optional<ImageHeader> ReadImageHeader(const std::string& path) {
  // Missing or a folder: the decoder's reader says what is wrong.
  if (!PathExists(path) || IsDirectory(path)) return std::nullopt;
  CheckInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  Bytes bytes(&in);
  return ParseHeader(bytes);
}

}  // namespace comic::io
