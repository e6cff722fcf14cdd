// Ground-truth camera formats: each convention is checked by projecting a known 3-D point, on
// excerpts of the real files (and on the full files in ../shared/data when present).
#include "io/datasets/ground_truth_cameras.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

Eigen::Vector2d Project(const GroundTruthCamera& camera, const Eigen::Vector3d& point_in_world) {
  const Eigen::Vector3d point_in_cam =
      camera.cam_from_world_rotation * point_in_world + camera.cam_from_world_translation;
  const Eigen::Vector3d pixel = camera.K * point_in_cam;
  return pixel.head<2>() / pixel.z();
}

double Depth(const GroundTruthCamera& camera, const Eigen::Vector3d& point_in_world) {
  return (camera.cam_from_world_rotation * point_in_world + camera.cam_from_world_translation).z();
}

// The first line of templeSR_par.txt (Middlebury templeSparseRing), verbatim.
const char* kTempleExcerpt =
    "1\n"
    "templeSR0001.png 1520.400000 0.000000 302.320000 0.000000 1525.900000 246.870000 0.000000 "
    "0.000000 1.000000 0.02187598221295043000 0.98329680886213122000 -0.18068986436368856000 "
    "0.99856708067455469000 -0.01266114646423925600 0.05199500709979997700 "
    "0.04883878372068499500 -0.18156839221560722000 -0.98216479887691122000 -0.0726637729648 "
    "0.0223360353405 0.614604845959\n";

// 0000.jpg.camera of Strecha's Herz-Jesu-P8, verbatim.
const char* kHerzJesuCamera =
    "2759.48 0 1520.69 \n0 2764.16 1006.81 \n0 0 1 \n0 0 0\n-0.0552 0.132982 0.98958 \n"
    "0.998433 0.0164966 0.0534769 \n-0.00921322 0.990981 -0.133684 \n"
    "-6.71999 -14.2551 0.279539 \n3072 2048\n";

TEST(GroundTruthCameras, MiddleburyParIsWorldToCamera) {
  test::ScopedTempDir dir;
  const std::string path = dir.File("templeSR_par.txt");
  WriteFileAtomically(path, kTempleExcerpt);
  EXPECT_EQ(DetectGroundTruthFormat(path), GroundTruthFormat::kMiddlebury);
  const GroundTruthCameras truth = ReadGroundTruthCameras(path);
  ASSERT_EQ(truth.cameras.size(), 1u);
  const GroundTruthCamera& camera = truth.cameras[0];
  EXPECT_EQ(camera.image_name, "templeSR0001.png");
  ASSERT_TRUE(camera.has_intrinsics);
  EXPECT_DOUBLE_EQ(camera.K(0, 0), 1520.4);
  EXPECT_DOUBLE_EQ(camera.K(1, 2), 246.87);
  // The centre of the temple's bounding box (README.txt) is 0.56 m in front of the camera and
  // lands inside the 640x480 image, near its middle.
  const Eigen::Vector3d center = 0.5 * (Eigen::Vector3d(-0.073568, 0.021728, -0.012445) +
                                        Eigen::Vector3d(0.028855, 0.181892, 0.062736));
  EXPECT_NEAR(Depth(camera, center), 0.56, 0.02);
  const Eigen::Vector2d pixel = Project(camera, center);
  EXPECT_GT(pixel.x(), 160);
  EXPECT_LT(pixel.x(), 480);
  EXPECT_GT(pixel.y(), 120);
  EXPECT_LT(pixel.y(), 360);
  // P = K [R | t] exactly: the world origin projects to K t.
  const Eigen::Vector3d kt = camera.K * camera.cam_from_world_translation;
  EXPECT_TRUE(Project(camera, Eigen::Vector3d::Zero()).isApprox(kt.head<2>() / kt.z(), 1e-12));
}

TEST(GroundTruthCameras, StrechaRotationIsCameraToWorld) {
  test::ScopedTempDir dir;
  const std::string path = dir.File("0000.jpg.camera");
  WriteFileAtomically(path, kHerzJesuCamera);
  EXPECT_EQ(DetectGroundTruthFormat(path), GroundTruthFormat::kStrecha);
  const GroundTruthCameras truth = ReadGroundTruthCameras(path);
  ASSERT_EQ(truth.cameras.size(), 1u);
  const GroundTruthCamera& camera = truth.cameras[0];
  EXPECT_EQ(camera.image_name, "0000.jpg");
  EXPECT_EQ(camera.width, 3072);
  EXPECT_EQ(camera.height, 2048);
  // The file's R has the camera axes as columns: a point 10 m along the third column from C
  // projects to the principal point, one 10 m along the first column further right by fx.
  const Eigen::Vector3d c(-6.71999, -14.2551, 0.279539);
  const Eigen::Vector3d x_axis(-0.0552, 0.998433, -0.00921322);
  const Eigen::Vector3d z_axis(0.98958, 0.0534769, -0.133684);
  const Eigen::Vector2d on_axis = Project(camera, c + 10.0 * z_axis);
  EXPECT_NEAR(on_axis.x(), 1520.69, 1e-3);
  EXPECT_NEAR(on_axis.y(), 1006.81, 1e-3);
  EXPECT_NEAR(Depth(camera, c + 10.0 * z_axis), 10.0, 1e-4);
  const Eigen::Vector2d right = Project(camera, c + 10.0 * z_axis + 10.0 * x_axis);
  EXPECT_NEAR(right.x(), 1520.69 + 2759.48, 0.5);
  EXPECT_NEAR(right.y(), 1006.81, 0.5);
}

TEST(GroundTruthCameras, KittiPosesAreCameraToWorldWithCalibIntrinsics) {
  test::ScopedTempDir dir;
  // Two poses: the identity, and 1.2 m forward turned 10 degrees to the right (about y).
  const double a = 10.0 * M_PI / 180.0;
  std::ostringstream poses;
  poses.precision(17);
  poses << "1 0 0 0 0 1 0 0 0 0 1 0\n"
        << std::cos(a) << " 0 " << std::sin(a) << " 0 0 1 0 0 " << -std::sin(a) << " 0 "
        << std::cos(a) << " 1.2\n";
  WriteFileAtomically(dir.File("poses.txt"), poses.str());
  WriteFileAtomically(dir.File("calib.txt"),
                      "P0: 7.070912e+02 0 6.018873e+02 0 0 7.070912e+02 1.831104e+02 0 0 0 1 0\n");
  EXPECT_EQ(DetectGroundTruthFormat(dir.File("poses.txt")), GroundTruthFormat::kKitti);
  const GroundTruthCameras truth = ReadGroundTruthCameras(dir.File("poses.txt"));
  ASSERT_EQ(truth.cameras.size(), 2u);
  EXPECT_TRUE(truth.cameras[1].image_name.empty());
  EXPECT_EQ(truth.cameras[1].index, 1);
  ASSERT_TRUE(truth.cameras[1].has_intrinsics);
  EXPECT_DOUBLE_EQ(truth.cameras[1].K(0, 2), 601.8873);
  // A point 10 m straight ahead of camera 1 (along its rotated optical axis) projects to the
  // principal point; the second camera's centre is (0, 0, 1.2) in the world.
  const Eigen::Vector3d ahead =
      Eigen::Vector3d(0, 0, 1.2) + 10.0 * Eigen::Vector3d(std::sin(a), 0, std::cos(a));
  const Eigen::Vector2d pixel = Project(truth.cameras[1], ahead);
  EXPECT_NEAR(pixel.x(), 601.8873, 1e-6);
  EXPECT_NEAR(pixel.y(), 183.1104, 1e-6);
  EXPECT_NEAR(Depth(truth.cameras[1], ahead), 10.0, 1e-9);
}

TEST(GroundTruthCameras, IntrinsicsFilesInThreeForms) {
  test::ScopedTempDir dir;
  WriteFileAtomically(dir.File("four.txt"), "700 710 600.5 180.25\n");
  WriteFileAtomically(dir.File("k.txt"), "2759.48 0 1520.69 \n0 2764.16 1006.81 \n0 0 1 \n");
  WriteFileAtomically(dir.File("p.txt"),
                      "P0: 7.07e+02 0 6.01e+02 0 0 7.07e+02 1.83e+02 0 0 0 1 0\n"
                      "P1: 7.07e+02 0 6.01e+02 -3.79e+02 0 7.07e+02 1.83e+02 0 0 0 1 0\n");
  const Eigen::Matrix3d four = ReadIntrinsicsFile(dir.File("four.txt"));
  EXPECT_DOUBLE_EQ(four(0, 0), 700);
  EXPECT_DOUBLE_EQ(four(1, 1), 710);
  EXPECT_DOUBLE_EQ(four(0, 2), 600.5);
  EXPECT_DOUBLE_EQ(four(1, 2), 180.25);
  EXPECT_DOUBLE_EQ(ReadIntrinsicsFile(dir.File("k.txt"))(1, 1), 2764.16);
  EXPECT_DOUBLE_EQ(ReadIntrinsicsFile(dir.File("p.txt"))(0, 2), 601);

  WriteFileAtomically(dir.File("bad.txt"), "700 710 600\n");
  EXPECT_THROW(ReadIntrinsicsFile(dir.File("bad.txt")), Error);
  WriteFileAtomically(dir.File("negative.txt"), "-700 710 600 100\n");
  EXPECT_THROW(ReadIntrinsicsFile(dir.File("negative.txt")), Error);
  EXPECT_THROW(ReadIntrinsicsFile(dir.File("missing.txt")), Error);
}

TEST(GroundTruthCameras, MalformedFilesThrowNamingTheFile) {
  test::ScopedTempDir dir;
  const auto expect_error = [&](const std::string& name, const std::string& content,
                                const std::string& message) {
    const std::string path = dir.File(name);
    WriteFileAtomically(path, content);
    try {
      ReadGroundTruthCameras(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << error.what();
    }
  };
  expect_error("count_par.txt", "2\nimg.png 1 0 0 0 1 0 0 0 1 1 0 0 0 1 0 0 0 1 0 0 0\n",
               "says 2 cameras");
  // Found by fuzz_ground_truth: a count beyond size_t was cast before it was compared (UB).
  expect_error("huge_count_par.txt",
               "7.070912000000e+022\nimg.png 1 0 0 0 1 0 0 0 1 1 0 0 0 1 0 0 0 1 0 0 0\n",
               "cameras but lists 1");
  expect_error("short_par.txt", "1\nimg.png 1 0 0 0 1 0 0 0 1 1 0 0 0 1 0 0 0 1 0 0\n",
               "21 numbers");
  expect_error("rotation_par.txt", "1\nimg.png 1 0 0 0 1 0 0 0 1 2 0 0 0 1 0 0 0 1 0 0 0\n",
               "not a rotation");
  expect_error("text.camera", "a b c\n", "9 lines");
  expect_error("unknown.txt", "1 2 3\n", "not a known ground-truth format");
  EXPECT_THROW(ReadGroundTruthCameras(dir.File("missing.txt")), Error);
  EXPECT_THROW(ReadGroundTruthCameras(dir.path()), Error);  // a folder without *.camera
  EXPECT_THROW(ParseGroundTruthFormat("bundler"), Error);
  EXPECT_EQ(ParseGroundTruthFormat("strecha"), GroundTruthFormat::kStrecha);
  EXPECT_EQ(ParseGroundTruthFormat("colmap"), GroundTruthFormat::kColmap);
  EXPECT_EQ(ParseGroundTruthFormat("nerf"), GroundTruthFormat::kNerf);
  expect_error("broken.json", "{\"frames\": [", "not a valid transforms file");
  expect_error("noframes.json", "{\"camera_angle_x\": 0.7}", "no \"frames\" array");
  expect_error("nofov.json",
               "{\"frames\": [{\"file_path\": \"a\", \"transform_matrix\": "
               "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]}",
               "neither camera_angle_x nor fl_x");
  expect_error("scaled.json",
               "{\"camera_angle_x\": 0.7, \"frames\": [{\"file_path\": \"a\", "
               "\"transform_matrix\": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]}",
               "not a rotation");
  expect_error("short.json",
               "{\"camera_angle_x\": 0.7, \"frames\": [{\"file_path\": \"a\", "
               "\"transform_matrix\": [[1,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]}",
               "4 rows of 4 numbers");
}

// A NeRF transforms file of two cameras 5 units from the origin, each looking at it: one from +z
// with world y up, one from +x with world z up, in Blender's camera axes (x right, y up, z back).
const char* kNerfTransforms = R"({
  "camera_angle_x": 0.9272952180016122,
  "frames": [
    {"file_path": "./train/r_0", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,5],[0,0,0,1]]},
    {"file_path": "./train/r_1", "transform_matrix": [[0,0,1,5],[1,0,0,0],[0,1,0,0],[0,0,0,1]]}
  ]
})";

TEST(GroundTruthCameras, NerfTransformsTurnBlenderCameraAxesIntoOpenCvs) {
  test::ScopedTempDir dir;
  const std::string path = dir.File("transforms_train.json");
  WriteFileAtomically(path, kNerfTransforms);
  EXPECT_EQ(DetectGroundTruthFormat(path), GroundTruthFormat::kNerf);
  const GroundTruthCameras truth = ReadGroundTruthCameras(path);
  ASSERT_EQ(truth.cameras.size(), 2u);
  EXPECT_EQ(truth.format, GroundTruthFormat::kNerf);
  EXPECT_EQ(truth.cameras[0].image_name, "r_0");
  // No image size in the file: the field of view, for the frames' size (2 atan(1/2): f = w).
  EXPECT_FALSE(truth.cameras[0].has_intrinsics);
  EXPECT_NEAR(truth.cameras[0].horizontal_fov_rad, 0.9272952180016122, 1e-15);
  for (GroundTruthCamera camera : truth.cameras) {
    camera.K << 100, 0, 49.5, 0, 100, 49.5, 0, 0, 1;  // a 100 x 100 image
    // The origin is 5 in front of each camera, at the image centre.
    EXPECT_NEAR(Depth(camera, Eigen::Vector3d::Zero()), 5.0, 1e-12);
    EXPECT_NEAR((Project(camera, Eigen::Vector3d::Zero()) - Eigen::Vector2d(49.5, 49.5)).norm(), 0,
                1e-9);
  }
  // Camera 0 (from +z, world y up): world +x is to the right, world +y up (smaller image y).
  GroundTruthCamera front = truth.cameras[0];
  front.K << 100, 0, 49.5, 0, 100, 49.5, 0, 0, 1;
  EXPECT_NEAR(Project(front, Eigen::Vector3d(1, 0, 0)).x(), 49.5 + 100.0 / 5, 1e-9);
  EXPECT_NEAR(Project(front, Eigen::Vector3d(0, 1, 0)).y(), 49.5 - 100.0 / 5, 1e-9);
  // Camera 1 (from +x, world z up): world +y is to the right, world +z up.
  GroundTruthCamera side = truth.cameras[1];
  side.K << 100, 0, 49.5, 0, 100, 49.5, 0, 0, 1;
  EXPECT_NEAR(Project(side, Eigen::Vector3d(0, 1, 0)).x(), 69.5, 1e-9);
  EXPECT_NEAR(Project(side, Eigen::Vector3d(0, 0, 1)).y(), 29.5, 1e-9);
  EXPECT_NEAR(Depth(side, Eigen::Vector3d(1, 0, 0)), 4.0, 1e-12);

  // With an image size and explicit intrinsics (pixel-corner convention, as COLMAP's).
  const std::string explicit_path = dir.File("transforms.json");
  WriteFileAtomically(explicit_path,
                      R"({"fl_x": 120, "fl_y": 121, "cx": 50, "cy": 40, "w": 100, "h": 80,
                          "frames": [{"file_path": "images/a.png",
                          "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,5],[0,0,0,1]]}]})");
  const GroundTruthCameras explicit_truth = ReadGroundTruthCameras(explicit_path);
  ASSERT_TRUE(explicit_truth.cameras[0].has_intrinsics);
  EXPECT_EQ(explicit_truth.cameras[0].image_name, "a.png");
  EXPECT_DOUBLE_EQ(explicit_truth.cameras[0].K(0, 0), 120);
  EXPECT_DOUBLE_EQ(explicit_truth.cameras[0].K(1, 1), 121);
  EXPECT_DOUBLE_EQ(explicit_truth.cameras[0].K(0, 2), 49.5);
  EXPECT_DOUBLE_EQ(explicit_truth.cameras[0].K(1, 2), 39.5);
  EXPECT_EQ(explicit_truth.cameras[0].width, 100);
}

TEST(GroundTruthCameras, ColmapModelsTextAndBinary) {
  ColmapTextModel model;
  model.cameras.push_back({1, "PINHOLE", 640, 480, {500, 510, 320, 240}});
  model.cameras.push_back({2, "SIMPLE_RADIAL", 640, 480, {500, 320, 240, 0.1}});
  ColmapImage a;
  a.image_id = 2;
  a.camera_id = 1;
  a.name = "images/b.png";
  a.cam_from_world_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  a.cam_from_world_translation = Eigen::Vector3d(1, 2, 3);
  ColmapImage b = a;
  b.image_id = 1;
  b.camera_id = 2;
  b.name = "images/a.png";
  model.images = {a, b};
  test::ScopedTempDir dir;
  WriteColmapTextModel(model, dir.File("text"));
  WriteColmapBinaryModel(model, dir.File("binary"));
  for (const std::string& path : {dir.File("text"), dir.File("binary"), dir.File("text/images.txt"),
                                  dir.File("binary/cameras.bin")}) {
    EXPECT_EQ(DetectGroundTruthFormat(path), GroundTruthFormat::kColmap) << path;
    const GroundTruthCameras truth = ReadGroundTruthCameras(path);
    ASSERT_EQ(truth.cameras.size(), 2u) << path;
    // By image id: a.png (id 1, distorted camera: poses only), then b.png.
    EXPECT_EQ(truth.cameras[0].image_name, "images/a.png");
    EXPECT_FALSE(truth.cameras[0].has_intrinsics);
    const GroundTruthCamera& pinhole = truth.cameras[1];
    EXPECT_EQ(pinhole.image_name, "images/b.png");
    ASSERT_TRUE(pinhole.has_intrinsics);
    EXPECT_DOUBLE_EQ(pinhole.K(0, 0), 500);
    EXPECT_DOUBLE_EQ(pinhole.K(1, 1), 510);
    EXPECT_DOUBLE_EQ(pinhole.K(0, 2), 319.5);  // COLMAP's pixel centres at +0.5
    EXPECT_EQ(pinhole.width, 640);
    EXPECT_TRUE(pinhole.cam_from_world_rotation.isApprox(
        a.cam_from_world_rotation.toRotationMatrix(), 1e-12));
    EXPECT_TRUE(pinhole.cam_from_world_translation.isApprox(Eigen::Vector3d(1, 2, 3), 1e-12));
  }
  // A folder without a model is not one.
  EXPECT_THROW(ReadColmapGroundTruth(dir.path()), Error);
}

TEST(GroundTruthCameras, SharedDataFilesParseAndSeeTheirObjects) {
  COMIC_REQUIRE_SHARED_DATA();
  const std::string data = test::SharedDataDir();
  const GroundTruthCameras temple =
      ReadGroundTruthCameras(data + "/middlebury_mview_templeSparseRing/templeSR_par.txt");
  ASSERT_EQ(temple.cameras.size(), 16u);
  const Eigen::Vector3d temple_center(-0.0224, 0.1018, 0.0251);
  for (const GroundTruthCamera& camera : temple.cameras) {
    EXPECT_NEAR(Depth(camera, temple_center), 0.565, 0.02) << camera.image_name;
    const Eigen::Vector2d pixel = Project(camera, temple_center);
    EXPECT_TRUE(pixel.x() > 0 && pixel.x() < 640 && pixel.y() > 0 && pixel.y() < 480)
        << camera.image_name;
  }
  const GroundTruthCameras dino =
      ReadGroundTruthCameras(data + "/middlebury_mview_dino_ring48/dino_ring48_par.txt");
  ASSERT_EQ(dino.cameras.size(), 48u);
  EXPECT_EQ(dino.cameras[47].image_name, "dino0048.png");

  const GroundTruthCameras herz =
      ReadGroundTruthCameras(data + "/strecha_Herz-Jesu-P8/gt_dense_cameras");
  ASSERT_EQ(herz.cameras.size(), 8u);
  EXPECT_EQ(herz.format, GroundTruthFormat::kStrecha);
  EXPECT_EQ(herz.cameras[7].image_name, "0007.jpg");
  // Neighbouring cameras look at the same facade: a point 20 m in front of camera 0 is in front
  // of camera 1 and inside its image.
  const Eigen::Matrix3d r0 = herz.cameras[0].cam_from_world_rotation;
  const Eigen::Vector3d c0 = -r0.transpose() * herz.cameras[0].cam_from_world_translation;
  const Eigen::Vector3d facade = c0 + 20.0 * r0.row(2).transpose();
  EXPECT_GT(Depth(herz.cameras[1], facade), 10.0);
  const Eigen::Vector2d pixel = Project(herz.cameras[1], facade);
  EXPECT_TRUE(pixel.x() > 0 && pixel.x() < 3072 && pixel.y() > 0 && pixel.y() < 2048);

  const GroundTruthCameras kitti =
      ReadGroundTruthCameras(data + "/kitti_odometry_seq06_000-050/poses.txt");
  ASSERT_EQ(kitti.cameras.size(), 51u);
  ASSERT_TRUE(kitti.cameras[0].has_intrinsics);
  // The car drives forward: frame 50's centre is ~60 m ahead along frame 0's +z.
  const Eigen::Vector3d c50 = -kitti.cameras[50].cam_from_world_rotation.transpose() *
                              kitti.cameras[50].cam_from_world_translation;
  EXPECT_GT(c50.z(), 55.0);
  EXPECT_LT(std::abs(c50.x()), 5.0);

  // NeRF lego: 100 cameras on a sphere of radius 4.03 around the object at the origin, each
  // looking at it (the origin within 10 px of the centre of the 800 x 800 views).
  GroundTruthCameras lego =
      ReadGroundTruthCameras(data + "/nerf_synthetic_lego/transforms_train.json");
  ASSERT_EQ(lego.cameras.size(), 100u);
  EXPECT_EQ(lego.cameras[99].image_name, "r_99");
  for (GroundTruthCamera& camera : lego.cameras) {
    const double f = 400.0 / std::tan(0.5 * camera.horizontal_fov_rad);
    camera.K << f, 0, 399.5, 0, f, 399.5, 0, 0, 1;
    EXPECT_NEAR(Depth(camera, Eigen::Vector3d::Zero()), 4.03, 0.01) << camera.image_name;
    EXPECT_LT((Project(camera, Eigen::Vector3d::Zero()) - Eigen::Vector2d(399.5, 399.5)).norm(),
              10.0)
        << camera.image_name;
  }
}

}  // namespace
}  // namespace comic::io
