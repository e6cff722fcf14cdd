// Base64, typed arrays and images as data: URIs, the way report pages carry binary data.
#include "io/report/data_uri.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "io/core/error.h"

namespace comic::io {
namespace {

std::string Base64(const std::string& text) {
  return EncodeBase64(reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

// RFC 4648 §10's test vectors: every padding case.
TEST(EncodeBase64, MatchesTheRfcVectors) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(EncodeBase64(std::vector<uint8_t>{0xff, 0xfe, 0x00}), "//4A");
}

// A Float32Array of [1, -2] is the bytes 00 00 80 3f 00 00 00 c0 (little-endian IEEE 754).
TEST(Base64OfFloats, IsLittleEndianIeee754) {
  EXPECT_EQ(Base64OfFloats({1.0f, -2.0f}),
            EncodeBase64(std::vector<uint8_t>{0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0xc0}));
  EXPECT_EQ(Base64OfFloats({}), "");
}

std::vector<uint8_t> Decode64(const std::string& text) {
  static const std::string alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<uint8_t> bytes;
  uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    if (c == '=') break;
    bits = (bits << 6) | static_cast<uint32_t>(alphabet.find(c));
    count += 6;
    if (count >= 8) {
      count -= 8;
      bytes.push_back(static_cast<uint8_t>(bits >> count));
    }
  }
  return bytes;
}

TEST(ImageDataUri, PngIsLosslessAndJpegDecodesToTheSameSize) {
  cv::Mat image(20, 30, CV_8UC3);
  cv::randu(image, 0, 255);
  const std::string png = ImageDataUri(image, 0);
  const std::string prefix = "data:image/png;base64,";
  ASSERT_EQ(png.rfind(prefix, 0), 0u);
  const cv::Mat back = cv::imdecode(Decode64(png.substr(prefix.size())), cv::IMREAD_COLOR);
  ASSERT_EQ(back.size(), image.size());
  EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0);

  const std::string jpeg = ImageDataUri(image, 80);
  const std::string jpeg_prefix = "data:image/jpeg;base64,";
  ASSERT_EQ(jpeg.rfind(jpeg_prefix, 0), 0u);
  const cv::Mat decoded = cv::imdecode(Decode64(jpeg.substr(jpeg_prefix.size())), cv::IMREAD_COLOR);
  EXPECT_EQ(decoded.size(), image.size());
  EXPECT_EQ(ImageDataUri(image, 80), jpeg);  // deterministic
}

TEST(ImageDataUri, RefusesWhatItCannotEncode) {
  EXPECT_THROW(ImageDataUri(cv::Mat()), Error);
  EXPECT_THROW(ImageDataUri(cv::Mat(4, 4, CV_32FC1, cv::Scalar(0))), Error);
  EXPECT_THROW(ImageDataUri(cv::Mat(4, 4, CV_8UC3, cv::Scalar(0)), 101), Error);
  EXPECT_THROW(ImageDataUri(cv::Mat(4, 4, CV_8UC3, cv::Scalar(0)), -1), Error);
}

}  // namespace
}  // namespace comic::io
