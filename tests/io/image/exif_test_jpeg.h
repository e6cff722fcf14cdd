// JPEG bytes with an Exif APP1 segment assembled by hand, for the EXIF reader's tests and the
// end-to-end run with an EXIF focal: a TIFF block in either byte order whose IFD0 holds only the
// ExifIFD pointer, and an ExifIFD with the focal tags asked for, spliced after a real JPEG's SOI.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <vector>

namespace comic::test {

struct ExifTestTags {
  std::optional<uint16_t> focal_length_35mm;                  // SHORT
  std::optional<std::pair<uint32_t, uint32_t>> focal_mm;      // RATIONAL
  std::optional<std::pair<uint32_t, uint32_t>> x_resolution;  // RATIONAL, pixels per unit
  std::optional<uint16_t> resolution_unit;                    // SHORT
  std::optional<uint32_t> pixel_x_dimension;                  // LONG
};

// Offsets inside the TIFF block ExifTiff writes (the tests corrupt them).
inline constexpr size_t kTestIfd0Offset = 8;
inline constexpr size_t kTestExifPointerValueAt = kTestIfd0Offset + 2 + 8;
inline constexpr size_t kTestExifIfdOffset = kTestIfd0Offset + 2 + 12 + 4;

class TiffWriter {
 public:
  explicit TiffWriter(bool big_endian) : big_endian_(big_endian) {}
  void U16(uint32_t value) {
    if (big_endian_) {
      Byte(value >> 8);
      Byte(value);
    } else {
      Byte(value);
      Byte(value >> 8);
    }
  }
  void U32(uint32_t value) {
    if (big_endian_) {
      U16(value >> 16);
      U16(value & 0xFFFF);
    } else {
      U16(value & 0xFFFF);
      U16(value >> 16);
    }
  }
  void Entry(uint16_t tag, uint16_t type, uint32_t count, uint32_t value) {
    U16(tag);
    U16(type);
    U32(count);
    if (type == 3) {
      U16(value);  // a SHORT is left-justified in the four value bytes
      U16(0);
    } else {
      U32(value);
    }
  }
  std::string bytes;

 private:
  void Byte(uint32_t value) { bytes += static_cast<char>(value & 0xFF); }
  bool big_endian_;
};

// The TIFF block of an Exif segment holding `tags`.
inline std::string ExifTiff(const ExifTestTags& tags, bool big_endian) {
  TiffWriter tiff(big_endian);
  tiff.bytes = big_endian ? std::string("MM\0*", 4) : std::string("II*\0", 4);
  tiff.U32(kTestIfd0Offset);
  tiff.U16(1);
  tiff.Entry(0x8769, 4, 1, kTestExifIfdOffset);
  tiff.U32(0);
  const uint32_t count = !!tags.focal_length_35mm + !!tags.focal_mm + !!tags.x_resolution +
                         !!tags.resolution_unit + !!tags.pixel_x_dimension;
  // The rationals follow the IFD.
  uint32_t data_at = kTestExifIfdOffset + 2 + 12 * count + 4;
  std::vector<std::pair<uint32_t, uint32_t>> rationals;
  tiff.U16(count);
  if (tags.pixel_x_dimension) tiff.Entry(0xA002, 4, 1, *tags.pixel_x_dimension);
  if (tags.focal_mm) {
    tiff.Entry(0x920A, 5, 1, data_at);
    data_at += 8;
    rationals.push_back(*tags.focal_mm);
  }
  if (tags.x_resolution) {
    tiff.Entry(0xA20E, 5, 1, data_at);
    data_at += 8;
    rationals.push_back(*tags.x_resolution);
  }
  if (tags.resolution_unit) tiff.Entry(0xA210, 3, 1, *tags.resolution_unit);
  if (tags.focal_length_35mm) tiff.Entry(0xA405, 3, 1, *tags.focal_length_35mm);
  tiff.U32(0);
  for (const auto& [numerator, denominator] : rationals) {
    tiff.U32(numerator);
    tiff.U32(denominator);
  }
  return tiff.bytes;
}

// `tiff` as an APP1 Exif segment spliced after the SOI of `jpeg`.
inline std::string WithExifSegment(const std::string& jpeg, const std::string& tiff) {
  const size_t length = 2 + 6 + tiff.size();
  std::string segment = "\xFF\xE1";
  segment += static_cast<char>(length >> 8);
  segment += static_cast<char>(length & 0xFF);
  segment += std::string("Exif\0\0", 6) + tiff;
  return jpeg.substr(0, 2) + segment + jpeg.substr(2);
}

// A small real JPEG (a grey gradient) to splice into.
inline std::string SmallJpeg() {
  cv::Mat image(48, 64, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image.at<uchar>(y, x) = static_cast<uchar>(3 * x + y);
  }
  std::vector<uchar> bytes;
  cv::imencode(".jpg", image, bytes);
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace comic::test
