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
// −1 (distance and ratio tests as COLMAP's FindBestMatchesOneWayBruteForce).
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
  const cv::Mat dots = DescriptorDotProducts(descriptors1, descriptors2);
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

}  // namespace comic::frontend
