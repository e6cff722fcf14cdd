#include "render/scene_elements.h"

#include <algorithm>
#include <cmath>

#include "io/core/error.h"

namespace comic::render {
namespace {

Eigen::Vector3d At(const Eigen::Vector2d& xz, double y) { return {xz.x(), y, xz.y()}; }

cv::Vec3f Times(const cv::Vec3f& a, const cv::Vec3f& b) {
  return {a[0] * b[0], a[1] * b[1], a[2] * b[2]};
}

cv::Vec3f Grey(float value) { return {value, value, value}; }

}  // namespace

TexturePicker::TexturePicker(const Scene& scene, int num_photos, double texels_per_metre)
    : scene_(scene), num_photos_(num_photos), texels_per_metre_(texels_per_metre) {
  COMIC_CHECK(num_photos >= 1 && num_photos <= static_cast<int>(scene.textures.size()),
              kInvalidArgument, "a scene needs at least one photograph to cut textures from");
  COMIC_CHECK(texels_per_metre > 0, kInvalidArgument, "texels per metre must be > 0");
}

TexturePicker::Choice TexturePicker::Pick(Random& random, double width_m, double height_m,
                                          const std::vector<int>& allowed,
                                          double texels_per_metre) const {
  const double density = texels_per_metre > 0 ? texels_per_metre : texels_per_metre_;
  Choice choice;
  choice.texture = allowed.empty() ? random.Index(num_photos_)
                                   : allowed[random.Index(static_cast<int>(allowed.size()))];
  COMIC_CHECK(choice.texture >= 0 && choice.texture < num_photos_, kInvalidArgument,
              "photograph index " << choice.texture << " out of range (" << num_photos_
                                  << " photographs given)");
  const Texture& photo = scene_.textures[choice.texture];
  double w = std::max(1e-3, width_m) * density;
  double h = std::max(1e-3, height_m) * density;
  const double fit = std::min({1.0, photo.width() / w, photo.height() / h});
  w *= fit;
  h *= fit;
  choice.rect = cv::Rect2d(random.Uniform() * (photo.width() - w),
                           random.Uniform() * (photo.height() - h), w, h);
  return choice;
}

int AddQuad(Scene* scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& s_axis,
            const Eigen::Vector3d& t_axis, const TexturePicker::Choice& choice, int object_id,
            const cv::Vec3f& tint, int alpha) {
  Piece piece;
  piece.origin = origin;
  piece.s_axis = s_axis;
  piece.t_axis = t_axis;
  piece.texture = choice.texture;
  piece.texture_rect = choice.rect;
  piece.object_id = object_id;
  piece.tint = tint;
  piece.alpha = alpha;
  scene->pieces.push_back(piece);
  return static_cast<int>(scene->pieces.size()) - 1;
}

void AddGround(Scene* scene, const TexturePicker& picker, Random& random,
               const Eigen::Vector2d& center, double extent, double tile,
               const ElementStyle& style) {
  const int object_id = scene->AddObject("ground", false);
  const TexturePicker::Choice choice =
      picker.Pick(random, tile, tile, style.photos, style.texels_per_metre);
  // s along +x, t along +z: seen from above, the texture is not mirrored.
  const int p = AddQuad(scene, At(center - Eigen::Vector2d(extent, extent) / 2.0, 0.0),
                        Eigen::Vector3d(extent, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, extent),
                        choice, object_id, style.tint);
  scene->pieces[p].repeat = cv::Vec2d(extent / tile, extent / tile);
  scene->pieces[p].wrap = TextureWrap::kMirror;
}

int AddWall(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& from,
            const Eigen::Vector2d& to, double bottom, double top, const std::string& kind,
            bool foreground, const ElementStyle& style, int object_id) {
  if (object_id == 0) object_id = scene->AddObject(kind, foreground);
  const double length = (to - from).norm();
  const TexturePicker::Choice choice =
      picker.Pick(random, length, top - bottom, style.photos, style.texels_per_metre);
  AddQuad(scene, At(from, top), At(to - from, 0.0), Eigen::Vector3d(0.0, bottom - top, 0.0), choice,
          object_id, style.tint);
  return object_id;
}

int AddBox(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& center,
           double width, double depth, double height, double yaw, const ElementStyle& style,
           double bottom, const std::string& kind, int object_id) {
  if (object_id == 0) object_id = scene->AddObject(kind, true);
  const Eigen::Vector2d ex = Eigen::Vector2d(std::cos(yaw), std::sin(yaw)) * (width / 2.0);
  const Eigen::Vector2d ez = Eigen::Vector2d(-std::sin(yaw), std::cos(yaw)) * (depth / 2.0);
  // Footprint corners counter-clockwise seen from above; one photograph for the whole box.
  const Eigen::Vector2d corners[4] = {center - ex - ez, center + ex - ez, center + ex + ez,
                                      center - ex + ez};
  ElementStyle box_style = style;
  box_style.photos = {picker.Pick(random, 1.0, 1.0, style.photos, style.texels_per_metre).texture};
  const float side_light[4] = {0.85f, 0.7f, 0.8f, 0.65f};
  const double top = bottom + height;
  for (int k = 0; k < 4; ++k) {
    ElementStyle side = box_style;
    side.tint = Times(style.tint, Grey(side_light[k]));
    AddWall(scene, picker, random, corners[k], corners[(k + 1) % 4], bottom, top, kind, true, side,
            object_id);
  }
  const TexturePicker::Choice lid =
      picker.Pick(random, width, depth, box_style.photos, style.texels_per_metre);
  AddQuad(scene, At(corners[0], top), At(corners[1] - corners[0], 0.0),
          At(corners[3] - corners[0], 0.0), lid, object_id, Times(style.tint, Grey(1.0f)));
  return object_id;
}

int AddPole(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& at,
            double width, double height, bool sign, const ElementStyle& style) {
  const int object_id = scene->AddObject("pole", true);
  const double yaw = random.Uniform(0.0, M_PI / 2.0);
  AddBox(scene, picker, random, at, width, width, height, yaw, style, 0.0, "pole", object_id);
  if (sign) {
    // A board on the pole, facing along its yaw: 0.6 x 0.8 m, 4 cm thick.
    const double board_bottom = height - random.Uniform(0.9, 1.6);
    AddBox(scene, picker, random, at, 0.6, 0.04, 0.8, yaw, style, board_bottom, "pole", object_id);
  }
  return object_id;
}

int AddTree(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& at,
            double width, double height, double yaw, const ElementStyle& style) {
  const int object_id = scene->AddObject("tree", true);
  scene->alpha_masks.push_back(MakeTreeMask(random));
  const int alpha = static_cast<int>(scene->alpha_masks.size()) - 1;
  for (double turn : {0.0, M_PI / 2.0}) {
    const Eigen::Vector2d half =
        Eigen::Vector2d(std::cos(yaw + turn), std::sin(yaw + turn)) * (width / 2.0);
    const TexturePicker::Choice choice =
        picker.Pick(random, width, height, style.photos, style.texels_per_metre);
    AddQuad(scene, At(at - half, height), At(2.0 * half, 0.0), Eigen::Vector3d(0.0, -height, 0.0),
            choice, object_id, style.tint, alpha);
  }
  return object_id;
}

int AddFence(Scene* scene, const TexturePicker& picker, Random& random, const Eigen::Vector2d& from,
             const Eigen::Vector2d& to, double height, double slat_spacing,
             const ElementStyle& style) {
  const int object_id = scene->AddObject("fence", true);
  const double length = (to - from).norm();
  const int slats = std::max(1, static_cast<int>(std::lround(length / slat_spacing)));
  scene->alpha_masks.push_back(MakeFenceMask(slats, 0.55));
  const TexturePicker::Choice choice =
      picker.Pick(random, length, height, style.photos, style.texels_per_metre);
  AddQuad(scene, At(from, height), At(to - from, 0.0), Eigen::Vector3d(0.0, -height, 0.0), choice,
          object_id, style.tint, static_cast<int>(scene->alpha_masks.size()) - 1);
  return object_id;
}

int AddBackgroundRing(Scene* scene, const TexturePicker& picker, Random& random,
                      const Eigen::Vector2d& center, double radius, double height, int segments,
                      const ElementStyle& style) {
  COMIC_CHECK(segments >= 3, kInvalidArgument, "a background ring needs at least 3 segments");
  const int object_id = scene->AddObject("background", false);
  for (int k = 0; k < segments; ++k) {
    const double a0 = 2.0 * M_PI * k / segments;
    const double a1 = 2.0 * M_PI * (k + 1) / segments;
    // From a1 to a0: seen from the centre, the texture runs left to right (not mirrored).
    const Eigen::Vector2d from = center + radius * Eigen::Vector2d(std::sin(a1), std::cos(a1));
    const Eigen::Vector2d to = center + radius * Eigen::Vector2d(std::sin(a0), std::cos(a0));
    AddWall(scene, picker, random, from, to, -1.0, height, "background", false, style, object_id);
  }
  return object_id;
}

}  // namespace comic::render
