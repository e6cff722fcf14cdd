#include "io/image/image_header.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;

std::string Encode(const std::string& extension, const cv::Mat& image) {
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes));
  return std::string(bytes.begin(), bytes.end());
}

std::string BigEndian32(uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16),
          static_cast<char>(value >> 8), static_cast<char>(value)};
}

// The first 33 bytes of a PNG: signature and IHDR of the given size (8-bit grey), CRC not checked.
std::string PngHeader(uint32_t width, uint32_t height) {
  return std::string("\x89PNG\r\n\x1a\n", 8) + BigEndian32(13) + "IHDR" + BigEndian32(width) +
         BigEndian32(height) + std::string("\x08\x00\x00\x00\x00", 5) + BigEndian32(0);
}

TEST(ImageHeader, ReadsTheSizeOfEveryFormatTheSequencesRead) {
  const cv::Mat grey(37, 53, CV_8UC1, cv::Scalar(90));
  const cv::Mat colour(37, 53, CV_8UC3, cv::Scalar(10, 90, 200));
  const std::vector<std::pair<std::string, std::string>> cases = {{".png", "PNG"}, {".jpg", "JPEG"},
                                                                  {".bmp", "BMP"}, {".tif", "TIFF"},
                                                                  {".pgm", "PNM"}, {".ppm", "PNM"}};
  for (const auto& [extension, format] : cases) {
    for (const cv::Mat& image : {grey, colour}) {
      if (extension == ".pgm" && image.channels() == 3) continue;
      if (extension == ".ppm" && image.channels() == 1) continue;
      SCOPED_TRACE(extension + " " + std::to_string(image.channels()));
      const auto header = ParseImageHeader(Encode(extension, image));
      ASSERT_TRUE(header.has_value());
      EXPECT_EQ(header->format, format);
      EXPECT_EQ(header->width, 53);
      EXPECT_EQ(header->height, 37);
    }
  }
}

TEST(ImageHeader, FindsTheJpegFrameAfterLargeSegments) {
  std::string jpeg = Encode(".jpg", cv::Mat(20, 30, CV_8UC1, cv::Scalar(7)));
  // An APP1 segment of 60 kB (EXIF with a thumbnail, say) between SOI and the rest.
  const uint16_t length = 60000;
  const std::string app1 = std::string("\xff\xe1", 2) + static_cast<char>(length >> 8) +
                           static_cast<char>(length & 0xff) + std::string(length - 2, 'e');
  jpeg.insert(2, app1);
  ScopedTempDir dir;
  WriteFileAtomically(dir.File("big_app.jpg"), jpeg);
  const auto header = ReadImageHeader(dir.File("big_app.jpg"));
  ASSERT_TRUE(header.has_value());
  EXPECT_EQ(header->width, 30);
  EXPECT_EQ(header->height, 20);
}

TEST(ImageHeader, ReadsBigEndianTiffWithItsDirectoryAfterThePixels) {
  // "MM", 42, IFD at offset 108 (after 100 bytes of pixels); 2 entries: width LONG 70000,
  // length SHORT 3.
  std::string tiff = std::string("MM\0*", 4) + BigEndian32(108) + std::string(100, '\0');
  tiff += std::string("\x00\x02", 2);
  tiff += std::string("\x01\x00\x00\x04", 4) + BigEndian32(1) + BigEndian32(70000);
  tiff += std::string("\x01\x01\x00\x03", 4) + BigEndian32(1) + std::string("\x00\x03\x00\x00", 4);
  const auto header = ParseImageHeader(tiff);
  ASSERT_TRUE(header.has_value());
  EXPECT_EQ(header->width, 70000);
  EXPECT_EQ(header->height, 3);
}

TEST(ImageHeader, GivesNothingForOtherOrBrokenHeaders) {
  EXPECT_FALSE(ParseImageHeader("").has_value());
  EXPECT_FALSE(ParseImageHeader("GIF89a...").has_value());
  EXPECT_FALSE(ParseImageHeader(PngHeader(10, 10).substr(0, 20)).has_value());
  EXPECT_FALSE(ParseImageHeader(std::string("\xff\xd8\xff\xe1\x40\x00", 6)).has_value());
  EXPECT_FALSE(ParseImageHeader(std::string("II*\0\xff\xff\xff\x7f", 8)).has_value());
  EXPECT_FALSE(ParseImageHeader("P5\n# only a comment").has_value());
  EXPECT_FALSE(ReadImageHeader("/nonexistent/image.png").has_value());
  const auto pnm = ParseImageHeader("P6\n# made by hand\n 640\t480\n255\n");
  ASSERT_TRUE(pnm.has_value());
  EXPECT_EQ(pnm->width, 640);
  EXPECT_EQ(pnm->height, 480);
}

// Issue 29: an 875 kB PNG declaring 30000x30000 was decoded (937 MB) before the budget refused
// it. Now the header refuses it, whatever follows the header.
TEST(ImageHeader, TheBudgetRefusesAHugeDeclaredImageBeforeDecoding) {
  ScopedTempDir dir;
  const std::string path = dir.File("huge.png");
  WriteFileAtomically(path, PngHeader(30000, 30000) + std::string(1000, '\0'));
  try {
    LoadImage(path);
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    EXPECT_NE(std::string(e.what()).find(path + ": 30000x30000 = 900000000 pixels exceeds"),
              std::string::npos)
        << e.what();
  }
  // Resized to 700 rows the same image is within the budget: the header passes it to the decoder,
  // which then finds the data broken.
  EXPECT_NO_THROW(CheckImageHeaderBudget(path, 700, kDefaultMaxPixels));
  EXPECT_THROW(CheckImageHeaderBudget(path, 0, kDefaultMaxPixels), Error);
  // A declared size beyond int (2^32 - 1 wide) is refused too, without overflow.
  WriteFileAtomically(path, PngHeader(0xffffffffu, 2) + std::string(100, '\0'));
  EXPECT_THROW(CheckImageHeaderBudget(path, 0, kMaxMaxPixels), Error);
}

}  // namespace
}  // namespace comic::io
