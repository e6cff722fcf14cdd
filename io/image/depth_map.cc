#include "io/image/depth_map.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"

namespace comic::io {
namespace {

void WritePfm(const std::string& path, const cv::Mat& depth) {
  std::ofstream out(path, std::ios::binary);
  COMIC_CHECK(out.good(), kIo, path << ": cannot write");
  // "Pf": one channel; a negative scale says little-endian.
  out << "Pf\n" << depth.cols << " " << depth.rows << "\n-1.0\n";
  for (int y = depth.rows - 1; y >= 0; --y) {
    out.write(reinterpret_cast<const char*>(depth.ptr<float>(y)),
              static_cast<std::streamsize>(depth.cols * sizeof(float)));
  }
  COMIC_CHECK(out.good(), kIo, path << ": write failed");
}

cv::Mat ReadPfm(const std::string& path) {
  const std::string bytes = ReadFileToString(path);
  std::istringstream header(bytes);
  std::string magic;
  int width = 0;
  int height = 0;
  double scale = 0.0;
  header >> magic >> width >> height >> scale;
  COMIC_CHECK(header && magic == "Pf" && width > 0 && height > 0 && scale != 0.0, kInvalidData,
              path << ": not a one-channel PFM depth map");
  COMIC_CHECK(scale < 0, kInvalidData, path << ": big-endian PFM is not supported");
  const size_t start = static_cast<size_t>(header.tellg()) + 1;  // one whitespace byte
  const size_t row_bytes = static_cast<size_t>(width) * sizeof(float);
  COMIC_CHECK(bytes.size() == start + row_bytes * height, kInvalidData,
              path << ": PFM data is " << bytes.size() - start << " bytes, expected "
                   << row_bytes * height);
  cv::Mat depth(height, width, CV_32F);
  for (int y = 0; y < height; ++y) {
    std::memcpy(depth.ptr<float>(height - 1 - y), bytes.data() + start + y * row_bytes, row_bytes);
  }
  return depth;
}

}  // namespace

void WriteDepthMap(const std::string& path, const cv::Mat& depth) {
  COMIC_CHECK(depth.type() == CV_32FC1, kInvalidArgument,
              path << ": a depth map must be one-channel float");
  const std::string extension = FileExtension(path);
  if (extension == "pfm") {
    WriteAtomically(path, [&](const std::string& temp) { WritePfm(temp, depth); });
    return;
  }
  COMIC_CHECK(extension == "png", kInvalidArgument,
              path << ": depth maps are written as .png (16-bit mm) or .pfm (float metres)");
  cv::Mat millimetres(depth.size(), CV_16UC1);
  for (int y = 0; y < depth.rows; ++y) {
    const float* in = depth.ptr<float>(y);
    uint16_t* out = millimetres.ptr<uint16_t>(y);
    for (int x = 0; x < depth.cols; ++x) {
      const double mm = std::round(static_cast<double>(in[x]) * 1000.0);
      out[x] = !(mm > 0) ? 0 : static_cast<uint16_t>(std::min(mm, 65535.0));
    }
  }
  WriteImageAtomically(path, millimetres);
}

cv::Mat ReadDepthMap(const std::string& path) {
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such depth map");
  if (FileExtension(path) == "pfm") return ReadPfm(path);
  const cv::Mat raw = ReadImageUnchanged(path);
  COMIC_CHECK(raw.type() == CV_16UC1, kInvalidData,
              path << ": a depth PNG must be 16-bit grey (millimetres)");
  cv::Mat depth(raw.size(), CV_32F);
  for (int y = 0; y < raw.rows; ++y) {
    const uint16_t* in = raw.ptr<uint16_t>(y);
    float* out = depth.ptr<float>(y);
    for (int x = 0; x < raw.cols; ++x) {
      out[x] = in[x] == 65535 ? std::numeric_limits<float>::infinity()
                              : static_cast<float>(in[x] / 1000.0);
    }
  }
  return depth;
}

}  // namespace comic::io
