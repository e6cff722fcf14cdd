// Per-pixel depth maps as files, in the two forms rendered truth is stored in:
//   .png  16-bit grey, millimetres (value = round(1000 z)); 0 = no surface; 65535 = at least
//         65.535 m (saturated) — compact, what ICL-NUIM/TUM-style tools read
//   .pfm  Portable Float Map (one channel, little-endian, bottom row first): metres, exact to
//         float precision; 0 = no surface, NaN = unknown (a composited object's depth)
// Depth is z, the distance along the optical axis, not along the ray. A PNG stores NaN as 0.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace comic::io {

// The largest depth a 16-bit PNG holds (metres); farther surfaces are stored as 65535.
constexpr double kMaxPngDepthMetres = 65.535;

// Writes `depth` (CV_32F, metres) atomically; the format follows the extension (png or pfm).
// Throws comic::Error: kInvalidArgument for another type or extension, kIo when writing fails.
void WriteDepthMap(const std::string& path, const cv::Mat& depth);

// Reads a depth map written as above into CV_32F metres (PNG: 65535 becomes +infinity, "at least
// 65.535 m"). Throws comic::Error: kNotFound, kInvalidData naming the file for a PNG that is not
// 16-bit grey or a malformed PFM.
cv::Mat ReadDepthMap(const std::string& path);

}  // namespace comic::io
