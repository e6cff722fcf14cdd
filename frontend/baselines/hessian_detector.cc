#include "frontend/baselines/hessian_detector.h"

#include <opencv2/imgproc.hpp>

#include "frontend/baselines/response_peaks.h"
#include "io/core/error.h"

namespace comic::frontend {

void HessianDetectorOptions::Check() const {
  COMIC_CHECK(sigma > 0, kInvalidArgument, "hessian: sigma must be > 0, got " << sigma);
  COMIC_CHECK(nms_radius >= 1, kInvalidArgument, "hessian: nms_radius must be >= 1");
  COMIC_CHECK(border >= 1, kInvalidArgument, "hessian: border must be >= 1");
  COMIC_CHECK(min_response >= 0, kInvalidArgument, "hessian: min_response must be >= 0");
}

HessianDetector::HessianDetector(const HessianDetectorOptions& options) : options_(options) {
  options_.Check();
}

cv::Mat HessianDetector::DeterminantOfHessian(const cv::Mat& gray) const {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "hessian: expected a non-empty 8-bit single-channel image");
  cv::Mat smooth;
  gray.convertTo(smooth, CV_32F);
  cv::GaussianBlur(smooth, smooth, cv::Size(), options_.sigma, options_.sigma,
                   cv::BORDER_REFLECT_101);
  // Second differences of the smoothed image (grey levels per pixel²).
  const cv::Mat d2 = (cv::Mat_<float>(1, 3) << 1.0f, -2.0f, 1.0f);
  const cv::Mat d1 = (cv::Mat_<float>(1, 3) << -0.5f, 0.0f, 0.5f);
  cv::Mat lxx, lyy, lxy;
  cv::filter2D(smooth, lxx, CV_32F, d2, cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::filter2D(smooth, lyy, CV_32F, d2.t(), cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::sepFilter2D(smooth, lxy, CV_32F, d1, d1, cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::Mat det = lxx.mul(lyy) - lxy.mul(lxy);
  return det;
}

FeatureSet HessianDetector::Detect(const cv::Mat& gray) const {
  const cv::Mat det = DeterminantOfHessian(gray);
  if (gray.rows <= 2 * options_.border || gray.cols <= 2 * options_.border) return {};
  ResponsePeakOptions peaks;
  peaks.nms_radius = options_.nms_radius;
  peaks.border = options_.border;
  peaks.min_value = static_cast<float>(options_.min_response);
  return FindResponsePeaks(det, peaks, static_cast<float>(options_.sigma));
}

}  // namespace comic::frontend
