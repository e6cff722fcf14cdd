#include "sfm/planar_pose_ambiguity.h"

#include <algorithm>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "io/core/error.h"
#include "sfm/absolute_pose.h"
#include "sfm/rigid3d.h"
#include "sfm/triangulation.h"

namespace comic::sfm {

void PlanarAmbiguityOptions::Check() const {
  COMIC_CHECK(
      min_homography_share > 0 && min_homography_share <= 1, kInvalidArgument,
      "planar ambiguity min_homography_share must be in (0, 1], got " << min_homography_share);
  COMIC_CHECK(min_rotation_difference_deg >= 0, kInvalidArgument,
              "planar ambiguity min_rotation_difference_deg must be >= 0, got "
                  << min_rotation_difference_deg);
  COMIC_CHECK(min_inlier_share > 0 && min_inlier_share <= 1, kInvalidArgument,
              "planar ambiguity min_inlier_share must be in (0, 1], got " << min_inlier_share);
}

void ThirdViewOptions::Check() const {
  COMIC_CHECK(min_shared_points >= 6, kInvalidArgument,
              "third view min_shared_points must be >= 6, got " << min_shared_points);
  COMIC_CHECK(max_views >= 1, kInvalidArgument,
              "third view max_views must be >= 1, got " << max_views);
  COMIC_CHECK(max_error_px > 0, kInvalidArgument,
              "third view max_error_px must be > 0, got " << max_error_px);
  COMIC_CHECK(min_pooled_error_reduction >= 0 && min_pooled_error_reduction < 1, kInvalidArgument,
              "third view min_pooled_error_reduction must be in [0, 1), got "
                  << min_pooled_error_reduction);
  COMIC_CHECK(
      min_frame_error_reduction >= 0 && min_frame_error_reduction < 1, kInvalidArgument,
      "third view min_frame_error_reduction must be in [0, 1), got " << min_frame_error_reduction);
  COMIC_CHECK(min_votes >= 1, kInvalidArgument,
              "third view min_votes must be >= 1, got " << min_votes);
  COMIC_CHECK(min_vote_ratio >= 1, kInvalidArgument,
              "third view min_vote_ratio must be >= 1, got " << min_vote_ratio);
}

namespace {

// `geometry`'s pose replaced by `cam2_from_cam1`, its inliers those correspondences that
// triangulate in front of both cameras and reproject within `threshold` (normalised units) in
// both views.
TwoViewGeometry WithPose(const Rigid3d& cam2_from_cam1, const std::vector<Eigen::Vector2d>& n1,
                         const std::vector<Eigen::Vector2d>& n2, double threshold,
                         const TwoViewGeometry& geometry) {
  TwoViewGeometry other = geometry;
  other.cam2_from_cam1 = cam2_from_cam1;
  other.inlier_mask.assign(n1.size(), 0);
  other.points3D.clear();
  other.triangulation_angles_deg.clear();
  const Rigid3d identity;
  const Eigen::Vector3d center2 = ProjectionCenter(cam2_from_cam1);
  for (size_t i = 0; i < n1.size(); ++i) {
    const auto point = TriangulatePointDlt({identity, cam2_from_cam1}, {n1[i], n2[i]});
    if (!point || point->z() <= 0) continue;
    const Eigen::Vector3d in2 = cam2_from_cam1 * *point;
    if (in2.z() <= 0) continue;
    if ((point->hnormalized() - n1[i]).norm() > threshold ||
        (in2.hnormalized() - n2[i]).norm() > threshold) {
      continue;
    }
    other.inlier_mask[i] = 1;
    other.points3D.push_back(*point);
    other.triangulation_angles_deg.push_back(
        TriangulationAngleDeg(Eigen::Vector3d::Zero(), center2, *point));
  }
  other.num_inliers = static_cast<int>(other.points3D.size());
  other.median_triangulation_angle_deg = 0.0;
  if (!other.triangulation_angles_deg.empty()) {
    std::vector<double> angles = other.triangulation_angles_deg;
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    other.median_triangulation_angle_deg = angles[angles.size() / 2];
  }
  return other;
}

}  // namespace

std::optional<TwoViewGeometry> OtherPlanarPose(const Camera& camera1, const Camera& camera2,
                                               const std::vector<Eigen::Vector2d>& points1,
                                               const std::vector<Eigen::Vector2d>& points2,
                                               const TwoViewGeometry& geometry, double max_error_px,
                                               const PlanarAmbiguityOptions& options) {
  options.Check();
  COMIC_CHECK(points1.size() == points2.size() && points1.size() == geometry.inlier_mask.size(),
              kInvalidArgument, "planar ambiguity: inconsistent correspondences");
  if (geometry.configuration == TwoViewConfiguration::kDegenerate || geometry.homography.isZero() ||
      geometry.num_essential_inliers <= 0) {
    return std::nullopt;
  }
  const double homography_share = static_cast<double>(geometry.num_homography_inliers) /
                                  static_cast<double>(geometry.num_essential_inliers);
  if (homography_share < options.min_homography_share) return std::nullopt;

  std::vector<Eigen::Vector2d> n1, n2;
  for (size_t i = 0; i < points1.size(); ++i) {
    n1.push_back(camera1.CamFromImage(points1[i]));
    n2.push_back(camera2.CamFromImage(points2[i]));
  }
  const double mean_focal = (camera1.fx + camera1.fy + camera2.fx + camera2.fy) / 4.0;
  const double threshold = max_error_px / mean_focal;

  // Up to four decompositions (R, t/d, n); the two with t and n flipped put the points behind a
  // camera and keep no inliers below.
  cv::Mat homography_cv;
  cv::eigen2cv(geometry.homography, homography_cv);
  std::vector<cv::Mat> rotations, translations, normals;
  cv::decomposeHomographyMat(homography_cv, cv::Mat::eye(3, 3, CV_64F), rotations, translations,
                             normals);
  // The two physically valid solutions keep (nearly) every point in front of both cameras; the
  // other two, t and n flipped, keep few. Of the two, the one nearer the essential matrix's pose
  // is that pose again; the other is the alternative.
  struct Solution {
    TwoViewGeometry geometry;
    double difference_deg = 0.0;  // rotation from the essential matrix's pose
  };
  std::vector<Solution> solutions;
  for (size_t s = 0; s < rotations.size(); ++s) {
    Eigen::Matrix3d rotation;
    Eigen::Vector3d translation;
    cv::cv2eigen(rotations[s], rotation);
    cv::cv2eigen(translations[s], translation);
    if (!rotation.allFinite() || !translation.allFinite() || translation.norm() < 1e-12) continue;
    const Rigid3d pose(Eigen::Quaterniond(rotation).normalized(), translation.normalized());
    solutions.push_back({WithPose(pose, n1, n2, threshold, geometry),
                         RotationAngleDeg(pose.rotation, geometry.cam2_from_cam1.rotation)});
  }
  // Most inliers first; ties (exact data) by the order OpenCV returned them.
  std::stable_sort(solutions.begin(), solutions.end(), [](const Solution& a, const Solution& b) {
    return a.geometry.num_inliers > b.geometry.num_inliers;
  });
  if (solutions.size() < 2) return std::nullopt;
  Solution& other =
      solutions[0].difference_deg >= solutions[1].difference_deg ? solutions[0] : solutions[1];
  if (other.difference_deg < options.min_rotation_difference_deg ||
      other.geometry.num_inliers < options.min_inlier_share * geometry.num_inliers) {
    return std::nullopt;
  }
  std::optional<TwoViewGeometry> best = std::move(other.geometry);
  return best;
}

namespace {

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Each inlier's 3-D point by correspondence index (nullptr for an outlier).
std::vector<const Eigen::Vector3d*> PointsByCorrespondence(const TwoViewGeometry& geometry) {
  std::vector<const Eigen::Vector3d*> points(geometry.inlier_mask.size(), nullptr);
  size_t next = 0;
  for (size_t i = 0; i < geometry.inlier_mask.size() && next < geometry.points3D.size(); ++i) {
    if (geometry.inlier_mask[i]) points[i] = &geometry.points3D[next++];
  }
  return points;
}

}  // namespace

ThirdViewComparison CompareByThirdViews(const frontend::FeatureTracks& tracks, const Camera& camera,
                                        int frame1, int frame2, const std::vector<int>& track_ids,
                                        const TwoViewGeometry& first, const TwoViewGeometry& second,
                                        const ThirdViewOptions& options) {
  options.Check();
  COMIC_CHECK(
      first.inlier_mask.size() == track_ids.size() && second.inlier_mask.size() == track_ids.size(),
      kInvalidArgument, "third view comparison: inconsistent correspondences");
  ThirdViewComparison result;
  const auto first_points = PointsByCorrespondence(first);
  const auto second_points = PointsByCorrespondence(second);
  std::vector<size_t> shared;  // correspondences both poses triangulated
  for (size_t i = 0; i < track_ids.size(); ++i) {
    if (first_points[i] && second_points[i]) shared.push_back(i);
  }
  result.num_points = static_cast<int>(shared.size());

  // The third frames: those seeing the most shared points.
  std::vector<int> seen_by_frame(tracks.NumFrames(), 0);
  for (size_t i : shared) {
    for (const auto& obs : tracks.tracks[track_ids[i]].observations) ++seen_by_frame[obs.frame];
  }
  std::vector<int> candidates;
  for (int f = 0; f < static_cast<int>(tracks.NumFrames()); ++f) {
    if (f != frame1 && f != frame2 && seen_by_frame[f] >= options.min_shared_points) {
      candidates.push_back(f);
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](int a, int b) { return seen_by_frame[a] > seen_by_frame[b]; });
  if (static_cast<int>(candidates.size()) > options.max_views) candidates.resize(options.max_views);
  std::sort(candidates.begin(), candidates.end());

  AbsolutePoseOptions pnp;
  pnp.max_error_px = options.max_error_px;
  pnp.min_num_inliers = 6;
  pnp.min_inlier_ratio = 0.0;
  std::vector<double> pooled_first, pooled_second;
  for (int frame : candidates) {
    std::vector<Eigen::Vector2d> pixels;
    std::vector<Eigen::Vector3d> in_first, in_second;
    for (size_t i : shared) {
      const int feature = tracks.tracks[track_ids[i]].FeatureInFrame(frame);
      if (feature < 0) continue;
      const frontend::Feature& seen = tracks.features[frame][feature];
      pixels.emplace_back(seen.x, seen.y);
      in_first.push_back(*first_points[i]);
      in_second.push_back(*second_points[i]);
    }
    const auto pose_first = EstimateAbsolutePose(camera, pixels, in_first, pnp);
    const auto pose_second = EstimateAbsolutePose(camera, pixels, in_second, pnp);
    result.frames.push_back(frame);
    const auto median_error = [&](const std::optional<AbsolutePose>& pose,
                                  const std::vector<Eigen::Vector3d>& points,
                                  std::vector<double>* pooled) {
      if (!pose) {
        pooled->insert(pooled->end(), points.size(), std::numeric_limits<double>::infinity());
        return -1.0;
      }
      std::vector<double> errors;
      for (size_t k = 0; k < points.size(); ++k) {
        const Eigen::Vector3d in_camera = pose->cam_from_world * points[k];
        if (in_camera.z() <= 0) {
          errors.push_back(1e9);
          continue;
        }
        errors.push_back((camera.ImageFromCam(in_camera.hnormalized()) - pixels[k]).norm());
      }
      pooled->insert(pooled->end(), errors.begin(), errors.end());
      return Median(errors);
    };
    result.frame_median_error_first_px.push_back(median_error(pose_first, in_first, &pooled_first));
    result.frame_median_error_second_px.push_back(
        median_error(pose_second, in_second, &pooled_second));
  }
  if (!result.frames.empty()) {
    result.median_error_first_px = Median(pooled_first);
    result.median_error_second_px = Median(pooled_second);
  }
  // A frame one pose cannot locate (error -1) votes for the other.
  const double keep = 1.0 - options.min_frame_error_reduction;
  for (size_t v = 0; v < result.frames.size(); ++v) {
    const double first_error = result.frame_median_error_first_px[v];
    const double second_error = result.frame_median_error_second_px[v];
    if (first_error < 0 && second_error < 0) continue;
    if (first_error < 0 || (second_error >= 0 && second_error < keep * first_error)) {
      ++result.votes_second;
    } else if (second_error < 0 || first_error < keep * second_error) {
      ++result.votes_first;
    }
  }
  const auto pooled_clear = [&](double error, double other_error) {
    return !result.frames.empty() &&
           error < (1.0 - options.min_pooled_error_reduction) * other_error;
  };
  const auto votes_clear = [&](int votes, int other_votes) {
    return votes >= options.min_votes && votes >= options.min_vote_ratio * other_votes;
  };
  const bool for_second =
      pooled_clear(result.median_error_second_px, result.median_error_first_px) ||
      votes_clear(result.votes_second, result.votes_first);
  const bool for_first =
      pooled_clear(result.median_error_first_px, result.median_error_second_px) ||
      votes_clear(result.votes_first, result.votes_second);
  result.prefers_second = for_second && !for_first;
  return result;
}

}  // namespace comic::sfm
