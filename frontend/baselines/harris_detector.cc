#include "frontend/baselines/harris_detector.h"

#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {

void HarrisDetectorOptions::Check() const {
  COMIC_CHECK(derivative_sigma > 0, kInvalidArgument,
              "harris: derivative_sigma must be > 0, got " << derivative_sigma);
  COMIC_CHECK(integration_sigma > 0, kInvalidArgument,
              "harris: integration_sigma must be > 0, got " << integration_sigma);
  COMIC_CHECK(k > 0 && k < 0.25, kInvalidArgument, "harris: k must be in (0, 0.25), got " << k);
  COMIC_CHECK(nms_radius >= 1, kInvalidArgument, "harris: nms_radius must be >= 1");
  COMIC_CHECK(border >= 1, kInvalidArgument, "harris: border must be >= 1");
  COMIC_CHECK(min_response >= 0, kInvalidArgument, "harris: min_response must be >= 0");
}

HarrisDetector::HarrisDetector(const HarrisDetectorOptions& options) : options_(options) {
  options_.Check();
}

cv::Mat HarrisDetector::Cornerness(const cv::Mat& gray) const {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "harris: expected a non-empty 8-bit single-channel image");
  cv::Mat smooth;
  gray.convertTo(smooth, CV_32F);
  cv::GaussianBlur(smooth, smooth, cv::Size(), options_.derivative_sigma, options_.derivative_sigma,
                   cv::BORDER_REFLECT_101);
  // Central differences of the smoothed image: grey levels per pixel.
  cv::Mat ix, iy;
  const cv::Mat kernel_x = (cv::Mat_<float>(1, 3) << -0.5f, 0.0f, 0.5f);
  cv::filter2D(smooth, ix, CV_32F, kernel_x, cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::filter2D(smooth, iy, CV_32F, kernel_x.t(), cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::Mat ixx = ix.mul(ix), iyy = iy.mul(iy), ixy = ix.mul(iy);
  const double s = options_.integration_sigma;
  cv::GaussianBlur(ixx, ixx, cv::Size(), s, s, cv::BORDER_REFLECT_101);
  cv::GaussianBlur(iyy, iyy, cv::Size(), s, s, cv::BORDER_REFLECT_101);
  cv::GaussianBlur(ixy, ixy, cv::Size(), s, s, cv::BORDER_REFLECT_101);
  cv::Mat trace = ixx + iyy;
  cv::Mat r = ixx.mul(iyy) - ixy.mul(ixy) - static_cast<float>(options_.k) * trace.mul(trace);
  return r;
}

FeatureSet HarrisDetector::Detect(const cv::Mat& gray) const {
  const cv::Mat r = Cornerness(gray);
  ResponsePeakOptions peaks;
  peaks.nms_radius = options_.nms_radius;
  peaks.border = options_.border;
  peaks.min_value = static_cast<float>(options_.min_response);
  if (gray.rows <= 2 * options_.border || gray.cols <= 2 * options_.border) return {};
  return FindResponsePeaks(r, peaks, static_cast<float>(options_.integration_sigma));
}

}  // namespace comic::frontend
