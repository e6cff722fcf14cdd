#include "render/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"
#include "render/json_fields.h"
#include "render/random.h"
#include "render/scene_elements.h"

namespace comic::render {
namespace {

constexpr double kDeg = M_PI / 180.0;

double Draw(Random& random, const Range& range) { return random.Uniform(range.low, range.high); }

ElementStyle ParseStyle(const JsonFields& fields, const cv::Vec3f& default_tint) {
  ElementStyle style;
  style.photos = fields.Integers("photos");
  const Eigen::Vector3d tint =
      fields.Vector3("tint", Eigen::Vector3d(default_tint[0], default_tint[1], default_tint[2]));
  style.tint = cv::Vec3f(static_cast<float>(tint[0]), static_cast<float>(tint[1]),
                         static_cast<float>(tint[2]));
  style.texels_per_metre = fields.Number("texels_per_metre", 0.0);
  if (style.texels_per_metre < 0) fields.Fail("texels_per_metre", "must be >= 0");
  return style;
}

// The sides of the track an element stands on: +1 left, -1 right.
std::vector<int> ParseSides(const JsonFields& fields) {
  const std::string side = fields.String("side", "both");
  if (side == "left") return {1};
  if (side == "right") return {-1};
  if (side == "both") return {1, -1};
  fields.Fail("side", "expected left, right or both");
}

// Placing along the track: the arc-length range and the point `offset` metres to `side`.
struct AlongTrack {
  const GroundTrack* track = nullptr;
  double first = 0.0;
  double last = 0.0;

  Eigen::Vector2d At(double a, int side, double offset) const {
    return track->PointAt(a) + side * offset * track->LeftAt(a);
  }
};

AlongTrack ParseAlong(const JsonFields& fields, const GroundTrack* track) {
  if (track == nullptr) {
    throw Error(ErrorKind::kInvalidArgument,
                fields.where() +
                    ": placed along the track, but the path (orbit, pan, poses) has "
                    "none; use single elements (box, tree, pole, fence, wall)");
  }
  AlongTrack along;
  along.track = track;
  along.first = fields.Number("start_at", 0.0);
  along.last = std::min(track->Length(), fields.Number("end_at", track->Length()));
  return along;
}

// A building's front along the track from a0 to a1 (chords of at most 4 m where the track
// bends, the texture continuous across them) and its two side walls reaching `depth` back.
void AddFacade(Scene* scene, const TexturePicker& picker, Random& random, const AlongTrack& along,
               int side, double offset, double a0, double a1, double height, double depth,
               const ElementStyle& style) {
  const int object_id = scene->AddObject("facade", false);
  const double length = a1 - a0;
  const TexturePicker::Choice choice =
      picker.Pick(random, length, height, style.photos, style.texels_per_metre);
  const bool bends = std::abs(along.track->HeadingAt(a1) - along.track->HeadingAt(a0)) > 1.0 * kDeg;
  const int chords = bends ? std::max(1, static_cast<int>(std::ceil(length / 4.0))) : 1;
  for (int k = 0; k < chords; ++k) {
    const double f0 = static_cast<double>(k) / chords;
    const double f1 = static_cast<double>(k + 1) / chords;
    const Eigen::Vector2d from = along.At(a0 + f0 * length, side, offset);
    const Eigen::Vector2d to = along.At(a0 + f1 * length, side, offset);
    TexturePicker::Choice part = choice;
    part.rect.x += f0 * choice.rect.width;
    part.rect.width *= f1 - f0;
    AddQuad(scene, Eigen::Vector3d(from.x(), height, from.y()),
            Eigen::Vector3d(to.x() - from.x(), 0.0, to.y() - from.y()),
            Eigen::Vector3d(0.0, -height, 0.0), part, object_id, style.tint);
  }
  ElementStyle side_style = style;
  side_style.tint = style.tint * 0.8f;
  for (double a : {a0, a1}) {
    const Eigen::Vector2d front = along.At(a, side, offset);
    const Eigen::Vector2d back = along.At(a, side, offset + depth);
    AddWall(scene, picker, random, front, back, 0.0, height, "facade", false, side_style,
            object_id);
  }
}

void AddFacades(Scene* scene, const TexturePicker& picker, Random& random, const JsonFields& f,
                const GroundTrack* track) {
  f.CheckKnown({"type", "side", "offset", "length", "height", "gap", "depth", "start_at", "end_at",
                "photos", "tint", "texels_per_metre"});
  const AlongTrack along = ParseAlong(f, track);
  const double offset = f.Number("offset", 9.0);
  const Range length = f.BoundedRange("length", {8.0, 25.0}, 0.5, 10000.0);
  const Range height = f.NumberRange("height", {6.0, 16.0});
  const Range gap = f.BoundedRange("gap", {0.0, 6.0}, 0.0, 1000.0);
  const Range depth = f.NumberRange("depth", {6.0, 12.0});
  const ElementStyle style = ParseStyle(f, {1.0f, 1.0f, 1.0f});
  for (int side : ParseSides(f)) {
    for (double a = along.first; a < along.last;) {
      const double a1 = std::min(along.last, a + Draw(random, length));
      if (a1 - a > 1.0) {
        AddFacade(scene, picker, random, along, side, offset, a, a1, Draw(random, height),
                  Draw(random, depth), style);
      }
      a = a1 + Draw(random, gap);
    }
  }
}

// Poles, trees, fences and boxes at random spacing along the track.
void AddAlongTrack(Scene* scene, const TexturePicker& picker, Random& random, const JsonFields& f,
                   const GroundTrack* track, const std::string& type) {
  f.CheckKnown({"type", "side", "offset", "spacing", "height", "width", "size", "length",
                "sign_probability", "slat_spacing", "start_at", "end_at", "photos", "tint",
                "texels_per_metre"});
  const AlongTrack along = ParseAlong(f, track);
  const Range offset = f.NumberRange("offset", {5.0, 5.0});
  const Range spacing = f.BoundedRange("spacing", {10.0, 20.0}, 0.1, 10000.0);
  const bool tree = type == "trees";
  const ElementStyle style =
      ParseStyle(f, tree ? cv::Vec3f(0.55f, 0.95f, 0.6f) : cv::Vec3f(1.0f, 1.0f, 1.0f));
  const Range height = f.NumberRange("height", tree ? Range{4.0, 8.0} : Range{4.0, 7.0});
  for (int side : ParseSides(f)) {
    for (double a = along.first + Draw(random, spacing) / 2.0; a < along.last;
         a += Draw(random, spacing)) {
      const Eigen::Vector2d at = along.At(a, side, Draw(random, offset));
      if (type == "poles") {
        AddPole(scene, picker, random, at, f.Number("width", 0.15), Draw(random, height),
                random.Uniform() < f.Number("sign_probability", 0.4), style);
      } else if (tree) {
        AddTree(scene, picker, random, at, Draw(random, f.NumberRange("width", {3.0, 5.0})),
                Draw(random, height), random.Uniform(0.0, M_PI), style);
      } else if (type == "fences") {
        const double length = Draw(random, f.NumberRange("length", {4.0, 12.0}));
        const Eigen::Vector2d to = at + length * along.track->DirectionAt(a);
        AddFence(scene, picker, random, at, to, Draw(random, f.NumberRange("height", {1.0, 1.5})),
                 f.BoundedNumber("slat_spacing", 0.15, 0.01, 100.0), style);
      } else {  // boxes
        const Range size = f.NumberRange("size", {0.5, 2.0});
        AddBox(scene, picker, random, at, Draw(random, size), Draw(random, size),
               Draw(random, size), random.Uniform(0.0, M_PI), style);
      }
    }
  }
}

// "velocity" (metres per frame) and "yaw_rate_deg" (degrees per frame): the objects from
// `first_object` on move so, each turning about the vertical through the centre of its pieces.
void SetMotion(Scene* scene, size_t first_object, const JsonFields& f) {
  ObjectMotion motion;
  motion.velocity = f.Vector3("velocity", Eigen::Vector3d::Zero());
  for (int k = 0; k < 3; ++k) {
    // Written so that NaN fails too.
    if (!(std::abs(motion.velocity[k]) <= 100.0)) {
      f.Fail("velocity", "each component must be within -100..100 metres per frame");
    }
  }
  motion.yaw_rate = f.BoundedNumber("yaw_rate_deg", 0.0, -180.0, 180.0) * kDeg;
  if (!motion.Moves()) return;
  for (size_t object = first_object; object < scene->objects.size(); ++object) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (const Piece& piece : scene->pieces) {
      if (piece.object_id != static_cast<int>(object) + 1) continue;
      sum += piece.PointAt(0.5, 0.5);
      ++count;
    }
    scene->objects[object].motion = motion;
    if (count > 0) scene->objects[object].motion.pivot = sum / count;
  }
}

// Elements at given places: box, tree, pole, fence, wall, box_field, background, ground.
void AddPlaced(Scene* scene, const TexturePicker& picker, Random& random, const JsonFields& f,
               const std::string& type, const Eigen::Vector2d& scene_center) {
  f.CheckKnown({"type",
                "center",
                "at",
                "size",
                "yaw_deg",
                "bottom",
                "height",
                "width",
                "sign",
                "from",
                "to",
                "top",
                "slat_spacing",
                "foreground",
                "area",
                "count",
                "radius",
                "segments",
                "extent",
                "tile",
                "photos",
                "tint",
                "texels_per_metre",
                "velocity",
                "yaw_rate_deg"});
  const size_t first_object = scene->objects.size();
  const ElementStyle style =
      ParseStyle(f, type == "tree" ? cv::Vec3f(0.55f, 0.95f, 0.6f) : cv::Vec3f(1.0f, 1.0f, 1.0f));
  const double yaw = f.Number("yaw_deg", 0.0) * kDeg;
  if (type == "box") {
    const Eigen::Vector3d size = f.Vector3("size", {1.0, 1.0, 1.0});
    AddBox(scene, picker, random, f.Vector2("center", {0, 0}), size.x(), size.z(), size.y(), yaw,
           style, f.Number("bottom", 0.0));
  } else if (type == "tree") {
    AddTree(scene, picker, random, f.Vector2("at", {0, 0}), f.Number("width", 4.0),
            f.Number("height", 6.0), yaw, style);
  } else if (type == "pole") {
    AddPole(scene, picker, random, f.Vector2("at", {0, 0}), f.Number("width", 0.15),
            f.Number("height", 5.0), f.Bool("sign", false), style);
  } else if (type == "fence") {
    AddFence(scene, picker, random, f.Vector2("from", {0, 0}), f.Vector2("to", {5, 0}),
             f.Number("height", 1.2), f.BoundedNumber("slat_spacing", 0.15, 0.01, 100.0), style);
  } else if (type == "wall") {
    AddWall(scene, picker, random, f.Vector2("from", {0, 0}), f.Vector2("to", {10, 0}),
            f.Number("bottom", 0.0), f.Number("top", 5.0), "wall", f.Bool("foreground", false),
            style);
  } else if (type == "box_field") {
    const nlohmann::json& area = f.At("area");
    if (!area.is_array() || area.size() != 4)
      f.Fail("area", "expected [x_min, z_min, x_max, z_max]");
    const Range size = f.NumberRange("size", {0.5, 2.0});
    const int count = f.BoundedInteger("count", 10, 0, 100000);
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector2d at(random.Uniform(area[0].get<double>(), area[2].get<double>()),
                               random.Uniform(area[1].get<double>(), area[3].get<double>()));
      AddBox(scene, picker, random, at, Draw(random, size), Draw(random, size), Draw(random, size),
             random.Uniform(0.0, M_PI), style);
    }
  } else if (type == "background") {
    AddBackgroundRing(scene, picker, random, f.Vector2("center", scene_center),
                      f.Number("radius", 300.0), f.Number("height", 80.0),
                      f.BoundedInteger("segments", 24, 3, 4096), style);
  } else if (type == "ground") {
    AddGround(scene, picker, random, f.Vector2("center", scene_center),
              f.BoundedNumber("extent", 600.0, 1.0, 100000.0),
              f.BoundedNumber("tile", 8.0, 0.1, 1000.0), style);
  } else {
    f.Fail("type",
           "unknown element \"" + type +
               "\" (ground, background, facades, poles, trees, fences, boxes, box, tree, pole, "
               "fence, wall, box_field)");
  }
  SetMotion(scene, first_object, f);
}

Lens ParseLens(const JsonFields& f) {
  f.CheckKnown({"width", "height", "fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"});
  Lens lens;
  lens.width = f.Integer("width", 640);
  lens.height = f.Integer("height", 480);
  lens.fx = f.Number("fx", 0.78 * lens.width);
  lens.fy = f.Number("fy", lens.fx);
  lens.cx = f.Number("cx", (lens.width - 1) / 2.0);
  lens.cy = f.Number("cy", (lens.height - 1) / 2.0);
  lens.k1 = f.Number("k1", 0.0);
  lens.k2 = f.Number("k2", 0.0);
  lens.p1 = f.Number("p1", 0.0);
  lens.p2 = f.Number("p2", 0.0);
  lens.Check();
  return lens;
}

cv::Mat ShrinkPhoto(const cv::Mat& photo, int max_size) {
  const int longest = std::max(photo.cols, photo.rows);
  if (longest <= max_size) return photo;
  cv::Mat small;
  const double f = static_cast<double>(max_size) / longest;
  cv::resize(photo, small, cv::Size(), f, f, cv::INTER_AREA);
  return small;
}

}  // namespace

void SceneBuildOptions::Check() const {
  COMIC_CHECK(max_texture_size >= 16, kInvalidArgument,
              "max texture size must be >= 16, got " << max_texture_size);
  COMIC_CHECK(num_frames >= 0, kInvalidArgument, "frames must be >= 0, got " << num_frames);
}

BuiltScene BuildSceneFromJson(const nlohmann::json& spec, const std::string& where,
                              const std::string& base_dir, const std::vector<cv::Mat>& photos,
                              const std::vector<std::string>& photo_names, uint64_t seed,
                              const SceneBuildOptions& options) {
  options.Check();
  const JsonFields f(spec, where);
  f.CheckKnown(
      {"name", "description", "frames", "camera", "path", "sky", "texels_per_metre", "elements"});
  COMIC_CHECK(!photos.empty(), kInvalidArgument,
              where << ": no photographs given to cut textures from");
  BuiltScene built;
  built.name = f.String("name", "scene");
  f.String("description", "");  // free text, but text
  built.num_frames =
      options.num_frames > 0 ? options.num_frames : f.BoundedInteger("frames", 100, 1, 100000);
  built.lens = ParseLens(
      JsonFields(f.Has("camera") ? f.At("camera") : nlohmann::json::object(), where + ": camera"));
  built.path = CameraPath::FromJson(f.At("path"), where + ": path", base_dir, built.num_frames,
                                    MixSeed(seed, 1));
  Scene& scene = built.scene;
  for (size_t k = 0; k < photos.size(); ++k) {
    scene.textures.push_back(
        Texture::FromImage(ShrinkPhoto(photos[k], options.max_texture_size), photo_names.at(k)));
  }
  if (f.Has("sky")) {
    const JsonFields sky(f.At("sky"), where + ": sky");
    sky.CheckKnown({"horizon", "zenith"});
    const Eigen::Vector3d h = sky.Vector3("horizon", {235, 222, 205});
    const Eigen::Vector3d z = sky.Vector3("zenith", {200, 150, 110});
    scene.sky_horizon = cv::Vec3f(h.x(), h.y(), h.z());
    scene.sky_zenith = cv::Vec3f(z.x(), z.y(), z.z());
  }
  const TexturePicker picker(scene, static_cast<int>(photos.size()),
                             f.Number("texels_per_metre", 40.0));
  const GroundTrack* track = built.path.track();
  const Eigen::Vector2d center =
      track != nullptr ? track->PointAt(track->Length() / 2.0) : Eigen::Vector2d(0.0, 0.0);
  const nlohmann::json& elements = f.At("elements");
  if (!elements.is_array()) f.Fail("elements", "expected a list");
  for (size_t k = 0; k < elements.size(); ++k) {
    const JsonFields element(elements[k], where + ": elements[" + std::to_string(k) + "]");
    const std::string type = element.RequiredString("type");
    // Each element draws from its own stream: editing one leaves the others as they were.
    Random random(seed, 1000 + k);
    if (type == "facades") {
      AddFacades(&scene, picker, random, element, track);
    } else if (type == "poles" || type == "trees" || type == "fences" || type == "boxes") {
      AddAlongTrack(&scene, picker, random, element, track, type);
    } else {
      AddPlaced(&scene, picker, random, element, type, center);
    }
  }
  scene.Check();
  built.resolved = {{"name", built.name}, {"seed", seed},          {"frames", built.num_frames},
                    {"source", spec},     {"photos", photo_names}, {"scene", DescribeScene(scene)}};
  return built;
}

namespace {

// A scene is a few levels deep; a parser and a JSON value's destructor recurse per level.
constexpr int kMaxSceneNesting = 64;

// The deepest nesting of arrays and objects in JSON `text`, strings skipped.
int JsonNestingDepth(const std::string& text) {
  int depth = 0;
  int deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

}  // namespace

BuiltScene BuildScene(const std::string& scene_file, const std::vector<std::string>& photos,
                      uint64_t seed, const SceneBuildOptions& options) {
  COMIC_CHECK(io::PathExists(scene_file), kNotFound, scene_file << ": no such scene file");
  const std::string text = io::ReadFileToString(scene_file);
  COMIC_CHECK(JsonNestingDepth(text) <= kMaxSceneNesting, kInvalidData,
              scene_file << ": arrays and objects nested deeper than " << kMaxSceneNesting
                         << " levels; refusing to parse it");
  nlohmann::json spec;
  try {
    spec = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(ErrorKind::kInvalidData, scene_file + ": not valid JSON: " + e.what());
  }
  std::vector<cv::Mat> images;
  for (const std::string& photo : photos) images.push_back(io::LoadImage(photo).color);
  return BuildSceneFromJson(spec, scene_file, io::ParentPath(scene_file), images, photos, seed,
                            options);
}

nlohmann::json DescribeScene(const Scene& scene) {
  nlohmann::json objects = nlohmann::json::array();
  const auto vec = [](const Eigen::Vector3d& v) {
    return std::vector<double>{v.x(), v.y(), v.z()};
  };
  for (size_t k = 0; k < scene.objects.size(); ++k) {
    const SceneObject& object = scene.objects[k];
    nlohmann::json described = {
        {"id", k + 1}, {"kind", object.kind}, {"foreground", object.foreground}};
    if (object.motion.Moves()) {
      described["velocity"] = vec(object.motion.velocity);
      described["yaw_rate"] = object.motion.yaw_rate;
      described["pivot"] = vec(object.motion.pivot);
    }
    objects.push_back(described);
  }
  nlohmann::json pieces = nlohmann::json::array();
  for (const Piece& piece : scene.pieces) {
    const cv::Rect2d& r = piece.texture_rect;
    pieces.push_back({{"object", piece.object_id},
                      {"origin", vec(piece.origin)},
                      {"s_axis", vec(piece.s_axis)},
                      {"t_axis", vec(piece.t_axis)},
                      {"texture", piece.texture},
                      {"texture_rect", {r.x, r.y, r.width, r.height}},
                      {"repeat", {piece.repeat[0], piece.repeat[1]}},
                      {"wrap", piece.wrap == TextureWrap::kMirror ? "mirror" : "clamp"},
                      {"alpha_mask", piece.alpha},
                      {"tint", {piece.tint[0], piece.tint[1], piece.tint[2]}}});
  }
  return {{"world", "x, z horizontal, y up, ground at y = 0, metres"},
          {"objects", objects},
          {"pieces", pieces},
          {"alpha_masks", scene.alpha_masks.size()}};
}

}  // namespace comic::render
