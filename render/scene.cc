#include "render/scene.h"

#include <Eigen/Geometry>

#include "io/core/error.h"

namespace comic::render {

int Scene::AddObject(const std::string& kind, bool foreground) {
  objects.push_back({kind, foreground, ObjectMotion()});
  return static_cast<int>(objects.size());
}

bool Scene::HasMotion() const {
  for (const SceneObject& object : objects) {
    if (object.motion.Moves()) return true;
  }
  return false;
}

Scene Scene::At(double time) const {
  Scene moved = *this;
  if (!HasMotion()) return moved;
  for (Piece& piece : moved.pieces) {
    const ObjectMotion& motion = objects.at(piece.object_id - 1).motion;
    if (!motion.Moves()) continue;
    piece.origin = motion.PointAt(piece.origin, time);
    piece.s_axis = motion.DirectionAt(piece.s_axis, time);
    piece.t_axis = motion.DirectionAt(piece.t_axis, time);
  }
  return moved;
}

void Scene::Check() const {
  for (size_t k = 0; k < objects.size(); ++k) {
    try {
      objects[k].motion.Check();
    } catch (const Error& e) {
      throw Error(ErrorKind::kInvalidArgument,
                  "object " + std::to_string(k + 1) + " (" + objects[k].kind + "): " + e.what());
    }
  }
  for (size_t p = 0; p < pieces.size(); ++p) {
    const Piece& piece = pieces[p];
    COMIC_CHECK(piece.texture >= 0 && piece.texture < static_cast<int>(textures.size()),
                kInvalidArgument,
                "piece " << p << ": texture " << piece.texture << " out of range");
    COMIC_CHECK(piece.alpha < static_cast<int>(alpha_masks.size()), kInvalidArgument,
                "piece " << p << ": alpha mask " << piece.alpha << " out of range");
    COMIC_CHECK(piece.object_id >= 1 && piece.object_id <= static_cast<int>(objects.size()),
                kInvalidArgument,
                "piece " << p << ": object " << piece.object_id << " out of range");
    COMIC_CHECK(piece.s_axis.cross(piece.t_axis).norm() > 1e-12, kInvalidArgument,
                "piece " << p << ": its axes are zero or parallel");
    COMIC_CHECK(piece.texture_rect.width > 0 && piece.texture_rect.height > 0, kInvalidArgument,
                "piece " << p << ": empty texture rectangle");
    COMIC_CHECK(piece.repeat[0] > 0 && piece.repeat[1] > 0, kInvalidArgument,
                "piece " << p << ": texture repeat must be > 0");
  }
}

}  // namespace comic::render
