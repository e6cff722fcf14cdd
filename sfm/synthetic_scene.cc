#include "sfm/synthetic_scene.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "io/core/error.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

namespace {

Camera MakeCamera(const SyntheticSceneOptions& options);
void RenderTracks(const SyntheticSceneOptions& options, std::mt19937* random,
                  SyntheticScene* scene);

}  // namespace

void SyntheticSceneOptions::Check() const {
  COMIC_CHECK(num_frames >= 1, kInvalidArgument, "synthetic num_frames must be >= 1");
  COMIC_CHECK(num_points >= 1, kInvalidArgument, "synthetic num_points must be >= 1");
  COMIC_CHECK(width > 0 && height > 0 && focal > 0, kInvalidArgument,
              "synthetic image size and focal length must be positive");
  COMIC_CHECK(noise_px >= 0, kInvalidArgument, "synthetic noise_px must be >= 0");
  COMIC_CHECK(outlier_ratio >= 0 && outlier_ratio < 1, kInvalidArgument,
              "synthetic outlier_ratio must be in [0, 1)");
  COMIC_CHECK(track_break_probability >= 0 && track_break_probability < 1, kInvalidArgument,
              "synthetic track_break_probability must be in [0, 1)");
}

double SyntheticScene::PathLength() const {
  double length = 0.0;
  for (size_t i = 1; i < cams_from_world.size(); ++i) {
    length +=
        (ProjectionCenter(cams_from_world[i]) - ProjectionCenter(cams_from_world[i - 1])).norm();
  }
  return length;
}

Rigid3d LookAt(const Eigen::Vector3d& center, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - center).normalized();
  Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(z);
  if (x.norm() < 1e-9) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d world_from_cam;
  world_from_cam.col(0) = x;
  world_from_cam.col(1) = y;
  world_from_cam.col(2) = z;
  const Eigen::Matrix3d rotation = world_from_cam.transpose();
  return Rigid3d(rotation, -rotation * center);
}

SyntheticScene MakeSyntheticScene(const SyntheticSceneOptions& options) {
  options.Check();
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * uniform(rng); };

  SyntheticScene scene;
  scene.camera = MakeCamera(options);

  const int n = options.num_frames;
  const double step = 1.2;  // metres per frame for forward motion
  for (int i = 0; i < n; ++i) {
    const double s = n > 1 ? static_cast<double>(i) / (n - 1) : 0.0;
    switch (options.motion) {
      case SyntheticMotion::kHandHeld: {
        // A 6 m sideways walk 10 m from the object, with a vertical bob and a slow zoom-in.
        const Eigen::Vector3d center(-3.0 + 6.0 * s, 0.3 * std::sin(6.0 * s), 1.5 * s);
        const Eigen::Vector3d target(0.5 * std::sin(4.0 * s), 0.3 * std::cos(3.0 * s), 10.0);
        scene.cams_from_world.push_back(LookAt(center, target));
        break;
      }
      case SyntheticMotion::kForward: {
        // Straight ahead with a gentle drift and a slightly wandering heading.
        const double z = step * i;
        const Eigen::Vector3d center(0.3 * std::sin(0.05 * i), 0.02 * std::sin(0.7 * i), z);
        const Eigen::Vector3d target(center.x() + 0.5 * std::sin(0.04 * i), center.y(), z + 20.0);
        scene.cams_from_world.push_back(LookAt(center, target));
        break;
      }
      case SyntheticMotion::kPureRotation: {
        const double yaw = 0.01 * i;  // radians
        const Eigen::Vector3d target(std::sin(yaw), 0.05 * std::sin(0.3 * i), std::cos(yaw));
        scene.cams_from_world.push_back(LookAt(Eigen::Vector3d::Zero(), target));
        break;
      }
    }
  }

  for (int p = 0; p < options.num_points; ++p) {
    switch (options.motion) {
      case SyntheticMotion::kHandHeld:
        scene.points3D.emplace_back(in(-5, 5), in(-3, 3), in(7, 14));
        break;
      case SyntheticMotion::kForward: {
        // Facades on both sides, the road, and some distant structure ahead.
        const double z = in(0.0, step * n + 40.0);
        const double kind = uniform(rng);
        if (kind < 0.7) {
          const double side = uniform(rng) < 0.5 ? -1.0 : 1.0;
          scene.points3D.emplace_back(side * in(4, 9), in(-4, 1.6), z);
        } else if (kind < 0.9) {
          scene.points3D.emplace_back(in(-4, 4), 1.6, z);
        } else {
          scene.points3D.emplace_back(in(-15, 15), in(-6, 1), step * n + in(40, 80));
        }
        break;
      }
      case SyntheticMotion::kPureRotation: {
        const double azimuth = in(-0.6, 1.2);
        const double depth = in(5, 20);
        scene.points3D.emplace_back(depth * std::sin(azimuth), in(-0.4, 0.4) * depth,
                                    depth * std::cos(azimuth));
        break;
      }
    }
  }

  RenderTracks(options, &rng, &scene);
  return scene;
}

SyntheticScene MakeSyntheticSceneFromPath(const SyntheticSceneOptions& path_options,
                                          std::vector<Rigid3d> cams_from_world,
                                          std::vector<Eigen::Vector3d> points3D) {
  SyntheticSceneOptions options = path_options;
  options.num_frames = std::max<int>(1, static_cast<int>(cams_from_world.size()));
  options.num_points = std::max<int>(1, static_cast<int>(points3D.size()));
  options.Check();
  SyntheticScene scene;
  scene.camera = MakeCamera(options);
  scene.cams_from_world = std::move(cams_from_world);
  scene.points3D = std::move(points3D);
  std::mt19937 rng(options.seed);
  RenderTracks(options, &rng, &scene);
  return scene;
}

std::vector<std::pair<int, int>> MatchSyntheticFrames(const SyntheticScene& scene, int frame1,
                                                      int frame2, double max_view_angle_deg) {
  const int num_frames = static_cast<int>(scene.tracks.NumFrames());
  COMIC_CHECK(frame1 >= 0 && frame1 < num_frames && frame2 >= 0 && frame2 < num_frames,
              kInvalidArgument,
              "synthetic match: frames " << frame1 << ", " << frame2 << " of " << num_frames);
  // Per point, its feature in each frame.
  std::map<int, int> in1, in2;
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : scene.tracks.tracks[t].observations) {
      if (obs.frame == frame1) in1[scene.track_point_index[t]] = obs.feature;
      if (obs.frame == frame2) in2[scene.track_point_index[t]] = obs.feature;
    }
  }
  const Eigen::Vector3d center1 = ProjectionCenter(scene.cams_from_world[frame1]);
  const Eigen::Vector3d center2 = ProjectionCenter(scene.cams_from_world[frame2]);
  const double max_cos = std::cos(max_view_angle_deg * M_PI / 180.0);
  std::vector<std::pair<int, int>> matches;
  for (const auto& [point, feature1] : in1) {
    const auto it = in2.find(point);
    if (it == in2.end()) continue;
    const Eigen::Vector3d& xyz = scene.points3D[point];
    if ((xyz - center1).normalized().dot((xyz - center2).normalized()) < max_cos) continue;
    matches.emplace_back(feature1, it->second);
  }
  return matches;
}

namespace {

Camera MakeCamera(const SyntheticSceneOptions& options) {
  Camera camera;
  camera.model = options.model;
  camera.width = options.width;
  camera.height = options.height;
  camera.fx = camera.fy = options.focal;
  if (options.focal_y != 0.0) camera.fy = options.focal_y;
  camera.cx = (options.width - 1) / 2.0;
  camera.cy = (options.height - 1) / 2.0;
  camera.k1 = options.k1;
  camera.k2 = options.k2;
  camera.p1 = options.p1;
  camera.p2 = options.p2;
  camera.Check();
  return camera;
}

// The tracks a tracker would make of scene->points3D seen from scene->cams_from_world.
void RenderTracks(const SyntheticSceneOptions& options, std::mt19937* random,
                  SyntheticScene* scene_out) {
  SyntheticScene& scene = *scene_out;
  std::mt19937& rng = *random;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, options.noise_px > 0 ? options.noise_px : 1.0);
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * uniform(rng); };
  const int n = static_cast<int>(scene.cams_from_world.size());
  const int num_points = static_cast<int>(scene.points3D.size());
  frontend::FeatureTracks& tracks = scene.tracks;
  tracks.detector_name = "synthetic";
  tracks.image_size = cv::Size(options.width, options.height);
  tracks.features.resize(n);
  scene.is_outlier.resize(n);
  for (int i = 0; i < n; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.png", i);
    tracks.frame_names.push_back(name);
  }
  constexpr double kMargin = 2.0;
  for (int p = 0; p < num_points; ++p) {
    frontend::Track track;
    const auto close_track = [&]() {
      if (!track.observations.empty()) {
        tracks.tracks.push_back(std::move(track));
        scene.track_point_index.push_back(p);
      }
      track = frontend::Track();
    };
    for (int i = 0; i < n; ++i) {
      const auto projection =
          ProjectPoint(scene.camera, scene.cams_from_world[i], scene.points3D[p]);
      const bool visible = projection && projection->x() >= kMargin && projection->y() >= kMargin &&
                           projection->x() <= options.width - 1 - kMargin &&
                           projection->y() <= options.height - 1 - kMargin &&
                           (scene.cams_from_world[i] * scene.points3D[p]).z() > 0.5;
      if (!visible) {
        close_track();
        continue;
      }
      if (!track.observations.empty() && uniform(rng) < options.track_break_probability) {
        close_track();
      }
      frontend::Feature feature;
      const bool outlier = uniform(rng) < options.outlier_ratio;
      if (outlier) {
        feature.x = static_cast<float>(in(0, options.width - 1));
        feature.y = static_cast<float>(in(0, options.height - 1));
      } else {
        const double dx = options.noise_px > 0 ? noise(rng) : 0.0;
        const double dy = options.noise_px > 0 ? noise(rng) : 0.0;
        feature.x = static_cast<float>(projection->x() + dx);
        feature.y = static_cast<float>(projection->y() + dy);
      }
      feature.response = 1.0f;
      tracks.features[i].push_back(feature);
      scene.is_outlier[i].push_back(outlier);
      track.observations.push_back({i, static_cast<int>(tracks.features[i].size()) - 1});
    }
    close_track();
  }
}

}  // namespace

}  // namespace comic::sfm
