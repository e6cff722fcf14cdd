#include "io/image/exif_focal.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/io/image/exif_test_jpeg.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ExifTestTags;
using comic::test::ExifTiff;
using comic::test::SmallJpeg;
using comic::test::WithExifSegment;

ExifTestTags PhoneTags() {
  ExifTestTags tags;
  tags.focal_length_35mm = 28;
  tags.focal_mm = {{473, 100}};  // 4.73 mm
  return tags;
}

// A Canon-like file: no 35 mm equivalent, focal 18 mm, 5184 pixels over a 22.3 mm sensor
// (FocalPlaneXResolution in pixels per inch).
ExifTestTags SensorTags() {
  ExifTestTags tags;
  tags.focal_mm = {{18, 1}};
  tags.x_resolution = {{5184u * 254u, 223u}};  // 5184 px / (22.3 mm / 25.4 mm per inch)
  tags.resolution_unit = 2;
  tags.pixel_x_dimension = 5184;
  return tags;
}

TEST(ExifFocal, ReadsTheTagsInBothByteOrders) {
  for (const bool big_endian : {false, true}) {
    SCOPED_TRACE(big_endian ? "MM" : "II");
    const auto exif =
        ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(PhoneTags(), big_endian)));
    ASSERT_TRUE(exif.has_value());
    EXPECT_EQ(exif->focal_length_35mm, 28.0);
    EXPECT_DOUBLE_EQ(*exif->focal_length_mm, 4.73);
    EXPECT_FALSE(exif->focal_plane_x_resolution.has_value());
    const auto sensor =
        ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(SensorTags(), big_endian)));
    ASSERT_TRUE(sensor.has_value());
    EXPECT_DOUBLE_EQ(*sensor->focal_plane_x_resolution, 5184.0 * 254 / 223);
    EXPECT_EQ(sensor->focal_plane_resolution_unit, 2);
    EXPECT_EQ(sensor->pixel_x_dimension, 5184);
  }
}

TEST(ExifFocal, PixelsFromThe35mmEquivalentAsColmap) {
  const auto exif = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(PhoneTags(), false)));
  ASSERT_TRUE(exif.has_value());
  // COLMAP: f35 / 35 * max(w, h); the 35 mm equivalent wins over FocalLength.
  const auto pixels = ExifFocalInPixels(*exif, 4032, 3024);
  ASSERT_TRUE(pixels.has_value());
  EXPECT_DOUBLE_EQ(pixels->focal_px, 28.0 / 35.0 * 4032);
  EXPECT_EQ(pixels->from, "FocalLengthIn35mmFilm 28 mm");
  // Portrait: the long side still counts.
  EXPECT_DOUBLE_EQ(ExifFocalInPixels(*exif, 3024, 4032)->focal_px, 28.0 / 35.0 * 4032);
}

TEST(ExifFocal, PixelsFromFocalLengthAndSensorWidth) {
  const auto exif = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(SensorTags(), true)));
  ASSERT_TRUE(exif.has_value());
  // 18 mm / 22.3 mm * 5184 px at the photo's size, 2592 px at half size.
  EXPECT_NEAR(ExifFocalInPixels(*exif, 5184, 3456)->focal_px, 18.0 / 22.3 * 5184, 1e-9);
  EXPECT_NEAR(ExifFocalInPixels(*exif, 2592, 1728)->focal_px, 18.0 / 22.3 * 2592, 1e-9);
  // Centimetres: the same sensor, resolution given per cm.
  ExifTestTags cm = SensorTags();
  cm.x_resolution = {{5184u * 100u, 223u}};  // 5184 px / 2.23 cm
  cm.resolution_unit = 3;
  const auto in_cm = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(cm, false)));
  EXPECT_NEAR(ExifFocalInPixels(*in_cm, 5184, 3456)->focal_px, 18.0 / 22.3 * 5184, 1e-9);
  // Without PixelXDimension the image's own width stands for it.
  ExifTestTags no_dimension = SensorTags();
  no_dimension.pixel_x_dimension.reset();
  const auto without =
      ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(no_dimension, false)));
  EXPECT_NEAR(ExifFocalInPixels(*without, 5184, 3456)->focal_px, 18.0 / 22.3 * 5184, 1e-9);
}

TEST(ExifFocal, NoFocalWithoutEnoughTags) {
  ExifTestTags focal_only;
  focal_only.focal_mm = {{18, 1}};
  const auto exif = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(focal_only, false)));
  ASSERT_TRUE(exif.has_value());
  EXPECT_TRUE(exif->HasFocal());
  EXPECT_FALSE(ExifFocalInPixels(*exif, 640, 480).has_value());  // no sensor width
  ExifTestTags unknown;
  unknown.focal_length_35mm = 0;  // EXIF's "unknown"
  const auto zero = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(unknown, false)));
  ASSERT_TRUE(zero.has_value());
  EXPECT_FALSE(zero->HasFocal());
  ExifTestTags bad_unit = SensorTags();
  bad_unit.resolution_unit = 7;
  const auto odd = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), ExifTiff(bad_unit, false)));
  EXPECT_FALSE(ExifFocalInPixels(*odd, 5184, 3456).has_value());
  EXPECT_FALSE(ParseJpegExifFocal(SmallJpeg()).has_value());  // a JPEG without EXIF
}

TEST(ExifFocal, AUnitTooLargeForAnIntIsNoUnit) {
  // The resolution unit stored as a LONG of 0xFFFFFFFF instead of a SHORT (a file the fuzzer
  // made): read as no unit, without converting it to an int it does not fit.
  std::string tiff = ExifTiff(SensorTags(), false);
  const std::string unit_entry("\x10\xA2\x03\x00\x01\x00\x00\x00", 8);
  const size_t at = tiff.find(unit_entry);
  ASSERT_NE(at, std::string::npos);
  tiff.replace(at + 2, 2, std::string("\x04\x00", 2));
  tiff.replace(at + 8, 4, std::string("\xFF\xFF\xFF\xFF", 4));
  const auto exif = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), tiff));
  ASSERT_TRUE(exif.has_value());
  EXPECT_TRUE(exif->HasFocal());
  EXPECT_FALSE(ExifFocalInPixels(*exif, 5184, 3456).has_value());
}

TEST(ExifFocal, TruncatedSegmentsAreNoExif) {
  const std::string tiff = ExifTiff(SensorTags(), false);
  const std::string whole = WithExifSegment(SmallJpeg(), tiff);
  // The file cut anywhere inside the segment: no EXIF, never a read past the end.
  for (size_t size = 0; size < 2 + 4 + 6 + tiff.size(); ++size) {
    EXPECT_FALSE(ParseJpegExifFocal(whole.substr(0, size)).has_value()) << size;
  }
  // The TIFF block cut short inside a segment whose length matches it.
  for (size_t size = 0; size < tiff.size(); ++size) {
    const auto exif = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), tiff.substr(0, size)));
    EXPECT_FALSE(exif && ExifFocalInPixels(*exif, 5184, 3456).has_value()) << size;
  }
}

TEST(ExifFocal, CyclicAndWildOffsetsAreNoExif) {
  std::string tiff = ExifTiff(PhoneTags(), false);
  // The ExifIFD pointer pointing back at IFD0: IFD0 holds no focal tag, and is read once.
  tiff[comic::test::kTestExifPointerValueAt] = static_cast<char>(comic::test::kTestIfd0Offset);
  const auto cyclic = ParseJpegExifFocal(WithExifSegment(SmallJpeg(), tiff));
  ASSERT_TRUE(cyclic.has_value());
  EXPECT_FALSE(cyclic->HasFocal());
  // Pointers to the last byte and far beyond the segment.
  for (const uint32_t offset :
       {0xFFFFFFFFu, 0x7FFFFFF0u, 0u + static_cast<uint32_t>(tiff.size())}) {
    std::string wild = ExifTiff(PhoneTags(), false);
    for (int k = 0; k < 4; ++k) {
      wild[comic::test::kTestExifPointerValueAt + k] = static_cast<char>(offset >> (8 * k));
    }
    EXPECT_FALSE(ParseJpegExifFocal(WithExifSegment(SmallJpeg(), wild)).has_value()) << offset;
    std::string wild_ifd0 = ExifTiff(PhoneTags(), false);
    for (int k = 0; k < 4; ++k) wild_ifd0[4 + k] = static_cast<char>(offset >> (8 * k));
    EXPECT_FALSE(ParseJpegExifFocal(WithExifSegment(SmallJpeg(), wild_ifd0)).has_value());
  }
}

TEST(ExifFocal, GarbageIsNoExif) {
  uint32_t state = 12345;
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bytes = WithExifSegment(SmallJpeg(), ExifTiff(SensorTags(), trial % 2 == 0));
    // A few random bytes of the segment overwritten: parsing must not crash or read out of
    // bounds (the sanitizer build checks the latter).
    for (int k = 0; k < 4; ++k) {
      state = state * 1664525u + 1013904223u;
      bytes[2 + (state >> 8) % 80] = static_cast<char>(state >> 24);
    }
    const auto exif = ParseJpegExifFocal(bytes);
    if (exif) ExifFocalInPixels(*exif, 640, 480);
  }
  EXPECT_FALSE(ParseJpegExifFocal("").has_value());
  EXPECT_FALSE(ParseJpegExifFocal("\xFF\xD8").has_value());
  EXPECT_FALSE(ParseJpegExifFocal(std::string(1000, '\xFF')).has_value());
  EXPECT_FALSE(ParseJpegExifFocal(std::string("\xFF\xD8\xFF\xE1\x00\x01", 6)).has_value());
}

TEST(ExifFocal, ReadsTheFileAndMissingFilesAreNoExif) {
  comic::test::ScopedTempDir dir;
  {
    std::ofstream file(dir.File("a.jpg"), std::ios::binary);
    file << WithExifSegment(SmallJpeg(), ExifTiff(PhoneTags(), true));
  }
  const auto exif = ReadJpegExifFocal(dir.File("a.jpg"));
  ASSERT_TRUE(exif.has_value());
  EXPECT_EQ(exif->focal_length_35mm, 28.0);
  EXPECT_FALSE(ReadJpegExifFocal(dir.File("missing.jpg")).has_value());
  EXPECT_FALSE(ReadJpegExifFocal(dir.path()).has_value());  // a folder
}

}  // namespace
}  // namespace comic::io
