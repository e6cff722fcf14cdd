#include "io/report/data_uri.h"

#include <cstring>
#include <opencv2/imgcodecs.hpp>

#include "io/core/error.h"

namespace comic::io {

std::string EncodeBase64(const uint8_t* data, size_t size) {
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((size + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const uint32_t v = (uint32_t{data[i]} << 16) | (uint32_t{data[i + 1]} << 8) | data[i + 2];
    text += kAlphabet[(v >> 18) & 63];
    text += kAlphabet[(v >> 12) & 63];
    text += kAlphabet[(v >> 6) & 63];
    text += kAlphabet[v & 63];
  }
  if (i < size) {
    const bool two = i + 1 < size;
    const uint32_t v = (uint32_t{data[i]} << 16) | (two ? uint32_t{data[i + 1]} << 8 : 0);
    text += kAlphabet[(v >> 18) & 63];
    text += kAlphabet[(v >> 12) & 63];
    text += two ? kAlphabet[(v >> 6) & 63] : '=';
    text += '=';
  }
  return text;
}

std::string EncodeBase64(const std::vector<uint8_t>& bytes) {
  return EncodeBase64(bytes.data(), bytes.size());
}

std::string Base64OfFloats(const std::vector<float>& values) {
  static_assert(sizeof(float) == 4, "IEEE 754 single precision");
  std::vector<uint8_t> bytes(values.size() * 4);
  for (size_t i = 0; i < values.size(); ++i) {
    uint32_t bits = 0;
    std::memcpy(&bits, &values[i], 4);
    for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<uint8_t>(bits >> (8 * b));
  }
  return EncodeBase64(bytes);
}

std::string ImageDataUri(const cv::Mat& image, int jpeg_quality) {
  COMIC_CHECK(!image.empty() && (image.type() == CV_8UC1 || image.type() == CV_8UC3),
              kInvalidArgument, "ImageDataUri: expected a non-empty 8-bit grey or BGR image");
  COMIC_CHECK(jpeg_quality >= 0 && jpeg_quality <= 100, kInvalidArgument,
              "ImageDataUri: jpeg_quality must be in 0..100 (0 = PNG), got " << jpeg_quality);
  std::vector<uint8_t> bytes;
  const bool png = jpeg_quality == 0;
  const std::vector<int> parameters =
      png ? std::vector<int>{cv::IMWRITE_PNG_COMPRESSION, 6}
          : std::vector<int>{cv::IMWRITE_JPEG_QUALITY, jpeg_quality};
  COMIC_CHECK(cv::imencode(png ? ".png" : ".jpg", image, bytes, parameters), kInvalidData,
              "ImageDataUri: the image could not be encoded");
  return std::string(png ? "data:image/png;base64," : "data:image/jpeg;base64,") +
         EncodeBase64(bytes);
}

}  // namespace comic::io
