#include "frontend/description/sift_descriptor.h"

#include <algorithm>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <vector>

#include "io/core/error.h"

namespace comic::frontend {

const char* DescriptorNormalizationName(DescriptorNormalization normalization) {
  switch (normalization) {
    case DescriptorNormalization::kL1Root:
      return "l1-root";
    case DescriptorNormalization::kL2:
      return "l2";
  }
  return "unknown";
}

DescriptorNormalization ParseDescriptorNormalization(const std::string& name) {
  for (DescriptorNormalization n :
       {DescriptorNormalization::kL1Root, DescriptorNormalization::kL2}) {
    if (name == DescriptorNormalizationName(n)) return n;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "unknown descriptor normalization '" + name + "' (expected l1-root or l2)");
}

void DescriptorOptions::Check() const {
  COMIC_CHECK(std::isfinite(sigma_per_scale) && sigma_per_scale > 0, kInvalidArgument,
              "descriptor: sigma_per_scale must be > 0, got " << sigma_per_scale);
  COMIC_CHECK(std::isfinite(curve_sigma_per_scale) && curve_sigma_per_scale > 0, kInvalidArgument,
              "descriptor: curve_sigma_per_scale must be > 0, got " << curve_sigma_per_scale);
  COMIC_CHECK(std::isfinite(min_sigma) && min_sigma > 0, kInvalidArgument,
              "descriptor: min_sigma must be > 0, got " << min_sigma);
  COMIC_CHECK(std::isfinite(max_sigma) && max_sigma >= min_sigma && max_sigma <= 1000,
              kInvalidArgument,
              "descriptor: max_sigma must be in [min_sigma, 1000], got " << max_sigma);
  orientation.Check();
}

DescriptorOptions DescriptorOptionsFor(const std::string& detector_name) {
  DescriptorOptions options;
  // The first baseline of the name sets sigma_per_scale (CoMIC's features use the curve factor).
  size_t start = 0;
  while (start <= detector_name.size()) {
    const size_t end = std::min(detector_name.find('+', start), detector_name.size());
    const std::string part = detector_name.substr(start, end - start);
    if (part == "fast" || part == "mser") {
      options.sigma_per_scale = 1.0;
      break;
    }
    if (part == "harris" || part == "hessian") {
      options.sigma_per_scale = 1.5;
      break;
    }
    start = end + 1;
  }
  return options;
}

double DescriptorSigma(const Feature& feature, const DescriptorOptions& options) {
  const double factor =
      feature.curve.empty() ? options.sigma_per_scale : options.curve_sigma_per_scale;
  const double sigma = factor * static_cast<double>(feature.scale);
  // A feature without a scale (0, or not finite) is described at the smallest σ.
  if (!std::isfinite(sigma) || sigma <= 0) return options.min_sigma;
  return std::clamp(sigma, options.min_sigma, options.max_sigma);
}

cv::Mat NormalizeSiftDescriptors(const cv::Mat& opencv_descriptors,
                                 DescriptorNormalization normalization) {
  COMIC_CHECK(opencv_descriptors.empty() || (opencv_descriptors.type() == CV_32FC1 &&
                                             opencv_descriptors.cols == kDescriptorSize),
              kInvalidArgument, "descriptor: expected CV_32F rows of " << kDescriptorSize);
  cv::Mat result(opencv_descriptors.rows, kDescriptorSize, CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < opencv_descriptors.rows; ++r) {
    const float* in = opencv_descriptors.ptr<float>(r);
    uint8_t* out = result.ptr<uint8_t>(r);
    double norm = 0.0;
    for (int c = 0; c < kDescriptorSize; ++c) {
      const double v = std::max(0.0f, in[c]);
      norm += normalization == DescriptorNormalization::kL1Root ? v : v * v;
    }
    if (normalization == DescriptorNormalization::kL2) norm = std::sqrt(norm);
    if (norm <= 0.0) continue;  // no gradient at all: a zero row matches nothing
    for (int c = 0; c < kDescriptorSize; ++c) {
      const double v = std::max(0.0f, in[c]) / norm;
      const double unit = normalization == DescriptorNormalization::kL1Root ? std::sqrt(v) : v;
      // COLMAP's FeatureDescriptorsToUnsignedByte: round(512 x), capped at 255.
      out[c] = static_cast<uint8_t>(std::min(255.0, std::round(512.0 * unit)));
    }
  }
  return result;
}

cv::Mat DescribeOrientedPoints(const cv::Mat& gray, const std::vector<OrientedPoint>& points,
                               DescriptorNormalization normalization) {
  COMIC_CHECK(gray.type() == CV_8UC1, kInvalidArgument,
              "descriptor: expected an 8-bit grey image (CV_8UC1)");
  if (points.empty()) return cv::Mat(0, kDescriptorSize, CV_8UC1);
  // cv::SIFT::compute describes a key point on the pyramid level its `octave` names, over a
  // window of 12 · size / 2 pixels: size = 2σ.
  std::vector<cv::KeyPoint> keypoints(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const OrientedPoint& point = points[i];
    COMIC_CHECK(std::isfinite(point.x) && std::isfinite(point.y) && std::isfinite(point.sigma) &&
                    point.sigma > 0 && std::isfinite(point.angle_deg),
                kInvalidArgument,
                "descriptor: point " << i << " has no finite position, σ > 0 "
                                     << "and angle");
    cv::KeyPoint& k = keypoints[i];
    k.pt = cv::Point2f(point.x, point.y);
    k.size = 2.0f * point.sigma;
    k.angle = point.angle_deg;
    k.octave = PackOpenCvOctave(NearestScaleLevel(point.sigma));
  }
  const cv::Ptr<cv::SIFT> sift =
      cv::SIFT::create(0, kSiftLevelsPerOctave, 0.04, 10.0, kSiftBaseSigma, CV_32F);
  cv::Mat descriptors;
  sift->compute(gray, keypoints, descriptors);
  COMIC_CHECK(descriptors.rows == static_cast<int>(points.size()), kInvalidArgument,
              "descriptor: OpenCV returned " << descriptors.rows << " descriptors for "
                                             << points.size() << " points");
  return NormalizeSiftDescriptors(descriptors, normalization);
}

cv::Mat DescribeFeatures(const cv::Mat& gray, const FeatureSet& features,
                         const DescriptorOptions& options) {
  options.Check();
  COMIC_CHECK(gray.type() == CV_8UC1, kInvalidArgument,
              "descriptor: expected an 8-bit grey image (CV_8UC1)");
  if (features.empty()) return cv::Mat(0, kDescriptorSize, CV_8UC1);
  std::vector<double> sigmas(features.size());
  for (size_t i = 0; i < features.size(); ++i) sigmas[i] = DescriptorSigma(features[i], options);
  ScaleLevelImages images(gray);
  const std::vector<float> angles =
      ComputeOrientations(features, sigmas, options.orientation, &images);
  std::vector<OrientedPoint> points(features.size());
  for (size_t i = 0; i < features.size(); ++i) {
    points[i] = {features[i].x, features[i].y, static_cast<float>(sigmas[i]), angles[i]};
  }
  return DescribeOrientedPoints(gray, points, options.normalization);
}

}  // namespace comic::frontend
