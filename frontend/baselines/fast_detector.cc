#include "frontend/baselines/fast_detector.h"

#include <algorithm>
#include <opencv2/features2d.hpp>

#include "frontend/baselines/response_peaks.h"
#include "io/core/error.h"

namespace comic::frontend {

void FastDetectorOptions::Check() const {
  COMIC_CHECK(min_threshold >= 1 && min_threshold <= 254, kInvalidArgument,
              "fast: min_threshold must be in [1, 254] grey levels, got " << min_threshold);
}

FastDetector::FastDetector(const FastDetectorOptions& options) : options_(options) {
  options_.Check();
}

namespace {

// The 16 pixels of the Bresenham circle of radius 3, in order around the circle.
constexpr int kCircle[16][2] = {{0, -3}, {1, -3},  {2, -2},  {3, -1}, {3, 0},  {3, 1},
                                {2, 2},  {1, 3},   {0, 3},   {-1, 3}, {-2, 2}, {-3, 1},
                                {-3, 0}, {-3, -1}, {-2, -2}, {-1, -3}};

// FAST-9 score: the largest threshold t at which (x, y) is still a corner, i.e. some 9
// contiguous circle pixels are all brighter than I + t or all darker than I − t. cv::FAST
// computes it only inside its own non-maximum suppression, so it is recomputed here.
int Fast9Score(const cv::Mat& gray, int x, int y) {
  const int centre = gray.at<uint8_t>(y, x);
  int diff[16];
  for (int i = 0; i < 16; ++i) {
    diff[i] = gray.at<uint8_t>(y + kCircle[i][1], x + kCircle[i][0]) - centre;
  }
  int best = 0;
  for (int start = 0; start < 16; ++start) {
    int brighter = 255;  // min over the arc of (I_x − I)
    int darker = 255;    // min over the arc of (I − I_x)
    for (int k = 0; k < 9; ++k) {
      const int d = diff[(start + k) % 16];
      brighter = std::min(brighter, d);
      darker = std::min(darker, -d);
    }
    best = std::max(best, std::max(brighter, darker) - 1);  // strict inequality: I_x > I + t
  }
  return best;
}

}  // namespace

FeatureSet FastDetector::Detect(const cv::Mat& gray) const {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "fast: expected a non-empty 8-bit single-channel image");
  std::vector<cv::KeyPoint> keypoints;
  cv::FAST(gray, keypoints, options_.min_threshold, /*nonmaxSuppression=*/false,
           cv::FastFeatureDetector::TYPE_9_16);
  // cv::FAST never fires within 3 pixels of the border, so the circle is always inside.
  std::vector<int> scores;
  scores.reserve(keypoints.size());
  for (const cv::KeyPoint& kp : keypoints) {
    scores.push_back(Fast9Score(gray, cvRound(kp.pt.x), cvRound(kp.pt.y)));
  }
  if (options_.nonmax_suppression) {
    cv::Mat score(gray.size(), CV_32FC1, cv::Scalar(0));
    for (size_t i = 0; i < keypoints.size(); ++i) {
      score.at<float>(cvRound(keypoints[i].pt.y), cvRound(keypoints[i].pt.x)) =
          static_cast<float>(scores[i]);
    }
    ResponsePeakOptions peaks;
    peaks.nms_radius = 1;
    peaks.border = 3;  // the Bresenham circle's radius: FAST never fires closer to the border
    peaks.subpixel = false;
    FeatureSet features = FindResponsePeaks(score, peaks, /*feature_scale=*/3.0f);
    return features;
  }
  FeatureSet features;
  features.reserve(keypoints.size());
  for (size_t i = 0; i < keypoints.size(); ++i) {
    Feature f;
    f.x = keypoints[i].pt.x;
    f.y = keypoints[i].pt.y;
    f.scale = 3.0f;
    f.response = static_cast<float>(scores[i]);
    features.push_back(std::move(f));
  }
  SortByResponse(&features);
  return features;
}

}  // namespace comic::frontend
