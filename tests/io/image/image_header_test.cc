#include "io/image/image_header.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <string>
#include <tuple>
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

std::string LittleEndian32(uint32_t value) {
  return {static_cast<char>(value), static_cast<char>(value >> 8), static_cast<char>(value >> 16),
          static_cast<char>(value >> 24)};
}

// Tiny files of the other formats OpenCV decodes, each declaring `width` x `height`: headers only,
// no pixel data, as a hostile file would be.
std::string WebpVp8lHeader(uint32_t width, uint32_t height) {
  const uint32_t bits = (width - 1) | (height - 1) << 14;
  return "RIFF" + LittleEndian32(100) + "WEBPVP8L" + LittleEndian32(80) + "\x2f" +
         LittleEndian32(bits) + std::string(20, '\0');
}
std::string WebpVp8xHeader(uint32_t width, uint32_t height) {
  const auto u24 = [](uint32_t v) { return LittleEndian32(v - 1).substr(0, 3); };
  return "RIFF" + LittleEndian32(100) + "WEBPVP8X" + LittleEndian32(10) + std::string(4, '\0') +
         u24(width) + u24(height) + std::string(20, '\0');
}
std::string WebpVp8Header(uint16_t width, uint16_t height) {
  return "RIFF" + LittleEndian32(100) + "WEBPVP8 " + LittleEndian32(80) + std::string(3, '\0') +
         "\x9d\x01\x2a" + LittleEndian32(width | uint32_t{height} << 16) + std::string(20, '\0');
}
std::string RadianceHeader(const std::string& resolution) {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1.0\n\n" + resolution + "\n" +
         std::string(16, '\0');
}
std::string SunRasterHeader(uint32_t width, uint32_t height) {
  return "\x59\xa6\x6a\x95" + BigEndian32(width) + BigEndian32(height) + BigEndian32(8) +
         std::string(16, '\0');
}
std::string J2kHeader(uint32_t width, uint32_t height) {
  return std::string("\xff\x4f\xff\x51\x00\x29\x00\x00", 8) + BigEndian32(width) +
         BigEndian32(height) + std::string(24, '\0');
}
std::string Jp2Header(uint32_t width, uint32_t height) {
  return std::string("\0\0\0\x0cjP  \r\n\x87\n", 12) + BigEndian32(20) + "ftypjp2 " +
         std::string(4, '\0') + "jp2 " + BigEndian32(45) + "jp2h" + BigEndian32(22) + "ihdr" +
         BigEndian32(height) + BigEndian32(width) + std::string(6, '\0');
}
std::string ExrHeader(int32_t width, int32_t height) {
  const auto attribute = [](const std::string& name, const std::string& type,
                            const std::string& value) {
    return name + '\0' + type + '\0' + LittleEndian32(static_cast<uint32_t>(value.size())) + value;
  };
  return "\x76\x2f\x31\x01" + LittleEndian32(2) + attribute("compression", "compression", "\x03") +
         attribute("dataWindow", "box2i",
                   LittleEndian32(0) + LittleEndian32(0) + LittleEndian32(width - 1) +
                       LittleEndian32(height - 1)) +
         std::string(1, '\0');
}

TEST(ImageHeader, ReadsTheSizeOfEveryOtherFormatOpenCvDecodes) {
  const cv::Mat grey(37, 53, CV_8UC1, cv::Scalar(90));
  const cv::Mat colour(37, 53, CV_8UC3, cv::Scalar(10, 90, 200));
  const cv::Mat radiance(37, 53, CV_32FC3, cv::Scalar(0.1, 0.5, 2.0));
  const std::vector<std::tuple<std::string, std::string, cv::Mat>> cases = {
      {".webp", "WebP", colour},      {".hdr", "Radiance HDR", radiance},
      {".ras", "Sun raster", colour}, {".jp2", "JPEG 2000", colour},
      {".pam", "PAM", colour},        {".pfm", "PFM", radiance},
      {".exr", "OpenEXR", radiance},  {".pbm", "PNM", grey}};
  for (const auto& [extension, format, image] : cases) {
    SCOPED_TRACE(extension);
    ASSERT_TRUE(cv::haveImageWriter("x" + extension));
    const auto header = ParseImageHeader(Encode(extension, image));
    ASSERT_TRUE(header.has_value());
    EXPECT_EQ(header->format, format);
    EXPECT_EQ(header->width, 53);
    EXPECT_EQ(header->height, 37);
  }
  // Lossless WebP is the VP8L chunk; the lossy one above the VP8 chunk.
  const auto lossless = ParseImageHeader([&] {
    std::vector<uchar> bytes;
    EXPECT_TRUE(cv::imencode(".webp", colour, bytes, {cv::IMWRITE_WEBP_QUALITY, 101}));
    return std::string(bytes.begin(), bytes.end());
  }());
  ASSERT_TRUE(lossless.has_value());
  EXPECT_EQ(lossless->width, 53);
  EXPECT_EQ(lossless->height, 37);
}

TEST(ImageHeader, ReadsHugeSizesFromTinyCraftedHeaders) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {WebpVp8lHeader(12000, 12000), "WebP"},
      {WebpVp8xHeader(12000, 12000), "WebP"},
      {WebpVp8Header(12000, 12000), "WebP"},
      {RadianceHeader("-Y 12000 +X 12000"), "Radiance HDR"},
      {SunRasterHeader(12000, 12000), "Sun raster"},
      {J2kHeader(12000, 12000), "JPEG 2000"},
      {Jp2Header(12000, 12000), "JPEG 2000"},
      {ExrHeader(12000, 12000), "OpenEXR"},
      {"P7\nWIDTH 12000\nHEIGHT 12000\nDEPTH 3\nMAXVAL 255\nTUPLTYPE RGB\nENDHDR\n", "PAM"},
      {"PF\n12000 12000\n-1.0\n", "PFM"}};
  for (const auto& [bytes, format] : cases) {
    SCOPED_TRACE(format);
    EXPECT_LT(bytes.size(), 200u);
    const auto header = ParseImageHeader(bytes);
    ASSERT_TRUE(header.has_value());
    EXPECT_EQ(header->format, format);
    EXPECT_EQ(header->width, 12000);
    EXPECT_EQ(header->height, 12000);
  }
  // Width and height apart, and the other orders of Radiance's resolution line.
  const auto wide = ParseImageHeader(RadianceHeader("+X 300 -Y 20"));
  ASSERT_TRUE(wide.has_value());
  EXPECT_EQ(wide->width, 300);
  EXPECT_EQ(wide->height, 20);
  const auto vp8x = ParseImageHeader(WebpVp8xHeader(70000, 3));
  ASSERT_TRUE(vp8x.has_value());
  EXPECT_EQ(vp8x->width, 70000);
  EXPECT_EQ(vp8x->height, 3);
  // Broken ones give nothing (and are then refused before decoding).
  EXPECT_FALSE(ParseImageHeader(RadianceHeader("-Y 12000 -Y 12000")).has_value());
  EXPECT_FALSE(ParseImageHeader(RadianceHeader("-Y 12000 +X -5")).has_value());
  EXPECT_FALSE(ParseImageHeader("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n").has_value());
  EXPECT_FALSE(ParseImageHeader(WebpVp8lHeader(10, 10).substr(0, 22)).has_value());
  EXPECT_FALSE(ParseImageHeader("RIFF\x10\0\0\0WAVEfmt ").has_value());
  EXPECT_FALSE(ParseImageHeader(ExrHeader(10, 10).substr(0, 30)).has_value());
  EXPECT_FALSE(ParseImageHeader(J2kHeader(10, 10).substr(0, 12)).has_value());
  EXPECT_FALSE(ParseImageHeader("P7\nWIDTH 10\nENDHDR\n").has_value());
}

// The decoder goes by content, the frame filter by extension: a WebP named .png is refused from
// its header, with the size it declares, never decoded.
TEST(ImageHeader, TheBudgetHoldsWhateverTheFileIsNamed) {
  ScopedTempDir dir;
  const std::vector<std::pair<std::string, std::string>> files = {
      {"webp.png", WebpVp8lHeader(12000, 12000)},
      {"radiance.hdr", RadianceHeader("-Y 12000 +X 12000")},
      {"exr.tif", ExrHeader(12000, 12000)},
      {"j2k.jpg", J2kHeader(12000, 12000)}};
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    const std::string path = dir.File(name);
    WriteFileAtomically(path, bytes);
    try {
      LoadImage(path);
      FAIL() << "not refused";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
      EXPECT_NE(std::string(e.what()).find(path + ": 12000x12000 = 144000000 pixels exceeds"),
                std::string::npos)
          << e.what();
    }
    // Without a budget of its own (masks, depth maps) the header is read as well.
    EXPECT_THROW(ReadImageUnchanged(path, kDefaultMaxPixels), Error);
  }
}

// What no header reader knows is not handed to the decoder: one line saying so.
TEST(ImageHeader, ContentWithoutAReadableHeaderIsRefusedBeforeDecoding) {
  ScopedTempDir dir;
  for (const std::string& bytes : {std::string("GIF89a\x10\0\x10\0", 10), std::string(),
                                   RadianceHeader("-Y 10"), WebpVp8lHeader(10, 10).substr(0, 22)}) {
    const std::string path = dir.File("frame.png");
    WriteFileAtomically(path, bytes);
    try {
      ReadImageUnchanged(path);
      FAIL() << "not refused";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
      const std::string message = e.what();
      EXPECT_NE(message.find(path + ": cannot decode image"), std::string::npos) << message;
      EXPECT_NE(message.find("WebP, Radiance HDR"), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_THROW(CheckImageHeaderBudget(path, 0, kDefaultMaxPixels), Error);
  }
  // A real image of each new format still decodes.
  const std::string path = dir.File("real.png");
  WriteFileAtomically(path, Encode(".webp", cv::Mat(37, 53, CV_8UC3, cv::Scalar(1, 2, 3))));
  EXPECT_EQ(LoadImage(path).gray.size(), cv::Size(53, 37));
}

}  // namespace
}  // namespace comic::io
