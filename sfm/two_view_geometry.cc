#include "sfm/two_view_geometry.h"

#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "frontend/matching/usac_params.h"
#include "io/core/error.h"
#include "sfm/triangulation.h"

namespace comic::sfm {

void TwoViewGeometryOptions::Check() const {
  COMIC_CHECK(max_error_px > 0, kInvalidArgument, "two-view max_error_px must be > 0");
  COMIC_CHECK(confidence > 0 && confidence < 1, kInvalidArgument,
              "two-view confidence must be in (0, 1)");
  COMIC_CHECK(max_num_iterations > 0, kInvalidArgument, "two-view max_num_iterations must be > 0");
  COMIC_CHECK(min_num_inliers >= 5, kInvalidArgument, "two-view min_num_inliers must be >= 5");
  COMIC_CHECK(max_homography_inlier_ratio > 0, kInvalidArgument,
              "two-view max_homography_inlier_ratio must be > 0");
  COMIC_CHECK(random_seed <= 0x7fffffffu, kInvalidArgument, "two-view random_seed must be < 2^31");
}

const char* TwoViewConfigurationName(TwoViewConfiguration configuration) {
  switch (configuration) {
    case TwoViewConfiguration::kDegenerate:
      return "degenerate";
    case TwoViewConfiguration::kPlanarOrPanoramic:
      return "planar_or_panoramic";
    case TwoViewConfiguration::kCalibrated:
      return "calibrated";
  }
  return "unknown";
}

TwoViewGeometry EstimateCalibratedTwoViewGeometry(const Camera& camera1, const Camera& camera2,
                                                  const std::vector<Eigen::Vector2d>& points1,
                                                  const std::vector<Eigen::Vector2d>& points2,
                                                  const TwoViewGeometryOptions& options) {
  options.Check();
  COMIC_CHECK(points1.size() == points2.size(), kInvalidArgument,
              "two-view geometry: " << points1.size() << " vs " << points2.size() << " points");
  TwoViewGeometry geometry;
  geometry.inlier_mask.assign(points1.size(), 0);
  if (static_cast<int>(points1.size()) < options.min_num_inliers) return geometry;

  // Work in undistorted normalised coordinates so the two cameras may differ; thresholds scale by
  // the mean focal length.
  std::vector<cv::Point2d> normalized1, normalized2;
  normalized1.reserve(points1.size());
  normalized2.reserve(points2.size());
  for (size_t i = 0; i < points1.size(); ++i) {
    const Eigen::Vector2d n1 = camera1.CamFromImage(points1[i]);
    const Eigen::Vector2d n2 = camera2.CamFromImage(points2[i]);
    normalized1.emplace_back(n1.x(), n1.y());
    normalized2.emplace_back(n2.x(), n2.y());
  }
  const double mean_focal = (camera1.fx + camera1.fy + camera2.fx + camera2.fy) / 4.0;
  const double threshold = options.max_error_px / mean_focal;

  // RANSAC with MSAC scoring and inner local optimisation (frontend/matching/usac_params.h): the
  // model and its inlier mask come from a least-squares fit to the inliers rather than from a
  // minimal sample, whose noise would make the homography check and the initial pose needlessly
  // poor.
  const cv::UsacParams params = frontend::DeterministicUsacParams(
      threshold, options.confidence, options.max_num_iterations, options.random_seed);
  const cv::Mat unit_camera = cv::Mat::eye(3, 3, CV_64F);
  cv::Mat essential_mask;
  cv::Mat essential;
  try {
    essential = cv::findEssentialMat(normalized1, normalized2, unit_camera, unit_camera,
                                     cv::noArray(), cv::noArray(), essential_mask, params);
  } catch (const cv::Exception&) {
    return geometry;  // USAC throws when it finds no model at all
  }
  // Several solutions may come back stacked; the first is the best.
  if (essential.rows < 3 || essential.cols != 3 || essential_mask.empty()) return geometry;
  geometry.num_essential_inliers = cv::countNonZero(essential_mask);
  if (geometry.num_essential_inliers < options.min_num_inliers) return geometry;

  cv::Mat homography_mask;
  cv::Mat homography;
  try {
    homography = cv::findHomography(normalized1, normalized2, homography_mask, params);
  } catch (const cv::Exception&) {
    homography.release();
  }
  geometry.num_homography_inliers =
      homography.empty() || homography_mask.empty() ? 0 : cv::countNonZero(homography_mask);
  if (geometry.num_homography_inliers > 0 && homography.rows == 3 && homography.cols == 3) {
    cv::cv2eigen(homography, geometry.homography);
    if (!geometry.homography.allFinite()) geometry.homography.setZero();
  }

  cv::Mat rotation_cv, translation_cv;
  cv::Mat pose_mask = essential_mask.clone();
  cv::recoverPose(essential.rowRange(0, 3), normalized1, normalized2, rotation_cv, translation_cv,
                  1.0, cv::Point2d(0, 0), pose_mask);
  Eigen::Matrix3d rotation;
  Eigen::Vector3d translation;
  cv::cv2eigen(rotation_cv, rotation);
  cv::cv2eigen(translation_cv, translation);
  if (!rotation.allFinite() || !translation.allFinite() || translation.norm() < 1e-12) {
    return geometry;
  }
  geometry.cam2_from_cam1 = Rigid3d(rotation, translation.normalized());

  // Cheirality and angles from our own triangulation of every essential inlier.
  const Rigid3d identity;
  std::vector<double> angles;
  const Eigen::Vector3d center2 = ProjectionCenter(geometry.cam2_from_cam1);
  for (size_t i = 0; i < points1.size(); ++i) {
    if (!essential_mask.at<uchar>(static_cast<int>(i))) continue;
    const auto point = TriangulatePointDlt({identity, geometry.cam2_from_cam1},
                                           {Eigen::Vector2d(normalized1[i].x, normalized1[i].y),
                                            Eigen::Vector2d(normalized2[i].x, normalized2[i].y)});
    if (!point || point->z() <= 0 || (geometry.cam2_from_cam1 * *point).z() <= 0) continue;
    geometry.inlier_mask[i] = 1;
    geometry.points3D.push_back(*point);
    angles.push_back(TriangulationAngleDeg(Eigen::Vector3d::Zero(), center2, *point));
  }
  geometry.triangulation_angles_deg = angles;
  geometry.num_inliers = static_cast<int>(angles.size());
  if (!angles.empty()) {
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    geometry.median_triangulation_angle_deg = angles[angles.size() / 2];
  }
  if (geometry.num_inliers < options.min_num_inliers) return geometry;
  const double homography_ratio = static_cast<double>(geometry.num_homography_inliers) /
                                  static_cast<double>(geometry.num_essential_inliers);
  geometry.configuration = homography_ratio > options.max_homography_inlier_ratio
                               ? TwoViewConfiguration::kPlanarOrPanoramic
                               : TwoViewConfiguration::kCalibrated;
  return geometry;
}

}  // namespace comic::sfm
