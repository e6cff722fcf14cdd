#include "frontend/matching/descriptor_matcher.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

using FloatMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr int kDescriptorWidth = 128;
// Descriptors have length ≈ 512 (COLMAP's convention): dot / 512² is the cosine.
constexpr double kDotToCosine = 1.0 / (512.0 * 512.0);

void CheckDescriptors(const cv::Mat& descriptors, const char* which) {
  COMIC_CHECK(descriptors.empty() ||
                  (descriptors.type() == CV_8UC1 && descriptors.cols == kDescriptorWidth),
              kInvalidArgument,
              "descriptor matching: " << which << " must be CV_8UC1 with " << kDescriptorWidth
                                      << " columns");
}

FloatMatrix ToFloat(const cv::Mat& descriptors) {
  FloatMatrix result(descriptors.rows, kDescriptorWidth);
  for (int r = 0; r < descriptors.rows; ++r) {
    const uint8_t* row = descriptors.ptr<uint8_t>(r);
    for (int c = 0; c < kDescriptorWidth; ++c) result(r, c) = row[c];
  }
  return result;
}

double Angle(float dot) { return std::acos(std::min(1.0, dot * kDotToCosine)); }

// Per row of `dots` (or per column, `by_column`): the index of the accepted nearest neighbour, or
// −1 (distance and ratio tests as COLMAP's FindBestMatchesOneWayBruteForce). Entries of `dots`
// that are 0 are no candidates (COLMAP's guided matching zeroes the excluded ones).
std::vector<int> BestMatchesOneWay(const cv::Mat& dots, bool by_column,
                                   const DescriptorMatchOptions& options) {
  const int num = by_column ? dots.cols : dots.rows;
  const int num_other = by_column ? dots.rows : dots.cols;
  std::vector<float> best(num, 0.0f), second(num, 0.0f);
  std::vector<int> best_index(num, -1);
  if (!by_column) {
    for (int i = 0; i < num; ++i) {
      const float* row = dots.ptr<float>(i);
      for (int j = 0; j < num_other; ++j) {
        const float dot = row[j];
        if (dot > best[i]) {
          second[i] = best[i];
          best[i] = dot;
          best_index[i] = j;
        } else if (dot > second[i]) {
          second[i] = dot;
        }
      }
    }
  } else {
    // Walk the rows in memory order, keeping a running best per column.
    for (int r = 0; r < num_other; ++r) {
      const float* row = dots.ptr<float>(r);
      for (int j = 0; j < num; ++j) {
        const float dot = row[j];
        if (dot > best[j]) {
          second[j] = best[j];
          best[j] = dot;
          best_index[j] = r;
        } else if (dot > second[j]) {
          second[j] = dot;
        }
      }
    }
  }
  std::vector<int> result(num, -1);
  for (int i = 0; i < num; ++i) {
    if (best_index[i] < 0) continue;
    const double best_angle = Angle(best[i]);
    if (best_angle > options.max_distance) continue;
    // ">=" so that two equally near neighbours (best == second) are rejected.
    if (best_angle >= options.max_ratio * Angle(second[i])) continue;
    result[i] = best_index[i];
  }
  return result;
}

// Mutual accepted nearest neighbours of `dots` (see MatchDescriptors).
std::vector<PatchMatch> MatchDotProducts(const cv::Mat& dots,
                                         const DescriptorMatchOptions& options) {
  std::vector<PatchMatch> matches;
  if (dots.empty()) return matches;
  const std::vector<int> forward = BestMatchesOneWay(dots, false, options);
  std::vector<int> backward;
  if (options.cross_check) backward = BestMatchesOneWay(dots, true, options);
  for (int i = 0; i < static_cast<int>(forward.size()); ++i) {
    const int j = forward[i];
    if (j < 0) continue;
    if (options.cross_check && backward[j] != i) continue;
    matches.push_back({i, j, static_cast<float>(Angle(dots.at<float>(i, j)))});
  }
  return matches;
}

// The line x2ᵀ F x1 = 0 of each point, scaled so that its dot product with a point is the distance
// in pixels.
std::vector<cv::Vec3d> EpipolarLines(const FeatureSet& features, const cv::Matx33d& f) {
  std::vector<cv::Vec3d> lines;
  lines.reserve(features.size());
  for (const Feature& feature : features) {
    const cv::Vec3d line = f * cv::Vec3d(feature.x, feature.y, 1.0);
    const double norm = std::hypot(line[0], line[1]);
    lines.push_back(norm > 0 ? line / norm : cv::Vec3d(0, 0, 1e30));
  }
  return lines;
}

}  // namespace

void DescriptorMatchOptions::Check() const {
  COMIC_CHECK(max_distance > 0 && max_distance <= M_PI, kInvalidArgument,
              "descriptor matching: max_distance must be in (0, pi], got " << max_distance);
  COMIC_CHECK(max_ratio > 0 && max_ratio <= 1, kInvalidArgument,
              "descriptor matching: max_ratio must be in (0, 1], got " << max_ratio);
}

cv::Mat DescriptorDotProducts(const cv::Mat& descriptors1, const cv::Mat& descriptors2) {
  CheckDescriptors(descriptors1, "descriptors1");
  CheckDescriptors(descriptors2, "descriptors2");
  cv::Mat dots(descriptors1.rows, descriptors2.rows, CV_32F);
  if (dots.empty()) return dots;
  const FloatMatrix a = ToFloat(descriptors1);
  const FloatMatrix b = ToFloat(descriptors2);
  Eigen::Map<FloatMatrix> out(dots.ptr<float>(), dots.rows, dots.cols);
  out.noalias() = a * b.transpose();
  return dots;
}

std::vector<PatchMatch> MatchDescriptors(const cv::Mat& descriptors1, const cv::Mat& descriptors2,
                                         const DescriptorMatchOptions& options) {
  options.Check();
  return MatchDotProducts(DescriptorDotProducts(descriptors1, descriptors2), options);
}

std::vector<PatchMatch> MatchDescriptorsAlongEpipolarLines(
    const cv::Mat& descriptors1, const cv::Mat& descriptors2, const FeatureSet& features1,
    const FeatureSet& features2, const cv::Matx33d& fundamental, double max_error_px,
    const DescriptorMatchOptions& options) {
  options.Check();
  COMIC_CHECK(max_error_px > 0, kInvalidArgument,
              "guided matching: max_error_px must be > 0, got " << max_error_px);
  COMIC_CHECK(descriptors1.rows == static_cast<int>(features1.size()) &&
                  descriptors2.rows == static_cast<int>(features2.size()),
              kInvalidArgument, "guided matching: one descriptor per feature is needed");
  cv::Mat dots = DescriptorDotProducts(descriptors1, descriptors2);
  if (dots.empty()) return {};
  const std::vector<cv::Vec3d> lines_in_2 = EpipolarLines(features1, fundamental);
  const std::vector<cv::Vec3d> lines_in_1 = EpipolarLines(features2, fundamental.t());
  for (int i = 0; i < dots.rows; ++i) {
    float* row = dots.ptr<float>(i);
    const cv::Vec3d& line2 = lines_in_2[i];
    const Feature& f1 = features1[i];
    for (int j = 0; j < dots.cols; ++j) {
      const Feature& f2 = features2[j];
      const double d2 = std::abs(line2[0] * f2.x + line2[1] * f2.y + line2[2]);
      const cv::Vec3d& line1 = lines_in_1[j];
      const double d1 = std::abs(line1[0] * f1.x + line1[1] * f1.y + line1[2]);
      if (d1 > max_error_px || d2 > max_error_px) row[j] = 0.0f;
    }
  }
  return MatchDotProducts(dots, options);
}

}  // namespace comic::frontend
