// Binary data inside a text page: base64 (RFC 4648), typed arrays for JavaScript and images as
// data: URIs, so one HTML file carries its pictures and point clouds.
//
//   const std::string src = ImageDataUri(thumbnail);          // "data:image/jpeg;base64,..."
//   const std::string xyz = Base64OfFloats({0.f, 1.f, 2.f});  // a Float32Array's bytes
#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace comic::io {

// Standard base64 with padding.
std::string EncodeBase64(const uint8_t* data, size_t size);
std::string EncodeBase64(const std::vector<uint8_t>& bytes);

// The bytes of a Float32Array (IEEE 754, little-endian, as every browser's typed arrays on
// x86 and ARM) holding `values`, in base64.
std::string Base64OfFloats(const std::vector<float>& values);

// `image` (CV_8UC1 or CV_8UC3 BGR) as a JPEG data: URI at `jpeg_quality` (1..100), or as a
// lossless PNG one with jpeg_quality 0. Throws comic::Error(kInvalidArgument) for an empty image,
// another type or quality.
std::string ImageDataUri(const cv::Mat& image, int jpeg_quality = 85);

}  // namespace comic::io
