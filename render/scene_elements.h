// The building blocks of scenes, each made of planar pieces with textures cut from the
// photographs: ground, walls (façades, backdrops), boxes, poles, trees (two crossed billboards
// with a crown-shaped alpha mask), fences (slatted alpha masks) and a ring of distant backdrops.
// Positions on the ground are (x, z); heights are y (up).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "render/random.h"
#include "render/scene.h"

namespace comic::render {

// Cuts texture regions out of the scene's photographs (textures 0 .. num_photos - 1) for
// surfaces of a given size, at `texels_per_metre` when the photograph is large enough (else the
// largest region of the surface's shape that fits, stretched).
class TexturePicker {
 public:
  TexturePicker(const Scene& scene, int num_photos, double texels_per_metre);

  struct Choice {
    int texture = 0;
    cv::Rect2d rect;
  };
  // A region of a photograph drawn from `allowed` (indices of photographs; empty: any), at
  // `texels_per_metre` when > 0 (else the picker's).
  Choice Pick(Random& random, double width_m, double height_m, const std::vector<int>& allowed,
              double texels_per_metre = 0.0) const;
  int num_photos() const { return num_photos_; }

 private:
  const Scene& scene_;
  int num_photos_;
  double texels_per_metre_;
};

struct ElementStyle {
  std::vector<int> photos;  // photographs to cut textures from (empty: any)
  cv::Vec3f tint{1.0f, 1.0f, 1.0f};
  double texels_per_metre = 0.0;  // > 0: this element's texture density, not the scene's
};

// A rectangle with corners origin, origin + s_axis, origin + s_axis + t_axis, origin + t_axis,
// textured once by `choice`. Returns the piece's index.
int AddQuad(Scene* scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& s_axis,
            const Eigen::Vector3d& t_axis, const TexturePicker::Choice& choice, int object_id,
            const cv::Vec3f& tint, int alpha = -1);

// The ground: a square of side `extent` centred on `center`, one photograph region repeated
// (mirrored) every `tile` metres.
void AddGround(Scene* scene, const TexturePicker& picker, Random& random,
               const Eigen::Vector2d& center, double extent, double tile,
               const ElementStyle& style);
// A vertical wall from `from` to `to` (x, z) between heights `bottom` and `top`, its texture
// continuous along it; `object_id` 0 makes a new object of `kind`.
int AddWall(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& from,
            const Eigen::Vector2d& to, double bottom, double top, const std::string& kind,
            bool foreground, const ElementStyle& style, int object_id = 0);
// A box standing on the ground (or at `bottom`): footprint `width` x `depth` turned by `yaw`
// radians, `height` tall; five faces (no bottom), the top brighter, sides shaded.
int AddBox(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& center,
           double width, double depth, double height, double yaw, const ElementStyle& style,
           double bottom = 0.0, const std::string& kind = "box", int object_id = 0);
// A square pole of side `width`, `height` tall, sometimes carrying a sign board.
int AddPole(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& at,
            double width, double height, bool sign, const ElementStyle& style);
// A tree: two crossed billboards (`width` wide, `height` tall) turned by `yaw`, sharing one crown
// mask.
int AddTree(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& at,
            double width, double height, double yaw, const ElementStyle& style);
// A picket fence from `from` to `to`, `height` tall, slats every `slat_spacing` metres.
int AddFence(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& from,
             const Eigen::Vector2d& to, double height, double slat_spacing,
             const ElementStyle& style);
// A ring of `segments` walls of radius `radius` around `center`, facing it, from 1 m below the
// ground to `height`: a distant backdrop all around.
int AddBackgroundRing(Scene* scene, const TexturePicker& picker, Random& random,
                      const Eigen::Vector2d& center, double radius, double height, int segments,
                      const ElementStyle& style);

}  // namespace comic::render
