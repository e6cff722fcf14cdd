#include "io/image/exif_focal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace comic::io {
namespace {

constexpr uint16_t kExifIfdPointer = 0x8769;
constexpr uint16_t kFocalLength = 0x920A;
constexpr uint16_t kFocalLengthIn35mmFilm = 0xA405;
constexpr uint16_t kFocalPlaneXResolution = 0xA20E;
constexpr uint16_t kFocalPlaneResolutionUnit = 0xA210;
constexpr uint16_t kPixelXDimension = 0xA002;
constexpr uint16_t kPixelYDimension = 0xA003;

// COLMAP's divisor for FocalLengthIn35mmFilm: between the 36 mm long side of a 3:2 frame and the
// 34.6 mm a 4:3 sensor's diagonal equivalence gives, and the same answer COLMAP's prior gives.
constexpr double kFilmLongSideMm = 35.0;

// Bounded reads from the TIFF block of an Exif segment: a read past its end gives std::nullopt.
class TiffBytes {
 public:
  explicit TiffBytes(std::string_view bytes) : bytes_(bytes) {}

  // Reads the byte order from the header; false when it is not "II*\0" or "MM\0*".
  bool ReadHeader() {
    if (bytes_.size() < 8) return false;
    if (bytes_.substr(0, 2) == "II") {
      big_endian_ = false;
    } else if (bytes_.substr(0, 2) == "MM") {
      big_endian_ = true;
    } else {
      return false;
    }
    return U16(2) == 42;
  }
  std::optional<uint32_t> U16(uint64_t at) const {
    if (at + 2 > bytes_.size()) return std::nullopt;
    const uint32_t a = Byte(at), b = Byte(at + 1);
    return big_endian_ ? (a << 8) | b : (b << 8) | a;
  }
  std::optional<uint32_t> U32(uint64_t at) const {
    const auto a = U16(at), b = U16(at + 2);
    if (!a || !b) return std::nullopt;
    return big_endian_ ? (*a << 16) | *b : (*b << 16) | *a;
  }

 private:
  uint32_t Byte(uint64_t at) const { return static_cast<unsigned char>(bytes_[at]); }
  std::string_view bytes_;
  bool big_endian_ = false;
};

// The first value of the IFD entry at `entry` as a number, for the integer and rational types;
// std::nullopt for another type, no value, a zero denominator or a value out of bounds.
std::optional<double> EntryNumber(const TiffBytes& tiff, uint64_t entry) {
  const auto type = tiff.U16(entry + 2);
  const auto count = tiff.U32(entry + 4);
  if (!type || !count || *count == 0) return std::nullopt;
  switch (*type) {
    case 3:  // SHORT
      return tiff.U16(entry + 8);
    case 4:  // LONG
      return tiff.U32(entry + 8);
    case 9:  // SLONG
      if (const auto value = tiff.U32(entry + 8)) return static_cast<int32_t>(*value);
      return std::nullopt;
    case 5:     // RATIONAL
    case 10: {  // SRATIONAL: eight bytes, always stored at an offset
      const auto offset = tiff.U32(entry + 8);
      if (!offset) return std::nullopt;
      const auto numerator = tiff.U32(*offset), denominator = tiff.U32(uint64_t{*offset} + 4);
      if (!numerator || !denominator || *denominator == 0) return std::nullopt;
      if (*type == 5) return static_cast<double>(*numerator) / *denominator;
      return static_cast<double>(static_cast<int32_t>(*numerator)) /
             static_cast<int32_t>(*denominator);
    }
    default:
      return std::nullopt;
  }
}

// A focal length or resolution as the file states it: positive and finite, else absent (EXIF
// writes 0 for "unknown").
std::optional<double> Positive(const std::optional<double>& value) {
  if (value && std::isfinite(*value) && *value > 0) return value;
  return std::nullopt;
}

// Calls visit(tag, entry offset) for each entry of the IFD at `ifd`; false when the IFD does not
// lie within the bytes.
template <typename Visit>
bool ForEachEntry(const TiffBytes& tiff, uint64_t ifd, Visit visit) {
  const auto count = tiff.U16(ifd);
  if (!count) return false;
  // The last entry's last four bytes: the whole table lies within the segment.
  if (*count > 0 && !tiff.U32(ifd + 2 + 12 * uint64_t{*count} - 4)) return false;
  for (uint32_t k = 0; k < *count; ++k) {
    const uint64_t entry = ifd + 2 + 12 * uint64_t{k};
    visit(*tiff.U16(entry), entry);
  }
  return true;
}

void ReadExifEntry(const TiffBytes& tiff, uint16_t tag, uint64_t entry, ExifFocal* exif) {
  const std::optional<double> value = EntryNumber(tiff, entry);
  switch (tag) {
    case kFocalLength:
      exif->focal_length_mm = Positive(value);
      break;
    case kFocalLengthIn35mmFilm:
      exif->focal_length_35mm = Positive(value);
      break;
    case kFocalPlaneXResolution:
      exif->focal_plane_x_resolution = Positive(value);
      break;
    case kFocalPlaneResolutionUnit:
      // A SHORT by the standard; another type may hold a value no int holds: an unknown unit.
      if (value) {
        exif->focal_plane_resolution_unit =
            *value >= 0 && *value <= 65535 ? static_cast<int>(*value) : 0;
      }
      break;
    case kPixelXDimension:
      if (Positive(value)) exif->pixel_x_dimension = static_cast<int64_t>(*value);
      break;
    case kPixelYDimension:
      if (Positive(value)) exif->pixel_y_dimension = static_cast<int64_t>(*value);
      break;
    default:
      break;
  }
}

// The tags of a TIFF block (the Exif segment after "Exif\0\0"): IFD0's ExifIFD pointer, then
// that one IFD. No other pointer is followed.
std::optional<ExifFocal> ParseTiff(std::string_view bytes) {
  TiffBytes tiff(bytes);
  if (!tiff.ReadHeader()) return std::nullopt;
  const auto ifd0 = tiff.U32(4);
  if (!ifd0) return std::nullopt;
  std::optional<uint32_t> exif_ifd;
  const bool ifd0_ok = ForEachEntry(tiff, *ifd0, [&](uint16_t tag, uint64_t entry) {
    if (tag == kExifIfdPointer) exif_ifd = tiff.U32(entry + 8);
  });
  if (!ifd0_ok || !exif_ifd) return std::nullopt;
  ExifFocal exif;
  const bool exif_ok = ForEachEntry(tiff, *exif_ifd, [&](uint16_t tag, uint64_t entry) {
    ReadExifEntry(tiff, tag, entry, &exif);
  });
  if (!exif_ok) return std::nullopt;
  return exif;
}

uint32_t ByteAt(std::string_view bytes, size_t at) { return static_cast<unsigned char>(bytes[at]); }

}  // namespace

std::optional<ExifFocal> ParseJpegExifFocal(std::string_view bytes) {
  if (bytes.size() < 4 || ByteAt(bytes, 0) != 0xFF || ByteAt(bytes, 1) != 0xD8) return std::nullopt;
  size_t at = 2;
  // Segments up to the scan: each is FF, a marker, and (except RSTn and TEM) a big-endian length
  // that counts itself, so every step moves forward.
  while (at + 4 <= bytes.size()) {
    if (ByteAt(bytes, at) != 0xFF) return std::nullopt;
    const uint32_t marker = ByteAt(bytes, at + 1);
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0xDA || marker == 0xD9) return std::nullopt;  // scan or end: no Exif before
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {
      at += 2;
      continue;
    }
    const size_t length = (ByteAt(bytes, at + 2) << 8) | ByteAt(bytes, at + 3);
    if (length < 2 || at + 2 + length > bytes.size()) return std::nullopt;
    const std::string_view segment = bytes.substr(at + 4, length - 2);
    if (marker == 0xE1 && segment.substr(0, 6) == std::string_view("Exif\0\0", 6)) {
      return ParseTiff(segment.substr(6));
    }
    at += 2 + length;
  }
  return std::nullopt;
}

std::optional<ExifFocal> ReadJpegExifFocal(const std::string& path) {
  constexpr size_t kMaxBytes = 256 << 10;
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  std::string bytes(kMaxBytes, '\0');
  file.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<size_t>(std::max<std::streamsize>(file.gcount(), 0)));
  return ParseJpegExifFocal(bytes);
}

std::optional<ExifFocalPixels> ExifFocalInPixels(const ExifFocal& exif, int width, int height) {
  const double max_size = std::max(width, height);
  if (max_size <= 0) return std::nullopt;
  char words[96];
  if (exif.focal_length_35mm) {
    std::snprintf(words, sizeof(words), "FocalLengthIn35mmFilm %g mm", *exif.focal_length_35mm);
    return ExifFocalPixels{*exif.focal_length_35mm / kFilmLongSideMm * max_size, words};
  }
  double mm_per_unit = 0;
  switch (exif.focal_plane_resolution_unit) {
    case 2:
      mm_per_unit = 25.4;
      break;
    case 3:
      mm_per_unit = 10.0;
      break;
    case 4:
      mm_per_unit = 1.0;
      break;
    case 5:
      mm_per_unit = 1e-3;
      break;
    default:
      return std::nullopt;
  }
  if (!exif.focal_length_mm || !exif.focal_plane_x_resolution) return std::nullopt;
  // PixelXDimension rather than the image's width, as COLMAP: a resized photo keeps its EXIF.
  const double pixels_across = exif.pixel_x_dimension ? *exif.pixel_x_dimension : width;
  const double sensor_width_mm = pixels_across / *exif.focal_plane_x_resolution * mm_per_unit;
  if (!std::isfinite(sensor_width_mm) || sensor_width_mm <= 0) return std::nullopt;
  std::snprintf(words, sizeof(words), "FocalLength %g mm on a %.3g mm wide sensor",
                *exif.focal_length_mm, sensor_width_mm);
  return ExifFocalPixels{*exif.focal_length_mm / sensor_width_mm * max_size, words};
}

}  // namespace comic::io
