#include "io/report/page_scene.h"

#include <algorithm>
#include <cmath>

#include "io/core/error.h"
#include "io/report/data_uri.h"

namespace comic::io {

namespace {

void AppendVector(const Eigen::Vector3d& v, std::vector<float>* values) {
  for (int k = 0; k < 3; ++k) values->push_back(static_cast<float>(v[k]));
}

// Centres (3 floats) and, with rotations, the world_from_camera quaternion (x, y, z, w as
// three.js orders it) of each camera, base64 Float32.
nlohmann::json CamerasJson(const SceneCameras& cameras) {
  COMIC_CHECK(cameras.rotations.empty() || cameras.rotations.size() == cameras.centers.size(),
              kInvalidArgument,
              "scene: cameras '" << cameras.name << "' need one rotation per "
                                 << "centre or none");
  COMIC_CHECK(cameras.frames.empty() || cameras.frames.size() == cameras.centers.size(),
              kInvalidArgument,
              "scene: cameras '" << cameras.name << "' need one frame per centre");
  COMIC_CHECK(cameras.emphasised.empty() || cameras.emphasised.size() == cameras.centers.size(),
              kInvalidArgument,
              "scene: cameras '" << cameras.name << "' emphasised: one per centre");
  std::vector<float> centers, rotations;
  for (const Eigen::Vector3d& c : cameras.centers) AppendVector(c, &centers);
  for (const Eigen::Quaterniond& q : cameras.rotations) {
    const Eigen::Quaterniond n = q.normalized();
    for (double v : {n.x(), n.y(), n.z(), n.w()}) rotations.push_back(static_cast<float>(v));
  }
  std::vector<int> emphasised(cameras.emphasised.begin(), cameras.emphasised.end());
  return {{"name", cameras.name},
          {"color", cameras.color},
          {"count", cameras.centers.size()},
          {"centers", Base64OfFloats(centers)},
          {"rotations", Base64OfFloats(rotations)},
          {"frames", cameras.frames},
          {"emphasised", emphasised},
          {"aspect", cameras.aspect},
          {"focal_over_width", cameras.focal_over_width}};
}

// A path with NaN breaks as base64 Float32 (NaN kept: the page breaks the line there).
nlohmann::json PathJson(const ScenePath& path) {
  std::vector<float> points;
  for (const Eigen::Vector3d& p : path.points) AppendVector(p, &points);
  return {{"name", path.name},
          {"color", path.color},
          {"count", path.points.size()},
          {"points", Base64OfFloats(points)},
          {"dots", path.dots}};
}

}  // namespace

PageSection SceneSection(const Scene& scene) {
  COMIC_CHECK(
      scene.colors.empty() || scene.colors.size() == scene.points.size(), kInvalidArgument,
      "scene: " << scene.colors.size() << " colours for " << scene.points.size() << " points");
  COMIC_CHECK(scene.max_points > 0, kInvalidArgument, "scene: max_points must be > 0");
  const size_t total = scene.points.size();
  // Every k-th point: deterministic, and it keeps the cloud's shape and density contrasts.
  const size_t stride = std::max<size_t>(1, (total + scene.max_points - 1) / scene.max_points);
  std::vector<float> xyz;
  std::vector<uint8_t> rgb;
  for (size_t i = 0; i < total; i += stride) {
    AppendVector(scene.points[i], &xyz);
    const std::array<uint8_t, 3> color =
        scene.colors.empty() ? std::array<uint8_t, 3>{150, 150, 150} : scene.colors[i];
    rgb.insert(rgb.end(), color.begin(), color.end());
  }
  nlohmann::json cameras = nlohmann::json::array();
  for (const SceneCameras& c : scene.cameras) cameras.push_back(CamerasJson(c));
  nlohmann::json paths = nlohmann::json::array();
  for (const ScenePath& p : scene.paths) paths.push_back(PathJson(p));
  const Eigen::Vector3d up =
      scene.up.norm() > 0 ? scene.up.normalized() : Eigen::Vector3d(0.0, 1.0, 0.0);
  return {{"type", "scene"},
          {"title", scene.title},
          {"points",
           {{"count", xyz.size() / 3},
            {"total", total},
            {"stride", stride},
            {"positions", Base64OfFloats(xyz)},
            {"colors", EncodeBase64(rgb)}}},
          {"cameras", cameras},
          {"paths", paths},
          {"up", {up.x(), up.y(), up.z()}},
          {"unit", scene.unit},
          {"note", scene.note}};
}

}  // namespace comic::io
