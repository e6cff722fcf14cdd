#include "io/image/image_header.h"

#include <cctype>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

#include "io/core/error.h"
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

// A decimal number of at most 12 digits (beyond any size a header may declare), or none.
std::optional<int64_t> ParseDecimal(const std::string& text) {
  if (text.empty() || text.size() > 12 ||
      text.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return std::stoll(text);
}

// PAM (P7): "WIDTH n" and "HEIGHT n" lines before ENDHDR, in any order.
std::optional<ImageHeader> ParsePam(const std::string& text) {
  std::optional<int64_t> width;
  std::optional<int64_t> height;
  std::istringstream lines(text.substr(2));
  std::string line;
  while (std::getline(lines, line) && !lines.eof()) {  // the last line may be cut short
    std::istringstream words(line);
    std::string key;
    std::string value;
    words >> key >> value;
    if (key == "ENDHDR") break;
    if (key == "WIDTH") width = ParseDecimal(value);
    if (key == "HEIGHT") height = ParseDecimal(value);
  }
  if (!width || !height) return std::nullopt;
  return ImageHeader{"PAM", *width, *height};
}

// WebP: RIFF, a size, "WEBP", then the first chunk: lossy "VP8 " (14-bit sizes after the frame
// tag and start code), lossless "VP8L" (14-bit sizes minus one after the 0x2f signature) or
// extended "VP8X" (the canvas: 24-bit sizes minus one), which the decoder allocates.
std::optional<ImageHeader> ParseWebp(Bytes& bytes) {
  if (bytes.StartsWith("RIFF") && bytes.U32(8, true) == 0x57454250) {  // WEBP
    const uint32_t chunk = bytes.U32(12, true);
    if (chunk == 0x56503820) {  // "VP8 "
      if (bytes.U8(23) != 0x9d || bytes.U8(24) != 0x01 || bytes.U8(25) != 0x2a) return std::nullopt;
      return Done(bytes, "WebP", bytes.U16(26, false) & 0x3fff, bytes.U16(28, false) & 0x3fff);
    }
    if (chunk == 0x5650384c) {  // "VP8L"
      if (bytes.U8(20) != 0x2f) return std::nullopt;
      const uint32_t bits = bytes.U32(21, false);
      return Done(bytes, "WebP", 1 + (bits & 0x3fff), 1 + ((bits >> 14) & 0x3fff));
    }
    if (chunk == 0x56503858) {  // "VP8X"
      const uint32_t width = bytes.U8(24) | bytes.U8(25) << 8 | bytes.U8(26) << 16;
      const uint32_t height = bytes.U8(27) | bytes.U8(28) << 8 | bytes.U8(29) << 16;
      return Done(bytes, "WebP", int64_t{width} + 1, int64_t{height} + 1);
    }
  }
  return std::nullopt;
}

// Radiance HDR: "#?RADIANCE" or "#?RGBE", header lines up to an empty one, then the resolution
// line: "Y n X n" with a sign before each axis (most often "-Y height +X width"), or X first.
std::optional<ImageHeader> ParseRadiance(const std::string& text) {
  const size_t blank = text.find("\n\n");
  if (blank == std::string::npos) return std::nullopt;
  const size_t end = text.find('\n', blank + 2);
  if (end == std::string::npos) return std::nullopt;
  std::istringstream line(text.substr(blank + 2, end - blank - 2));
  std::string axes[2];
  std::string numbers[2];
  line >> axes[0] >> numbers[0] >> axes[1] >> numbers[1];
  const auto is_axis = [](const std::string& axis, char name) {
    return axis.size() == 2 && (axis[0] == '-' || axis[0] == '+') && axis[1] == name;
  };
  const bool y_first = is_axis(axes[0], 'Y') && is_axis(axes[1], 'X');
  const bool x_first = is_axis(axes[0], 'X') && is_axis(axes[1], 'Y');
  const std::optional<int64_t> first = ParseDecimal(numbers[0]);
  const std::optional<int64_t> second = ParseDecimal(numbers[1]);
  if (!(y_first || x_first) || !first || !second) return std::nullopt;
  return ImageHeader{"Radiance HDR", y_first ? *second : *first, y_first ? *first : *second};
}

// Sun raster: the magic, then width and height (32-bit big-endian).
std::optional<ImageHeader> ParseSunRaster(Bytes& bytes) {
  return Done(bytes, "Sun raster", bytes.U32(4, true), bytes.U32(8, true));
}

// JPEG 2000 codestream: SOC, then the SIZ segment: length, capabilities, the reference grid's
// size and the image's offset on it (32-bit big-endian each).
std::optional<ImageHeader> ParseJ2k(Bytes& bytes, size_t at) {
  if (bytes.U16(at, true) != 0xff4f || bytes.U16(at + 2, true) != 0xff51) return std::nullopt;
  const int64_t width = int64_t{bytes.U32(at + 8, true)} - bytes.U32(at + 16, true);
  const int64_t height = int64_t{bytes.U32(at + 12, true)} - bytes.U32(at + 20, true);
  if (width <= 0 || height <= 0) return std::nullopt;
  return Done(bytes, "JPEG 2000", width, height);
}

// JP2: boxes (32-bit length, type; length 1: a 64-bit length follows; 0: to the end) up to
// "jp2h", whose first box is "ihdr": height, width (32-bit big-endian).
std::optional<ImageHeader> ParseJp2(Bytes& bytes) {
  size_t at = 0;
  for (int boxes = 0; boxes < 64 && bytes.ok(); ++boxes) {
    uint64_t length = bytes.U32(at, true);
    const uint32_t type = bytes.U32(at + 4, true);
    size_t body = at + 8;
    if (length == 1) {
      length = uint64_t{bytes.U32(at + 8, true)} << 32 | bytes.U32(at + 12, true);
      body += 8;
    }
    if (type == 0x6a703268) {                              // "jp2h"
      if (bytes.U32(body + 4, true) != 0x69686472) break;  // "ihdr"
      return Done(bytes, "JPEG 2000", bytes.U32(body + 12, true), bytes.U32(body + 8, true));
    }
    if (length < body - at || length > (16u << 20)) break;  // 0 (to the end) included
    at += length;
  }
  return std::nullopt;
}

// OpenEXR: magic, version, then attributes (name, type, 32-bit little-endian size, value) up to
// an empty name; "dataWindow" (box2i: xMin, yMin, xMax, yMax) is the size the decoder allocates.
std::optional<ImageHeader> ParseExr(Bytes& bytes) {
  size_t at = 8;
  const auto read_name = [&]() {
    std::string name;
    for (uint32_t c = bytes.U8(at++); c != 0 && bytes.ok() && name.size() < 256;
         c = bytes.U8(at++)) {
      name += static_cast<char>(c);
    }
    return name;
  };
  for (int attributes = 0; attributes < 1024 && bytes.ok(); ++attributes) {
    const std::string name = read_name();
    if (name.empty()) return std::nullopt;  // end of the header, no data window
    const std::string type = read_name();
    const uint32_t size = bytes.U32(at, false);
    at += 4;
    if (name == "dataWindow") {
      if (type != "box2i" || size != 16) return std::nullopt;
      const int64_t x_min = static_cast<int32_t>(bytes.U32(at, false));
      const int64_t y_min = static_cast<int32_t>(bytes.U32(at + 4, false));
      const int64_t x_max = static_cast<int32_t>(bytes.U32(at + 8, false));
      const int64_t y_max = static_cast<int32_t>(bytes.U32(at + 12, false));
      if (x_max < x_min || y_max < y_min) return std::nullopt;
      return Done(bytes, "OpenEXR", x_max - x_min + 1, y_max - y_min + 1);
    }
    at += size;
  }
  return std::nullopt;
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
  if (bytes.U8(0) == 'P' && bytes.ok()) {
    const uint32_t kind = bytes.U8(1);
    if (kind >= '1' && kind <= '6') return ParsePnm(bytes.Prefix(4096));
    if (kind == '7') return ParsePam(bytes.Prefix(4096));
    if (kind == 'F' || kind == 'f') {
      std::optional<ImageHeader> header = ParsePnm(bytes.Prefix(4096));
      if (header) header->format = "PFM";
      return header;
    }
  }
  if (bytes.StartsWith("RIFF")) return ParseWebp(bytes);
  if (bytes.StartsWith("#?RADIANCE\n") || bytes.StartsWith("#?RGBE\n")) {
    return ParseRadiance(bytes.Prefix(64 << 10));
  }
  if (bytes.StartsWith("\x59\xa6\x6a\x95")) return ParseSunRaster(bytes);
  if (bytes.StartsWith("\xff\x4f\xff\x51")) return ParseJ2k(bytes, 0);
  if (bytes.StartsWith(std::string("\0\0\0\x0cjP  \r\n\x87\n", 12))) return ParseJp2(bytes);
  if (bytes.StartsWith("\x76\x2f\x31\x01")) return ParseExr(bytes);
  return std::nullopt;
}

}  // namespace

std::optional<ImageHeader> ParseImageHeader(const std::string& data) {
  Bytes bytes(data);
  return ParseHeader(bytes);
}

const char* ReadableImageFormats() {
  return "PNG, JPEG, BMP, TIFF, PNM, PAM, PFM, WebP, Radiance HDR, Sun raster, JPEG 2000, OpenEXR";
}

ImageHeader RequireImageHeader(const std::string& path) {
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such file");
  COMIC_CHECK(!IsDirectory(path), kInvalidData, path << ": is a folder, not an image file");
  std::optional<ImageHeader> header = ReadImageHeader(path);
  COMIC_CHECK(header.has_value(), kInvalidData,
              path << ": cannot decode image (empty, not an image, or its header is cut short or "
                      "malformed; the formats read are "
                   << ReadableImageFormats() << ")");
  return std::move(*header);
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
