// What the renderer draws: textured planar pieces (rectangles, optionally cut by an alpha mask)
// grouped into objects. Every surface of a scene is one of these, so each is drawn exactly by the
// homography between its plane and the image (rasterizer.h).
//
// World axes: x and z horizontal, y up, the ground at y = 0, metres.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "render/alpha_mask.h"
#include "render/object_motion.h"
#include "render/texture.h"

namespace comic::render {

enum class TextureWrap {
  kClamp,   // the texture rectangle spans the piece once
  kMirror,  // the rectangle repeats, mirrored at each seam so the texture stays continuous
};

// A planar rectangle: the points origin + s·s_axis + t·t_axis for s, t in [0, 1].
struct Piece {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d s_axis = Eigen::Vector3d::UnitX();  // metres
  Eigen::Vector3d t_axis = Eigen::Vector3d::UnitY();
  int texture = 0;  // index into Scene::textures
  // The texture region (level-0 texel coordinates) on the piece, repeated `repeat` times along s
  // and t: (s, t) maps to (x + s·repeat_s·width, y + t·repeat_t·height), wrapped by `wrap` into
  // the region.
  cv::Rect2d texture_rect{0, 0, 1, 1};
  cv::Vec2d repeat{1.0, 1.0};
  TextureWrap wrap = TextureWrap::kClamp;
  int alpha = -1;     // index into Scene::alpha_masks; -1: the whole rectangle is solid
  int object_id = 0;  // 1-based index into Scene::objects
  cv::Vec3f tint{1.0f, 1.0f, 1.0f};  // BGR factors (a crude light: box tops brighter than sides)

  Eigen::Vector3d PointAt(double s, double t) const { return origin + s * s_axis + t * t_axis; }
};

struct SceneObject {
  std::string kind;         // "ground", "facade", "box", "pole", "tree", "fence", "background"...
  bool foreground = false;  // stands in front of the ground and background (the object masks)
  // Its pieces are placed at time 0; Scene::At moves them.
  ObjectMotion motion;
};

struct Scene {
  std::vector<Texture> textures;
  std::vector<AlphaMask> alpha_masks;
  std::vector<Piece> pieces;
  std::vector<SceneObject> objects;  // object id k is objects[k - 1]
  // What is seen where no piece is (BGR, 0..255): blended from the horizon to the zenith.
  cv::Vec3f sky_horizon{235.0f, 222.0f, 205.0f};
  cv::Vec3f sky_zenith{200.0f, 150.0f, 110.0f};

  // Adds an object and returns its id (1-based).
  int AddObject(const std::string& kind, bool foreground);
  // Whether any object moves.
  bool HasMotion() const;
  // The scene at `time` (frames): every moving object's pieces where its motion puts them then.
  // The same pieces in the same order, so piece indices and object ids mean the same at every
  // time (the truth images). Textures are shared, not copied.
  Scene At(double time) const;
  // Throws comic::Error(kInvalidArgument) naming the piece or object: indices out of range,
  // degenerate (parallel or zero) axes, an empty texture rectangle, a bad motion.
  void Check() const;
};

}  // namespace comic::render
