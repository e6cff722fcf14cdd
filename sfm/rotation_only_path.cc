#include "sfm/rotation_only_path.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <random>

#include "io/core/error.h"

namespace comic::sfm {

void RotationOnlyPathOptions::Check() const {
  COMIC_CHECK(
      min_num_inliers >= 2 && min_num_inliers <= 1000000, kInvalidArgument,
      "rotation path: min_num_inliers must be >= 2 and <= 1000000, got " << min_num_inliers);
  COMIC_CHECK(max_error_px > 0.0 && max_error_px <= 1000.0, kInvalidArgument,
              "rotation path: max_error_px must be > 0 and <= 1000, got " << max_error_px);
  COMIC_CHECK(num_trials >= 1 && num_trials <= 100000, kInvalidArgument,
              "rotation path: num_trials must be >= 1 and <= 100000, got " << num_trials);
}

namespace {

// The rotation R minimising Σ |b_i − R a_i|² (Kabsch), for unit rays a_i, b_i.
Eigen::Matrix3d FitRotation(const std::vector<Eigen::Vector3d>& a,
                            const std::vector<Eigen::Vector3d>& b, const std::vector<int>& use) {
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int i : use) covariance += b[i] * a[i].transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d sign = Eigen::Matrix3d::Identity();
  sign(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * sign * svd.matrixV().transpose();
}

}  // namespace

std::optional<RayRotation> EstimateRayRotation(const std::vector<Eigen::Vector3d>& a,
                                               const std::vector<Eigen::Vector3d>& b,
                                               double max_angle, int min_num_inliers,
                                               int num_trials, std::mt19937* random) {
  COMIC_CHECK(a.size() == b.size(), kInvalidArgument,
              "ray rotation: " << a.size() << " rays against " << b.size());
  if (static_cast<int>(a.size()) < min_num_inliers || a.size() < 2) return std::nullopt;
  const auto inliers_of = [&](const Eigen::Matrix3d& rotation) {
    std::vector<int> inliers;
    for (size_t i = 0; i < a.size(); ++i) {
      if ((rotation * a[i]).cross(b[i]).norm() < max_angle) inliers.push_back(static_cast<int>(i));
    }
    return inliers;
  };
  std::vector<int> best;
  std::uniform_int_distribution<int> pick(0, static_cast<int>(a.size()) - 1);
  for (int trial = 0; trial < num_trials; ++trial) {
    const int i = pick(*random), j = pick(*random);
    if (i == j || a[i].cross(a[j]).norm() < 1e-3) continue;
    std::vector<int> inliers = inliers_of(FitRotation(a, b, {i, j}));
    if (inliers.size() > best.size()) best = std::move(inliers);
  }
  if (static_cast<int>(best.size()) < min_num_inliers) return std::nullopt;
  // Refit on the inliers, and once more on the inliers of the refit.
  RayRotation result;
  result.rotation = FitRotation(a, b, best);
  best = inliers_of(result.rotation);
  if (static_cast<int>(best.size()) < min_num_inliers) return std::nullopt;
  result.rotation = FitRotation(a, b, best);
  double sum_squared = 0.0;
  for (int i : best) {
    const double angle = (result.rotation * a[i]).cross(b[i]).norm();
    sum_squared += angle * angle;
  }
  result.rms_angle = std::sqrt(sum_squared / best.size());
  result.inliers = std::move(best);
  return result;
}

RotationOnlyPath EstimateRotationOnlyPath(const frontend::FeatureTracks& tracks,
                                          const Camera& camera,
                                          const RotationOnlyPathOptions& options) {
  tracks.Check();
  camera.Check();
  options.Check();
  RotationOnlyPath path;
  const camera_t camera_id = path.reconstruction.AddCamera(camera);
  const size_t num_frames = tracks.NumFrames();
  for (size_t frame = 0; frame < num_frames; ++frame) {
    Image image;
    image.image_id = static_cast<image_t>(frame + 1);
    image.camera_id = camera_id;
    image.name = frame < tracks.frame_names.size() ? tracks.frame_names[frame]
                                                   : "frame_" + std::to_string(frame);
    path.reconstruction.AddImage(std::move(image));
  }
  if (num_frames == 0) return path;
  const Eigen::Matrix3d K_inverse = camera.K().inverse();
  const auto ray = [&](int frame, int feature) {
    const frontend::Feature& f = tracks.features[frame][feature];
    return (K_inverse * Eigen::Vector3d(f.x, f.y, 1.0)).normalized();
  };
  // Per frame, its feature -> track's feature in the next frame.
  std::vector<std::vector<std::pair<int, int>>> links(num_frames);
  for (const frontend::Track& track : tracks.tracks) {
    for (size_t k = 0; k + 1 < track.observations.size(); ++k) {
      const frontend::TrackObservation& obs = track.observations[k];
      const frontend::TrackObservation& next = track.observations[k + 1];
      if (next.frame == obs.frame + 1) links[obs.frame].emplace_back(obs.feature, next.feature);
    }
  }
  // An angular tolerance: max_error_px at the mean focal length.
  const double max_angle = options.max_error_px / (0.5 * (camera.fx + camera.fy));
  std::mt19937 random(1);
  Eigen::Matrix3d cam_from_world = Eigen::Matrix3d::Identity();
  path.reconstruction.image(1).cam_from_world = Rigid3d();
  path.reconstruction.RegisterImage(1);
  path.num_registered = 1;
  for (size_t frame = 0; frame + 1 < num_frames; ++frame) {
    std::vector<std::pair<int, int>> pairs = links[frame];
    std::sort(pairs.begin(), pairs.end());  // the tracks' order must not matter
    if (static_cast<int>(pairs.size()) < options.min_num_inliers) break;
    std::vector<Eigen::Vector3d> a, b;
    for (const auto& [feature1, feature2] : pairs) {
      a.push_back(ray(static_cast<int>(frame), feature1));
      b.push_back(ray(static_cast<int>(frame) + 1, feature2));
    }
    const std::optional<RayRotation> fit =
        EstimateRayRotation(a, b, max_angle, options.min_num_inliers, options.num_trials, &random);
    if (!fit) break;
    const Eigen::Matrix3d& next_from_this = fit->rotation;
    double sum_squared = 0.0;
    for (int i : fit->inliers) {
      const double error =
          (next_from_this * a[i]).cross(b[i]).norm() * 0.5 * (camera.fx + camera.fy);
      sum_squared += error * error;
    }
    const std::vector<int>& best = fit->inliers;
    cam_from_world = next_from_this * cam_from_world;
    const image_t image_id = static_cast<image_t>(frame + 2);
    path.reconstruction.image(image_id).cam_from_world =
        Rigid3d(Eigen::Quaterniond(cam_from_world).normalized(), Eigen::Vector3d::Zero());
    path.reconstruction.RegisterImage(image_id);
    ++path.num_registered;
    path.num_inliers.push_back(static_cast<int>(best.size()));
    path.rms_error_px.push_back(std::sqrt(sum_squared / best.size()));
  }
  return path;
}

}  // namespace comic::sfm
