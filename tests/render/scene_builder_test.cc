// Scene files (render/scene_builder.h): the seed decides every placement and texture region, the
// file every kind and count; mistakes are one clear line naming the key.
#include "render/scene_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "render/random.h"
#include "tests/test_support.h"

namespace comic::render {
namespace {

std::vector<cv::Mat> Photos() {
  std::vector<cv::Mat> photos;
  for (int k = 0; k < 3; ++k) {
    cv::Mat photo(200 + 40 * k, 300, CV_8UC3);
    Random random(k);
    for (int i = 0; i < photo.rows * photo.cols * 3; ++i) photo.data[i] = random.Index(256);
    photos.push_back(photo);
  }
  return photos;
}

const char* kStreet = R"({
  "name": "street", "frames": 10,
  "path": {"type": "drive", "speed": 1.0, "segments": [{"straight": 60}, {"turn": 45, "radius": 20}]},
  "elements": [
    {"type": "ground", "extent": 300, "tile": 10},
    {"type": "background", "radius": 80, "segments": 12},
    {"type": "facades", "side": "both", "offset": 9},
    {"type": "poles", "side": "right", "offset": 5, "spacing": [8, 12]},
    {"type": "trees", "side": "left", "offset": 6},
    {"type": "fences", "side": "left", "offset": 7, "spacing": [20, 30]},
    {"type": "boxes", "side": "right", "offset": [3, 4], "spacing": [10, 15]},
    {"type": "box", "center": [0, 30], "size": [1, 2, 1], "photos": [2]}
  ]})";

BuiltScene Build(const std::string& json, uint64_t seed) {
  return BuildSceneFromJson(nlohmann::json::parse(json), "scene.json", ".", Photos(),
                            {"a", "b", "c"}, seed, SceneBuildOptions());
}

std::string BuildError(const std::string& json) {
  try {
    Build(json, 1);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    return e.what();
  }
  return "no error";
}

TEST(SceneBuilder, TheSeedDecidesTheSceneAndTheFileItsContent) {
  const BuiltScene a = Build(kStreet, 7);
  const BuiltScene b = Build(kStreet, 7);
  const BuiltScene c = Build(kStreet, 8);
  EXPECT_EQ(a.resolved.dump(), b.resolved.dump());
  EXPECT_NE(a.resolved["scene"].dump(), c.resolved["scene"].dump());
  std::map<std::string, int> kinds;
  for (const SceneObject& object : a.scene.objects) ++kinds[object.kind];
  EXPECT_EQ(kinds["ground"], 1);
  EXPECT_EQ(kinds["background"], 1);
  EXPECT_GE(kinds["facade"], 6);  // both sides of ~76 m in 8-25 m buildings
  EXPECT_GE(kinds["pole"], 5);    // every 8-12 m on one side
  EXPECT_GE(kinds["tree"], 3);
  EXPECT_GE(kinds["fence"], 2);
  EXPECT_GE(kinds["box"], 5);
  EXPECT_EQ(a.num_frames, 10);
  EXPECT_EQ(a.resolved["seed"], 7);
  EXPECT_EQ(a.resolved["scene"]["pieces"].size(), a.scene.pieces.size());
  // "photos": [2] restricts the single box to the third photograph.
  const int box_object = static_cast<int>(a.scene.objects.size());
  for (const Piece& piece : a.scene.pieces) {
    if (piece.object_id == box_object) {
      EXPECT_EQ(piece.texture, 2);
    }
  }
  // Trees and fences are cut by alpha masks; texture regions lie inside their photographs
  // (the ground's region repeats over it, mirrored).
  int masked = 0;
  for (const Piece& piece : a.scene.pieces) {
    masked += piece.alpha >= 0;
    const Texture& photo = a.scene.textures[piece.texture];
    EXPECT_GE(piece.texture_rect.x, 0.0);
    EXPECT_LE(piece.texture_rect.x + piece.texture_rect.width, photo.width() + 1e-9);
    EXPECT_LE(piece.texture_rect.y + piece.texture_rect.height, photo.height() + 1e-9);
  }
  EXPECT_GE(masked, 2 * kinds["tree"] + kinds["fence"]);
}

TEST(SceneBuilder, EditingOneElementLeavesTheOthersAsTheyWere) {
  nlohmann::json spec = nlohmann::json::parse(kStreet);
  const BuiltScene before = Build(spec.dump(), 5);
  spec["elements"][3]["spacing"] = nlohmann::json::array({9, 11});  // the poles
  const BuiltScene after = Build(spec.dump(), 5);
  // The facades (element 2) come out the same: the first pieces up to the poles are identical.
  const auto& a = before.resolved["scene"]["pieces"];
  const auto& b = after.resolved["scene"]["pieces"];
  int same = 0;
  while (same < static_cast<int>(std::min(a.size(), b.size())) && a[same] == b[same]) ++same;
  int facade_pieces = 0;
  for (const Piece& piece : before.scene.pieces) {
    const std::string& kind = before.scene.objects[piece.object_id - 1].kind;
    facade_pieces += kind == "facade" || kind == "ground" || kind == "background";
  }
  EXPECT_GE(same, facade_pieces);
}

TEST(SceneBuilder, MistakesAreOneLineNamingTheKey) {
  nlohmann::json spec = nlohmann::json::parse(kStreet);
  spec["elements"][2]["ofset"] = 3;
  EXPECT_NE(BuildError(spec.dump()).find("elements[2]: \"ofset\": unknown key"), std::string::npos);
  spec = nlohmann::json::parse(kStreet);
  spec["elements"][3]["height"] = "tall";
  EXPECT_NE(BuildError(spec.dump()).find("\"height\": expected a number or [low, high]"),
            std::string::npos);
  spec = nlohmann::json::parse(kStreet);
  spec["elements"][0]["type"] = "lake";
  EXPECT_NE(BuildError(spec.dump()).find("unknown element \"lake\""), std::string::npos);
  spec = nlohmann::json::parse(kStreet);
  spec["path"] = {{"type", "orbit"}, {"radius", 5}, {"degrees_per_frame", 1}};
  EXPECT_NE(BuildError(spec.dump()).find("has none"), std::string::npos);  // poles need a track
  spec = nlohmann::json::parse(kStreet);
  spec["camera"] = {{"fx", -3}};
  EXPECT_NE(BuildError(spec.dump()).find("fx and fy must be > 0"), std::string::npos);
  spec = nlohmann::json::parse(kStreet);
  spec["elements"][7]["photos"] = {5};
  EXPECT_NE(BuildError(spec.dump()).find("photograph index 5 out of range"), std::string::npos);
}

// What a scene asks of the renderer is bounded before any work, in the scene's words.
TEST(SceneBuilder, ValuesThatCrashOrNeverEndAreRefused) {
  const auto error = [](const std::function<void(nlohmann::json*)>& edit) {
    nlohmann::json spec = nlohmann::json::parse(kStreet);
    edit(&spec);
    return BuildError(spec.dump());
  };
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][0]["tile"] = 0;
            }).find("elements[0]: \"tile\": must be in [0.1, 1000], got 0"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][1]["segments"] = 1000000000;
            }).find("\"segments\": must be in [3, 4096]"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][2]["gap"] = {-5, 1};
            }).find("\"gap\": must be in [0, 1000], got -5"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][3]["spacing"] = 1e-6;
            }).find("\"spacing\": must be in [0.1, 10000]"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["frames"] = 1000000000;
            }).find("\"frames\": must be in [1, 100000]"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["camera"] = {{"width", 4294967297ull}};
            }).find("\"width\": expected a whole number within int's range, got 4294967297"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["description"] = {{"nested", {1, 2}}};
            }).find("\"description\": expected a string"),
            std::string::npos);
}

TEST(SceneBuilder, APlacedElementMovesAsItsVelocityAndYawRateSay) {
  nlohmann::json spec = nlohmann::json::parse(kStreet);
  spec["elements"][7]["velocity"] = {0.5, 0, -0.25};
  spec["elements"][7]["yaw_rate_deg"] = 2;
  const BuiltScene built = Build(spec.dump(), 7);
  ASSERT_TRUE(built.scene.HasMotion());
  const SceneObject& box = built.scene.objects.back();
  EXPECT_EQ(box.kind, "box");
  EXPECT_EQ(box.motion.velocity, Eigen::Vector3d(0.5, 0, -0.25));
  EXPECT_NEAR(box.motion.yaw_rate, 2 * M_PI / 180, 1e-15);
  // It turns about the vertical through its own centre, [0, 30] on the ground.
  EXPECT_NEAR(box.motion.pivot.x(), 0.0, 1e-9);
  EXPECT_NEAR(box.motion.pivot.z(), 30.0, 1e-9);
  for (size_t k = 0; k + 1 < built.scene.objects.size(); ++k) {
    EXPECT_FALSE(built.scene.objects[k].motion.Moves()) << k;
  }
  // scene.json says so, and only for what moves.
  const nlohmann::json& objects = built.resolved["scene"]["objects"];
  EXPECT_EQ(objects.back()["velocity"], nlohmann::json({0.5, 0.0, -0.25}));
  EXPECT_FALSE(objects.front().contains("velocity"));
  // The same file and seed: the same motion.
  EXPECT_EQ(Build(spec.dump(), 7).resolved.dump(), built.resolved.dump());
  EXPECT_FALSE(Build(kStreet, 7).scene.HasMotion());
}

TEST(SceneBuilder, BadMotionIsRefusedNamingTheKey) {
  const auto error = [](const std::function<void(nlohmann::json*)>& edit) {
    nlohmann::json spec = nlohmann::json::parse(kStreet);
    edit(&spec);
    try {
      BuildSceneFromJson(spec, "scene.json", ".", Photos(), {"a", "b", "c"}, 1,
                         SceneBuildOptions());
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][7]["velocity"] = {std::nan(""), 0, 0};
            }).find("elements[7]: \"velocity\": each component must be within -100..100"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][7]["velocity"] = {1e12, 0, 0};
            }).find("\"velocity\": each component must be within -100..100"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][7]["velocity"] = "fast";
            }).find("\"velocity\": expected three numbers"),
            std::string::npos);
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][7]["yaw_rate_deg"] = 1000;
            }).find("\"yaw_rate_deg\": must be in [-180, 180], got 1000"),
            std::string::npos);
  // Elements strewn along the track do not move.
  EXPECT_NE(error([](nlohmann::json* s) {
              (*s)["elements"][6]["velocity"] = {1, 0, 0};
            }).find("elements[6]: \"velocity\": unknown key"),
            std::string::npos);
}

TEST(SceneBuilder, FilesAndPhotographsAreReadWithClearErrors) {
  test::ScopedTempDir dir;
  const std::string photo = test::ExampleDir() + "/image_l/000000.png";
  EXPECT_THROW(BuildScene(dir.File("missing.json"), {photo}, 1, SceneBuildOptions()), Error);
  io::WriteFileAtomically(dir.File("broken.json"), "{ not json");
  try {
    BuildScene(dir.File("broken.json"), {photo}, 1, SceneBuildOptions());
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos);
  }
  nlohmann::json one_photo = nlohmann::json::parse(kStreet);
  one_photo["elements"].erase(7);  // the box restricted to a third photograph
  io::WriteFileAtomically(dir.File("street.json"), one_photo.dump());
  const BuiltScene built = BuildScene(dir.File("street.json"), {photo}, 1, SceneBuildOptions());
  EXPECT_EQ(built.scene.textures.size(), 1u);
  EXPECT_EQ(built.scene.textures[0].width(), 1226);
  EXPECT_THROW(BuildScene(dir.File("street.json"), {dir.File("none.png")}, 1, SceneBuildOptions()),
               Error);
}

}  // namespace
}  // namespace comic::render
