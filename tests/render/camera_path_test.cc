// Camera paths (render/camera_path.h) and the ground track they follow.
#include "render/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "io/core/error.h"
#include "render/truth_files.h"
#include "tests/test_support.h"

namespace comic::render {
namespace {

CameraPath Path(const std::string& json, int frames = 100, uint64_t seed = 3) {
  return CameraPath::FromJson(nlohmann::json::parse(json), "path", ".", frames, seed);
}

double RotationAngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a * b.transpose()).angle() * 180.0 / M_PI;
}

TEST(GroundTrack, TurnsFollowCirclesAndALoopCloses) {
  GroundTrack track({0.0, 0.0}, 0.0);
  track.AddStraight(10.0);
  track.AddTurn(90.0, 5.0);  // left: from +z towards +x
  EXPECT_NEAR(track.Length(), 10.0 + 2.5 * M_PI, 1e-12);
  const Eigen::Vector2d end = track.PointAt(track.Length());
  EXPECT_NEAR(end.x(), 5.0, 1e-9);
  EXPECT_NEAR(end.y(), 15.0, 1e-9);
  EXPECT_NEAR(track.HeadingAt(track.Length()), M_PI / 2.0, 1e-12);
  EXPECT_NEAR(track.LeftAt(0.0).x(), 1.0, 1e-12);  // y up: +x lies left of +z
  EXPECT_THROW(track.Close(), Error);              // it ends 15.8 m from its start

  GroundTrack square({0.0, 0.0}, 0.0);
  for (int k = 0; k < 4; ++k) {
    square.AddStraight(30.0);
    square.AddTurn(90.0, 8.0);
  }
  square.Close();
  EXPECT_NEAR((square.PointAt(square.Length() + 7.0) - square.PointAt(7.0)).norm(), 0.0, 1e-9);
}

TEST(CameraPath, ADriveMovesForwardAtItsSpeedAndALoopReturnsToItsStart) {
  const CameraPath path = Path(R"({"type": "drive", "speed": 0.5, "height": 1.5,
      "segments": [{"straight": 30}, {"turn": 90, "radius": 8}, {"straight": 30},
                   {"turn": 90, "radius": 8}, {"straight": 30}, {"turn": 90, "radius": 8},
                   {"straight": 30}, {"turn": 90, "radius": 8}], "loop": true})");
  const Pose a = path.At(0.0);
  const Pose b = path.At(1.0);
  EXPECT_NEAR((b.Center() - a.Center()).norm(), 0.5, 1e-9);
  EXPECT_NEAR(a.Center().y(), 1.5, 1e-12);
  // Forward is the camera's +z: the centre moves along it.
  const Eigen::Vector3d forward = a.rotation.row(2).transpose();
  EXPECT_NEAR(forward.dot((b.Center() - a.Center()).normalized()), 1.0, 1e-9);
  const double lap = (120.0 + 4 * 4 * M_PI) / 0.5;  // frames per lap
  const Pose again = path.At(lap);
  EXPECT_NEAR((again.Center() - a.Center()).norm(), 0.0, 1e-9);
  EXPECT_LT(RotationAngleDeg(again.rotation, a.rotation), 1e-6);
}

TEST(CameraPath, AnOrbitLooksAtItsCentreFromItsRadius) {
  const CameraPath path = Path(R"({"type": "orbit", "center": [2, 3], "radius": 6,
      "height": 2.5, "look_at_height": 1.0, "degrees_per_frame": 3})");
  for (double t : {0.0, 17.0, 55.5}) {
    const Pose pose = path.At(t);
    const Eigen::Vector3d c = pose.CamFromWorld({2.0, 1.0, 3.0});
    EXPECT_NEAR(c.x() / c.z(), 0.0, 1e-9);
    EXPECT_NEAR(c.y() / c.z(), 0.0, 1e-9);
    const Eigen::Vector3d center = pose.Center();
    EXPECT_NEAR(std::hypot(center.x() - 2.0, center.z() - 3.0), 6.0, 1e-9);
  }
  EXPECT_NEAR(RotationAngleDeg(path.At(1.0).rotation, path.At(0.0).rotation), 3.0, 0.2);
}

TEST(CameraPath, AWalkGoesSidewaysWithBobbingAndAPanOnlyTurns) {
  const CameraPath walk = Path(R"({"type": "walk", "speed": 0.05, "bob_amplitude": 0.03,
      "bob_period": 20})");
  const Pose a = walk.At(0.0);
  const Pose b = walk.At(5.0);
  const Eigen::Vector3d forward = a.rotation.row(2).transpose();
  const Eigen::Vector3d moved = b.Center() - a.Center();
  EXPECT_NEAR(Eigen::Vector2d(moved.x(), moved.z()).norm(), 0.25, 1e-9);
  EXPECT_NEAR(forward.dot(moved), 0.0, 0.031);  // only the bob's height change
  EXPECT_NEAR(walk.At(10.0).Center().y() - a.Center().y(), -0.06, 1e-9);  // half a step: down

  const CameraPath pan = Path(R"({"type": "pan", "position": [1, 1], "degrees_per_frame": 2})");
  EXPECT_NEAR((pan.At(7.0).Center() - pan.At(0.0).Center()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(RotationAngleDeg(pan.At(7.0).rotation, pan.At(0.0).rotation), 14.0, 1e-9);
}

TEST(CameraPath, ShakeIsSmoothAndSeeded) {
  const std::string json = R"({"type": "pan", "degrees_per_frame": 0.5,
      "shake": {"height": 0.05, "pitch_deg": 1, "roll_deg": 1, "yaw_deg": 1}})";
  const CameraPath a = Path(json, 100, 3);
  const CameraPath b = Path(json, 100, 3);
  const CameraPath c = Path(json, 100, 4);
  EXPECT_EQ(a.At(12.3).rotation, b.At(12.3).rotation);
  EXPECT_GT(RotationAngleDeg(a.At(12.3).rotation, c.At(12.3).rotation), 1e-3);
  // Continuous in time: a tenth of a frame moves it little.
  EXPECT_LT(RotationAngleDeg(a.At(12.3).rotation, a.At(12.4).rotation), 0.2);
}

TEST(CameraPath, APosesFileIsFollowedUpToTheChangeOfWorldAxes) {
  const CameraPath drive = Path(R"({"type": "drive", "speed": 0.7, "segments": [{"straight": 20},
      {"turn": -40, "radius": 10}], "shake": {"pitch_deg": 1, "yaw_deg": 2}})");
  test::ScopedTempDir dir;
  {
    std::ofstream poses(dir.File("poses.txt"));
    for (int k = 0; k < 20; ++k) poses << KittiPoseLine(drive.At(k)) << "\n";
  }
  const CameraPath replay = CameraPath::FromJson(
      nlohmann::json::parse(R"({"type": "poses", "file": "poses.txt", "height": 0})"), "path",
      dir.path(), 20, 1);
  // The file's world is turned into the scene's, so compare motions between frames.
  for (int k = 1; k < 20; ++k) {
    const Pose a0 = drive.At(0), a1 = drive.At(k), b0 = replay.At(0), b1 = replay.At(k);
    const Eigen::Matrix3d ra = a1.rotation * a0.rotation.transpose();
    const Eigen::Matrix3d rb = b1.rotation * b0.rotation.transpose();
    EXPECT_LT(RotationAngleDeg(ra, rb), 1e-6);
    const Eigen::Vector3d ta = a1.translation - ra * a0.translation;
    const Eigen::Vector3d tb = b1.translation - rb * b0.translation;
    EXPECT_NEAR((ta - tb).norm(), 0.0, 1e-6);
  }
  EXPECT_THROW(CameraPath::FromJson(nlohmann::json::parse(R"({"type": "poses",
      "file": "poses.txt"})"),
                                    "path", dir.path(), 21, 1),
               Error);  // 20 poses, 21 frames
}

// A scene reads files beside it only: never any file a path can name, quoted in an error.
TEST(CameraPath, APosesFileOutsideTheScenesFolderIsRefused) {
  test::ScopedTempDir dir;
  for (const char* file : {"/etc/hostname", "../poses.txt", "sub/../../poses.txt"}) {
    const nlohmann::json json = {{"type", "poses"}, {"file", file}};
    try {
      CameraPath::FromJson(json, "path", dir.path(), 1, 1);
      FAIL() << file << " not refused";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("path: \"file\": must be a path inside the scene's folder (relative, "
                            "without \"..\"), got \"") +
                    file + "\"");
    }
  }
}

TEST(CameraPath, MistakesNameTheKey) {
  const auto message = [](const std::string& json) {
    try {
      Path(json);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"type": "orbit", "radius": 5, "degrees_per_frame": 1, "radus": 3})")
                .find("\"radus\": unknown key"),
            std::string::npos);
  EXPECT_NE(message(R"({"type": "fly"})").find("unknown path"), std::string::npos);
  EXPECT_NE(message(R"({"type": "drive", "speed": 1, "segments": [{"straight": 10}],
      "loop": true})")
                .find("from its start"),
            std::string::npos);
  EXPECT_NE(message(R"({"type": "walk", "speed": 0})").find("\"speed\""), std::string::npos);
}

}  // namespace
}  // namespace comic::render
