// comic_sfm's outputs for the next tools, on the bundled KITTI example: transforms.json
// (nerfstudio) read back against sparse/0 by nerfstudio's convention, written down here:
//   transform_matrix M = [A 0; 0 1] · c2w_gl, A = applied_transform (rows x, z, −y)
//   c2w_gl = c2w_cv with columns y and z negated; c2w_cv = [R t; 0 1]^-1, COLMAP's cam_from_world
//   fl_x, fl_y, cx, cy: COLMAP's parameters as in cameras.bin (pixel-corner principal point);
// trajectory_tum.txt (timestamp tx ty tz qx qy qz qw, the centre and camera-to-world rotation) read
// back, and as --gt of a second run; --undistort's dense/ read by the real `colmap
// model_analyzer` (skipped where COLMAP is not installed).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/colmap/colmap_binary_model.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

std::string Example() { return comic::test::ExampleDir(); }

// fx, fy, cx, cy, k1 of a COLMAP camera as nerfstudio's parse_colmap_camera_params reads them.
std::vector<double> NerfstudioIntrinsics(const comic::io::ColmapCamera& camera) {
  const std::vector<double>& p = camera.params;
  if (camera.model == "PINHOLE") return {p[0], p[1], p[2], p[3], 0.0};
  if (camera.model == "SIMPLE_RADIAL") return {p[0], p[0], p[1], p[2], p[3]};
  ADD_FAILURE() << "unexpected camera model " << camera.model;
  return {};
}

void ExpectTransformsEqualTheModel(const std::string& folder) {
  const comic::io::ColmapTextModel model =
      comic::io::ReadColmapBinaryModel(comic::io::JoinPaths(folder, "sparse/0"));
  const nlohmann::json json = nlohmann::json::parse(
      comic::io::ReadFileToString(comic::io::JoinPaths(folder, "transforms.json")));
  ASSERT_EQ(model.cameras.size(), 1u);
  const std::vector<double> k = NerfstudioIntrinsics(model.cameras[0]);
  ASSERT_EQ(k.size(), 5u);
  EXPECT_EQ(json["camera_model"], "OPENCV");
  EXPECT_EQ(json["w"], model.cameras[0].width);
  EXPECT_EQ(json["h"], model.cameras[0].height);
  EXPECT_NEAR(json["fl_x"].get<double>(), k[0], 1e-9);
  EXPECT_NEAR(json["fl_y"].get<double>(), k[1], 1e-9);
  EXPECT_NEAR(json["cx"].get<double>(), k[2], 1e-9);
  EXPECT_NEAR(json["cy"].get<double>(), k[3], 1e-9);
  EXPECT_NEAR(json["k1"].get<double>(), k[4], 1e-12);

  Eigen::Matrix4d applied = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) applied(r, c) = json["applied_transform"][r][c].get<double>();
  }
  std::map<uint32_t, const comic::io::ColmapImage*> images;
  for (const auto& image : model.images) images[image.image_id] = &image;
  ASSERT_EQ(json["frames"].size(), model.images.size());
  for (const nlohmann::json& frame : json["frames"]) {
    const comic::io::ColmapImage& image = *images.at(frame["colmap_im_id"].get<uint32_t>());
    // The image file is where file_path says, relative to the output folder.
    const std::string path = comic::io::JoinPaths(folder, frame["file_path"].get<std::string>());
    EXPECT_TRUE(comic::io::IsRegularFile(path)) << path;
    EXPECT_EQ(comic::io::FileName(path), image.name);
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) m(r, c) = frame["transform_matrix"][r][c].get<double>();
    }
    Eigen::Matrix4d c2w = applied.inverse() * m;
    c2w.block<3, 2>(0, 1) *= -1.0;
    const Eigen::Matrix4d w2c = c2w.inverse();
    EXPECT_LT((w2c.topLeftCorner<3, 3>() - image.cam_from_world_rotation.toRotationMatrix()).norm(),
              1e-9);
    EXPECT_LT((w2c.topRightCorner<3, 1>() - image.cam_from_world_translation).norm(), 1e-9);
  }
}

void ExpectTumTrajectoryEqualsTheModel(const std::string& folder) {
  const comic::io::ColmapTextModel model =
      comic::io::ReadColmapBinaryModel(comic::io::JoinPaths(folder, "sparse/0"));
  std::map<std::string, const comic::io::ColmapImage*> images;
  for (const auto& image : model.images) images[image.name] = &image;
  std::istringstream lines(
      comic::io::ReadFileToString(comic::io::JoinPaths(folder, "trajectory_tum.txt")));
  std::string line;
  size_t count = 0;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    double t, x, y, z, qx, qy, qz, qw;
    ASSERT_TRUE(fields >> t >> x >> y >> z >> qx >> qy >> qz >> qw) << line;
    // A folder of frames has no frame rate: the time stamp is the frame's index, 000000.png ...
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.png", static_cast<int>(t));
    const comic::io::ColmapImage& image = *images.at(name);
    const Eigen::Quaterniond world_from_cam(qw, qx, qy, qz);
    EXPECT_LT(world_from_cam.angularDistance(image.cam_from_world_rotation.conjugate()), 1e-9);
    const Eigen::Vector3d center =
        -(image.cam_from_world_rotation.conjugate() * image.cam_from_world_translation);
    EXPECT_LT((Eigen::Vector3d(x, y, z) - center).norm(), 1e-9);
    ++count;
  }
  EXPECT_EQ(count, model.images.size());
}

// dense/ holds every registered image and a PINHOLE model COLMAP reads.
void ExpectUndistortedWorkspace(const std::string& folder) {
  const comic::io::ColmapTextModel model =
      comic::io::ReadColmapBinaryModel(comic::io::JoinPaths(folder, "sparse/0"));
  const comic::io::ColmapTextModel dense =
      comic::io::ReadColmapBinaryModel(comic::io::JoinPaths(folder, "dense/sparse"));
  ASSERT_EQ(dense.cameras.size(), 1u);
  EXPECT_EQ(dense.cameras[0].model, "PINHOLE");
  EXPECT_EQ(dense.images.size(), model.images.size());
  EXPECT_EQ(dense.points3D.size(), model.points3D.size());
  for (const auto& image : dense.images) {
    EXPECT_TRUE(
        comic::io::IsRegularFile(comic::io::JoinPaths(folder, "dense/images/" + image.name)))
        << image.name;
  }
  EXPECT_NE(
      comic::io::ReadFileToString(comic::io::JoinPaths(folder, "dense/stereo/patch-match.cfg"))
          .find("__auto__, 20\n"),
      std::string::npos);
  if (RunCommand("command -v colmap").exit_code != 0) return;
  const auto analyzed = RunCommand("QT_QPA_PLATFORM=offscreen colmap model_analyzer --path " +
                                   comic::io::JoinPaths(folder, "dense/sparse"));
  ASSERT_EQ(analyzed.exit_code, 0) << analyzed.output;
  EXPECT_NE(analyzed.output.find("Registered images: " + std::to_string(model.images.size())),
            std::string::npos)
      << analyzed.output;
}

TEST(ComicSfmHandoff, TransformsAndTumTrajectoryReadBackAsTheModel) {
  ScopedTempDir dir;
  const auto result =
      RunCommand(AppPath("comic_sfm") + " " + Example() + "/image_l --gt " + Example() +
                 "/poses.txt --quiet --undistort --output " + dir.File("out"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  ExpectTransformsEqualTheModel(dir.File("out"));
  ExpectTumTrajectoryEqualsTheModel(dir.File("out"));
  ExpectUndistortedWorkspace(dir.File("out"));

  // Our own trajectory as ground truth (detected as TUM, matched by frame index): the same path.
  const auto again = RunCommand(AppPath("comic_sfm") + " " + Example() + "/image_l --gt " +
                                dir.File("out/trajectory_tum.txt") +
                                " --quiet --undistort --output " + dir.File("again"));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  // Self-calibrated: SIMPLE_RADIAL (its k as refined, 0 on this forward drive).
  ExpectTransformsEqualTheModel(dir.File("again"));
  ExpectUndistortedWorkspace(dir.File("again"));
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("again/report.json")));
  EXPECT_LT(report["ground_truth"]["ate_fraction_of_path"].get<double>(), 0.01) << report.dump(2);
}

}  // namespace
