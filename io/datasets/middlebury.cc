#include "io/datasets/middlebury.h"

#include <opencv2/imgproc.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"

namespace comic::io {
namespace {

// Reads a single-channel 8-bit map (palette PNGs with grey palettes included) at original size.
cv::Mat ReadGreyMap(const std::string& path, const cv::Size& expected_size, const char* what) {
  const cv::Mat raw = ReadImageUnchanged(path);
  COMIC_CHECK(raw.depth() == CV_8U, kInvalidData,
              path << ": " << what << " must be an 8-bit image");
  const cv::Mat grey = ToGray8(raw);
  COMIC_CHECK(grey.size() == expected_size, kInvalidData,
              path << ": " << what << " is " << grey.cols << "x" << grey.rows
                   << " but the left image is " << expected_size.width << "x"
                   << expected_size.height);
  return grey;
}

cv::Mat ResizeNearest(const cv::Mat& map, const cv::Size& size) {
  if (map.empty() || map.size() == size) return map.clone();
  cv::Mat out;
  cv::resize(map, out, size, 0, 0, cv::INTER_NEAREST_EXACT);
  return out;
}

}  // namespace

double MiddleburyPair::MaxDisparity() const {
  if (disparity.empty()) return 0.0;
  double max_value = 0.0;
  cv::minMaxLoc(disparity, nullptr, &max_value);
  return max_value;
}

MiddleburyPair LoadMiddleburyPair(const MiddleburyPairPaths& paths, int resize_height) {
  COMIC_CHECK(paths.disparity_scale > 0, kInvalidArgument,
              "disparity scale must be > 0 (Tsukuba: 16, 2003 quarter-size pairs: 4), got "
                  << paths.disparity_scale);
  COMIC_CHECK(resize_height >= 0, kInvalidArgument, "resize height must be >= 0");
  const cv::Mat left_raw = ReadImageUnchanged(paths.left);
  const cv::Mat right_raw = ReadImageUnchanged(paths.right);
  COMIC_CHECK(left_raw.size() == right_raw.size(), kInvalidData,
              paths.right << ": right image is " << right_raw.cols << "x" << right_raw.rows
                          << " but the left image is " << left_raw.cols << "x" << left_raw.rows);
  const cv::Size original_size = left_raw.size();
  const cv::Mat stored = ReadGreyMap(paths.disparity, original_size, "disparity map");

  MiddleburyPair pair;
  pair.name = FileName(ParentPath(paths.left).empty() ? paths.left : ParentPath(paths.left));
  pair.original_size = original_size;
  pair.disparity_scale = paths.disparity_scale;
  try {
    pair.left_gray = ResizeToHeight(ToGray8(left_raw), resize_height);
    pair.left_color = ResizeToHeight(ToBgr8(left_raw), resize_height);
    pair.right_gray = ResizeToHeight(ToGray8(right_raw), resize_height);
    pair.right_color = ResizeToHeight(ToBgr8(right_raw), resize_height);
  } catch (const Error& e) {
    throw Error(e.kind(), paths.left + ": " + e.what());
  }
  const cv::Size working = pair.left_gray.size();
  pair.resize_factor = static_cast<double>(working.width) / original_size.width;

  // Disparity in pixels at the original size, then nearest-neighbour resized and scaled: a
  // horizontal offset between pixel centres scales exactly by the horizontal resize factor.
  cv::Mat disparity;
  stored.convertTo(disparity, CV_32F, 1.0 / paths.disparity_scale);
  pair.disparity = ResizeNearest(disparity, working);
  pair.disparity *= pair.resize_factor;

  if (!paths.nonocc.empty()) {
    pair.nonocc = ResizeNearest(ReadGreyMap(paths.nonocc, original_size, "nonocc mask"), working);
  }
  if (!paths.disc.empty()) {
    pair.disc = ResizeNearest(ReadGreyMap(paths.disc, original_size, "disc mask"), working);
  }
  return pair;
}

MiddleburyPair LoadMiddleburyFolder(const std::string& folder, int resize_height,
                                    double disparity_scale) {
  COMIC_CHECK(PathExists(folder), kNotFound, folder << ": no such folder");
  COMIC_CHECK(IsDirectory(folder), kInvalidArgument, folder << ": not a folder");
  MiddleburyPairPaths paths;
  if (PathExists(JoinPaths(folder, "im2.png")) && PathExists(JoinPaths(folder, "im6.png"))) {
    paths.left = JoinPaths(folder, "im2.png");  // Middlebury 2003: views 2 and 6, disparity x4
    paths.right = JoinPaths(folder, "im6.png");
    paths.disparity_scale = 4.0;
  } else if (PathExists(JoinPaths(folder, "im3.png")) && PathExists(JoinPaths(folder, "im4.png"))) {
    paths.left = JoinPaths(folder, "im3.png");  // Tsukuba: views 3 and 4, disparity x16
    paths.right = JoinPaths(folder, "im4.png");
    paths.disparity_scale = 16.0;
  } else {
    throw Error(ErrorKind::kNotFound,
                folder +
                    ": no Middlebury pair found (expected im2.png + im6.png or im3.png + "
                    "im4.png)");
  }
  if (disparity_scale > 0) paths.disparity_scale = disparity_scale;
  paths.disparity = JoinPaths(folder, "groundtruth.png");
  paths.nonocc = JoinPaths(folder, "nonocc.png");
  paths.disc = JoinPaths(folder, "disc.png");
  for (const std::string* path : {&paths.disparity, &paths.nonocc, &paths.disc}) {
    COMIC_CHECK(PathExists(*path), kNotFound, *path << ": no such file");
  }
  MiddleburyPair pair = LoadMiddleburyPair(paths, resize_height);
  pair.name = FileName(folder);
  return pair;
}

}  // namespace comic::io
