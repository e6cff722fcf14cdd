// Middlebury stereo pairs (Scharstein & Szeliski, IJCV 2002; CVPR 2003) with ground-truth
// disparity and evaluation masks, loaded at a working size.
//
//   auto pair = comic::io::LoadMiddleburyFolder("../shared/data/middlebury2003_cones", 700);
//   // left (x, y) corresponds to right (x - pair.disparity(y, x), y) where disparity > 0
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace comic::io {

struct MiddleburyPair {
  std::string name;     // folder or left-image name, for reports
  cv::Mat left_gray;    // CV_8UC1, working size
  cv::Mat right_gray;   // CV_8UC1, working size
  cv::Mat left_color;   // CV_8UC3 BGR
  cv::Mat right_color;  // CV_8UC3 BGR
  // Disparity of the LEFT image in pixels at the working size, CV_32F; 0 = unknown.
  cv::Mat disparity;
  // CV_8UC1 masks at the working size (empty if not given): nonocc 255 = non-occluded evaluated
  // pixel; disc 255 = near a depth discontinuity, 128 = other non-occluded pixel, 0 = excluded.
  cv::Mat nonocc;
  cv::Mat disc;
  double disparity_scale = 0.0;  // stored value / scale = disparity at the original size
  double resize_factor = 1.0;    // working width / original width (disparities scale by it)
  cv::Size original_size;

  // Largest known disparity at the working size (0 if none is known).
  double MaxDisparity() const;
};

struct MiddleburyPairPaths {
  std::string left;
  std::string right;
  std::string disparity;
  double disparity_scale = 0.0;  // required, > 0 (Tsukuba: 16, the 2003 quarter-size pairs: 4)
  std::string nonocc;            // optional
  std::string disc;              // optional
};

// Loads a pair and resizes everything to `resize_height` (0 = original size): images with
// io::ResizeToHeight, disparity and masks with exact nearest-neighbour (INTER_NEAREST_EXACT) to
// the same size, disparity values multiplied by the horizontal resize factor. Throws
// comic::Error naming the file: missing file (kNotFound), a scale <= 0 (kInvalidArgument), a
// right image, disparity map or mask whose size differs from the left image (kInvalidData).
MiddleburyPair LoadMiddleburyPair(const MiddleburyPairPaths& paths, int resize_height = 0);

// Loads a folder laid out like ../shared/data/middlebury2003_cones: im2.png/im6.png (2003 pairs,
// disparity scale 4) or im3.png/im4.png (Tsukuba, scale 16), groundtruth.png, nonocc.png and
// disc.png. `disparity_scale` > 0 overrides the scale implied by the file names.
MiddleburyPair LoadMiddleburyFolder(const std::string& folder, int resize_height = 0,
                                    double disparity_scale = 0.0);

}  // namespace comic::io
