#include "frontend/matching/match_verification.h"

#include <opencv2/calib3d.hpp>

#include "frontend/matching/usac_params.h"
#include "io/core/error.h"

namespace comic::frontend {

void MatchVerificationOptions::Check() const {
  COMIC_CHECK(max_error_px > 0, kInvalidArgument, "match verification: max_error_px must be > 0");
  COMIC_CHECK(min_num_inliers >= 8, kInvalidArgument,
              "match verification: min_num_inliers must be >= 8, got " << min_num_inliers);
  COMIC_CHECK(min_inlier_ratio >= 0 && min_inlier_ratio <= 1, kInvalidArgument,
              "match verification: min_inlier_ratio must be in [0, 1]");
  COMIC_CHECK(confidence > 0 && confidence < 1, kInvalidArgument,
              "match verification: confidence must be in (0, 1)");
  COMIC_CHECK(max_num_iterations > 0, kInvalidArgument,
              "match verification: max_num_iterations must be > 0");
  COMIC_CHECK(random_seed <= 0x7fffffffu, kInvalidArgument,
              "match verification: random_seed must be < 2^31");
}

std::vector<PatchMatch> VerifyMatches(const FeatureSet& features1, const FeatureSet& features2,
                                      const std::vector<PatchMatch>& matches,
                                      const MatchVerificationOptions& options,
                                      cv::Matx33d* fundamental_out) {
  options.Check();
  std::vector<cv::Point2f> points1, points2;
  points1.reserve(matches.size());
  points2.reserve(matches.size());
  for (const PatchMatch& m : matches) {
    COMIC_CHECK(m.index1 >= 0 && m.index1 < static_cast<int>(features1.size()) && m.index2 >= 0 &&
                    m.index2 < static_cast<int>(features2.size()),
                kInvalidArgument, "match verification: match index out of range");
    points1.push_back(features1[m.index1].Position());
    points2.push_back(features2[m.index2].Position());
  }
  std::vector<PatchMatch> kept;
  if (static_cast<int>(matches.size()) < options.min_num_inliers) return kept;

  const cv::UsacParams params = DeterministicUsacParams(
      options.max_error_px, options.confidence, options.max_num_iterations, options.random_seed);
  cv::Mat mask;
  cv::Mat fundamental;
  try {
    fundamental = cv::findFundamentalMat(points1, points2, mask, params);
  } catch (const cv::Exception&) {
    return kept;  // USAC throws when it finds no model at all
  }
  if (fundamental.empty() || mask.empty()) return kept;
  const int num_inliers = cv::countNonZero(mask);
  if (num_inliers < options.min_num_inliers ||
      num_inliers < options.min_inlier_ratio * static_cast<double>(matches.size())) {
    return kept;
  }
  if (fundamental_out != nullptr) {
    cv::Mat f64;
    fundamental.rowRange(0, 3).convertTo(f64, CV_64F);
    *fundamental_out = cv::Matx33d(f64.ptr<double>());
  }
  kept.reserve(num_inliers);
  for (size_t i = 0; i < matches.size(); ++i) {
    if (mask.at<uchar>(static_cast<int>(i))) kept.push_back(matches[i]);
  }
  return kept;
}

}  // namespace comic::frontend
