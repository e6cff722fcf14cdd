#include "sfm/absolute_pose.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "io/core/error.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

void AbsolutePoseOptions::Check() const {
  COMIC_CHECK(max_error_px > 0, kInvalidArgument, "absolute pose max_error_px must be > 0");
  COMIC_CHECK(confidence > 0 && confidence < 1, kInvalidArgument,
              "absolute pose confidence must be in (0, 1)");
  COMIC_CHECK(max_num_iterations > 0, kInvalidArgument,
              "absolute pose max_num_iterations must be > 0");
  COMIC_CHECK(min_num_inliers >= 4, kInvalidArgument, "absolute pose min_num_inliers must be >= 4");
  COMIC_CHECK(min_inlier_ratio >= 0 && min_inlier_ratio <= 1, kInvalidArgument,
              "absolute pose min_inlier_ratio must be in [0, 1]");
}

namespace {

Rigid3d PoseFromRodrigues(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat rotation_cv;
  cv::Rodrigues(rvec, rotation_cv);
  Eigen::Matrix3d rotation;
  Eigen::Vector3d translation;
  cv::cv2eigen(rotation_cv, rotation);
  cv::cv2eigen(tvec, translation);
  return Rigid3d(rotation, translation);
}

// Marks correspondences reprojecting within `max_error` in front of the camera.
int CountInliers(const Camera& camera, const Rigid3d& cam_from_world,
                 const std::vector<Eigen::Vector2d>& points2D,
                 const std::vector<Eigen::Vector3d>& points3D, double max_error,
                 std::vector<char>* mask) {
  mask->assign(points2D.size(), 0);
  int count = 0;
  for (size_t i = 0; i < points2D.size(); ++i) {
    const auto projection = ProjectPoint(camera, cam_from_world, points3D[i]);
    if (projection && (*projection - points2D[i]).norm() <= max_error) {
      (*mask)[i] = 1;
      ++count;
    }
  }
  return count;
}

}  // namespace

std::optional<AbsolutePose> EstimateAbsolutePose(const Camera& camera,
                                                 const std::vector<Eigen::Vector2d>& points2D,
                                                 const std::vector<Eigen::Vector3d>& points3D,
                                                 const AbsolutePoseOptions& options,
                                                 int* num_inliers_found) {
  options.Check();
  if (num_inliers_found) *num_inliers_found = 0;
  COMIC_CHECK(
      points2D.size() == points3D.size(), kInvalidArgument,
      "absolute pose: " << points2D.size() << " pixels for " << points3D.size() << " points");
  if (static_cast<int>(points2D.size()) < options.min_num_inliers) return std::nullopt;

  std::vector<cv::Point3d> object_points;
  std::vector<cv::Point2d> image_points;
  for (size_t i = 0; i < points2D.size(); ++i) {
    object_points.emplace_back(points3D[i].x(), points3D[i].y(), points3D[i].z());
    // PnP sees the pixels an ideal pinhole camera with this K would: the distortion is removed
    // first, and inliers are counted on the original pixels through the full model.
    const Eigen::Vector2d undistorted = camera.UndistortPixel(points2D[i]);
    image_points.emplace_back(undistorted.x(), undistorted.y());
  }
  cv::Mat k;
  cv::eigen2cv(camera.K(), k);
  cv::Mat rvec, tvec;
  std::vector<int> ransac_inliers;
  const bool found =
      cv::solvePnPRansac(object_points, image_points, k, cv::noArray(), rvec, tvec, false,
                         options.max_num_iterations, static_cast<float>(options.max_error_px),
                         options.confidence, ransac_inliers, cv::SOLVEPNP_AP3P);
  if (num_inliers_found && found) *num_inliers_found = static_cast<int>(ransac_inliers.size());
  if (!found || static_cast<int>(ransac_inliers.size()) < options.min_num_inliers) {
    return std::nullopt;
  }

  // Refine on the RANSAC inliers, then re-select inliers with the refined pose and refine once
  // more, so the pose is a least-squares fit to the final inlier set.
  AbsolutePose result;
  std::vector<int> inliers = ransac_inliers;
  for (int round = 0; round < 2; ++round) {
    std::vector<cv::Point3d> inlier_object;
    std::vector<cv::Point2d> inlier_image;
    for (int i : inliers) {
      inlier_object.push_back(object_points[i]);
      inlier_image.push_back(image_points[i]);
    }
    if (static_cast<int>(inlier_object.size()) < options.min_num_inliers) return std::nullopt;
    cv::solvePnPRefineLM(inlier_object, inlier_image, k, cv::noArray(), rvec, tvec);
    result.cam_from_world = PoseFromRodrigues(rvec, tvec);
    result.num_inliers = CountInliers(camera, result.cam_from_world, points2D, points3D,
                                      options.max_error_px, &result.inlier_mask);
    if (num_inliers_found) *num_inliers_found = result.num_inliers;
    inliers.clear();
    for (size_t i = 0; i < result.inlier_mask.size(); ++i) {
      if (result.inlier_mask[i]) inliers.push_back(static_cast<int>(i));
    }
  }
  if (!result.cam_from_world.translation.allFinite() ||
      result.num_inliers < options.min_num_inliers ||
      result.num_inliers < options.min_inlier_ratio * static_cast<double>(points2D.size())) {
    return std::nullopt;
  }
  return result;
}

}  // namespace comic::sfm
