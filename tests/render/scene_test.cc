// A scene at a time (render/scene.h): the moving objects' pieces moved, every other piece where it
// was, the same pieces in the same order; a bad motion is refused naming its object.
#include "render/scene.h"

#include <gtest/gtest.h>

#include <string>

#include "io/core/error.h"

namespace comic::render {
namespace {

Scene TwoObjects() {
  Scene scene;
  scene.textures.push_back(Texture::Solid({100, 120, 140}, "grey"));
  const int wall = scene.AddObject("wall", false);
  const int box = scene.AddObject("box", true);
  Piece piece;
  piece.object_id = wall;
  scene.pieces.push_back(piece);
  piece.object_id = box;
  piece.origin = Eigen::Vector3d(1.0, 0.0, 4.0);
  piece.s_axis = Eigen::Vector3d(0.0, 0.0, 1.0);
  scene.pieces.push_back(piece);
  piece.origin = Eigen::Vector3d(1.0, 1.0, 4.0);
  scene.pieces.push_back(piece);
  return scene;
}

TEST(Scene, AtATimeOnlyTheMovingObjectsPiecesMove) {
  Scene scene = TwoObjects();
  EXPECT_FALSE(scene.HasMotion());
  const Scene still = scene.At(5.0);
  ASSERT_EQ(still.pieces.size(), 3u);
  for (size_t p = 0; p < 3; ++p) EXPECT_EQ(still.pieces[p].origin, scene.pieces[p].origin);

  scene.objects[1].motion.velocity = Eigen::Vector3d(0.25, 0.0, 0.5);
  scene.objects[1].motion.yaw_rate = M_PI / 8;  // a quarter turn in 4 frames
  scene.objects[1].motion.pivot = Eigen::Vector3d(1.0, 0.0, 4.0);
  EXPECT_TRUE(scene.HasMotion());
  scene.Check();
  const Scene moved = scene.At(4.0);
  ASSERT_EQ(moved.pieces.size(), 3u);
  EXPECT_EQ(moved.pieces[0].origin, scene.pieces[0].origin);  // the wall stands still
  EXPECT_EQ(moved.pieces[0].s_axis, scene.pieces[0].s_axis);
  for (size_t p = 1; p < 3; ++p) {
    EXPECT_EQ(moved.pieces[p].object_id, scene.pieces[p].object_id);
    // The origins are on the axis: carried by 4 frames of velocity; the axis along z turns to x.
    EXPECT_LT(
        (moved.pieces[p].origin - (scene.pieces[p].origin + Eigen::Vector3d(1.0, 0.0, 2.0))).norm(),
        1e-12);
    EXPECT_LT((moved.pieces[p].s_axis - Eigen::Vector3d::UnitX()).norm(), 1e-12);
    EXPECT_LT((moved.pieces[p].t_axis - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  }
  // The scene as built is the scene at time 0, and the scene itself is not changed.
  EXPECT_EQ(scene.At(0.0).pieces[2].origin, scene.pieces[2].origin);
  EXPECT_EQ(scene.pieces[1].origin, Eigen::Vector3d(1.0, 0.0, 4.0));
}

TEST(Scene, ABadMotionIsRefusedNamingItsObject) {
  Scene scene = TwoObjects();
  scene.objects[1].motion.velocity = Eigen::Vector3d(0.0, 0.0, 1e6);
  try {
    scene.Check();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("object 2 (box)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("speed"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace comic::render
