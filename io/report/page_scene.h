// The 3-D section of a report page (html_page.h): coloured points, camera frusta and paths,
// drawn with three.js (orbit, zoom, pan) by io/report/web/scene.js. Large point sets are
// subsampled to max_points, and the page says so.
//
//   Scene scene;
//   scene.points = {...};  scene.colors = {...};
//   scene.cameras.push_back({"model 1", "#1f77b4", centers, rotations});
//   page.sections.push_back(SceneSection(scene));
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/report/page_sections.h"

namespace comic::io {

// Cameras drawn as frusta (pyramids from the centre along the optical axis) joined by a path.
struct SceneCameras {
  std::string name;
  std::string color;
  std::vector<Eigen::Vector3d> centers;
  // world_from_camera rotations, one per centre (camera axes: x right, y down, z forward, as
  // COLMAP's); empty: the path alone, without frusta.
  std::vector<Eigen::Quaterniond> rotations;
  std::vector<int> frames;          // per camera: its frame (for the tooltip), or empty
  std::vector<uint8_t> emphasised;  // per camera, or empty: drawn larger (keyframes)
  double aspect = 4.0 / 3.0;        // image width / height
  double focal_over_width = 1.0;    // focal length / image width (the frustum's opening)
};

// A polyline (e.g. the ground-truth path), broken at NaN points, with optional dots.
struct ScenePath {
  std::string name;
  std::string color;
  std::vector<Eigen::Vector3d> points;
  bool dots = false;
};

struct Scene {
  std::string title;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<uint8_t, 3>> colors;  // RGB, one per point (or empty: grey)
  size_t max_points = 200000;  // more are subsampled (every k-th, deterministically)
  std::vector<SceneCameras> cameras;
  std::vector<ScenePath> paths;
  // The world direction drawn up (e.g. minus the cameras' mean y axis); zero: +y.
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  std::string unit;  // "m" or e.g. "model units"
  std::string note;
};

// Throws comic::Error(kInvalidArgument) for colours or rotations of the wrong count.
PageSection SceneSection(const Scene& scene);

}  // namespace comic::io
