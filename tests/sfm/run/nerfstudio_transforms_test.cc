// transforms.json in nerfstudio's convention (sfm/run/nerfstudio_transforms.h), read back by the
// convention as nerfstudio's colmap_utils.colmap_to_json writes it, independently of the writer:
//   written  M = [A 0; 0 1] · c2w_gl, A = rows (x, z, −y) (also in "applied_transform")
//            c2w_gl = c2w_cv with its y and z columns negated (OpenCV → OpenGL camera axes)
//            c2w_cv = [R t; 0 1]^-1, (R, t) COLMAP's cam_from_world
//   back     c2w_cv = ([Aᵀ 0; 0 1] · M) with columns 1, 2 negated; [R t] = c2w_cv^-1
//   cameras  fl_x, fl_y, cx, cy as in COLMAP's cameras.bin (principal point + 0.5 on ours),
//            k1, k2, p1, p2; camera_model "OPENCV" for every model.
#include "sfm/run/nerfstudio_transforms.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "io/core/error.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {
namespace {

Eigen::Matrix4d MatrixOf(const nlohmann::json& rows) {
  Eigen::Matrix4d matrix;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) matrix(r, c) = rows.at(r).at(c).get<double>();
  }
  return matrix;
}

// The convention above, backwards.
Rigid3d CamFromWorldOf(const nlohmann::json& frame, const nlohmann::json& applied_rows) {
  Eigen::Matrix4d applied = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) applied(r, c) = applied_rows.at(r).at(c).get<double>();
  }
  Eigen::Matrix4d c2w = applied.inverse() * MatrixOf(frame.at("transform_matrix"));
  c2w.block<3, 2>(0, 1) *= -1.0;
  const Eigen::Matrix4d w2c = c2w.inverse();
  return Rigid3d(Eigen::Matrix3d(w2c.topLeftCorner<3, 3>()), w2c.topRightCorner<3, 1>());
}

// Three views of a camera of each model in `cameras`, in turn, at random poses.
Reconstruction SyntheticModel(const std::vector<Camera>& cameras) {
  Reconstruction reconstruction;
  std::vector<camera_t> ids;
  for (const Camera& camera : cameras) ids.push_back(reconstruction.AddCamera(camera));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-2.0, 2.0);
  for (int i = 0; i < 6; ++i) {
    Image image;
    image.camera_id = ids[i % ids.size()];
    image.name = "frame_" + std::to_string(i) + ".png";
    const Eigen::Vector3d axis =
        Eigen::Vector3d(uniform(random), uniform(random), uniform(random)).normalized();
    image.cam_from_world = Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(uniform(random), axis)),
                                   Eigen::Vector3d(uniform(random), uniform(random), 5.0));
    reconstruction.RegisterImage(reconstruction.AddImage(image));
  }
  Image unregistered;
  unregistered.camera_id = ids.front();
  unregistered.name = "lost.png";
  reconstruction.AddImage(unregistered);
  return reconstruction;
}

void ExpectCamera(const nlohmann::json& json, const Camera& camera) {
  EXPECT_EQ(json.at("camera_model"), "OPENCV");
  EXPECT_EQ(json.at("w").get<int>(), camera.width);
  EXPECT_EQ(json.at("h").get<int>(), camera.height);
  EXPECT_NEAR(json.at("fl_x").get<double>(), camera.fx, 1e-9);
  EXPECT_NEAR(json.at("fl_y").get<double>(), camera.fy, 1e-9);
  EXPECT_NEAR(json.at("cx").get<double>() - 0.5, camera.cx, 1e-9);
  EXPECT_NEAR(json.at("cy").get<double>() - 0.5, camera.cy, 1e-9);
  EXPECT_NEAR(json.at("k1").get<double>(), camera.k1, 1e-12);
  EXPECT_NEAR(json.at("k2").get<double>(), camera.k2, 1e-12);
  EXPECT_NEAR(json.at("p1").get<double>(), camera.p1, 1e-12);
  EXPECT_NEAR(json.at("p2").get<double>(), camera.p2, 1e-12);
}

void ExpectPosesReadBack(const Reconstruction& reconstruction, const nlohmann::json& json) {
  const std::vector<image_t> registered = reconstruction.RegisteredImageIds();
  ASSERT_EQ(json.at("frames").size(), registered.size());
  for (size_t k = 0; k < registered.size(); ++k) {
    const nlohmann::json& frame = json.at("frames").at(k);
    const Image& image = reconstruction.image(registered[k]);
    EXPECT_EQ(frame.at("colmap_im_id").get<image_t>(), image.image_id);
    EXPECT_EQ(frame.at("file_path"), "../images/" + image.name);
    const Rigid3d back = CamFromWorldOf(frame, json.at("applied_transform"));
    EXPECT_LT((back.RotationMatrix() - image.cam_from_world.RotationMatrix()).norm(), 1e-9);
    EXPECT_LT((back.translation - image.cam_from_world.translation).norm(), 1e-9);
  }
}

nlohmann::json TransformsThroughText(const Reconstruction& reconstruction, int width, int height) {
  const nlohmann::json json = NerfstudioTransforms(
      reconstruction, width, height, [](const Image& image) { return "../images/" + image.name; });
  return nlohmann::json::parse(json.dump(2));  // what a reader gets from the file
}

TEST(NerfstudioTransforms, OneSimpleRadialCameraReadsBackAtTheTopLevel) {
  const Camera camera = Camera::FromParams(CameraModelId::kSimpleRadial, 1241, 376,
                                           {718.856, 607.1928, 185.2157, -0.031});
  const Reconstruction reconstruction = SyntheticModel({camera});
  const nlohmann::json json = TransformsThroughText(reconstruction, 0, 0);
  ExpectCamera(json, camera);
  ExpectPosesReadBack(reconstruction, json);
  EXPECT_FALSE(json.at("frames").at(0).contains("fl_x"));
}

TEST(NerfstudioTransforms, TwoCamerasGoToEachFrame) {
  const Camera opencv = Camera::FromParams(CameraModelId::kOpenCV, 640, 480,
                                           {500.5, 502.25, 319.0, 241.5, 0.1, -0.02, 1e-3, -2e-3});
  const Camera pinhole =
      Camera::FromParams(CameraModelId::kPinhole, 800, 600, {700, 710, 400, 300});
  const Reconstruction reconstruction = SyntheticModel({opencv, pinhole});
  const nlohmann::json json = TransformsThroughText(reconstruction, 0, 0);
  EXPECT_FALSE(json.contains("fl_x"));
  for (size_t k = 0; k < json.at("frames").size(); ++k) {
    ExpectCamera(json.at("frames").at(k), k % 2 == 0 ? opencv : pinhole);
  }
  ExpectPosesReadBack(reconstruction, json);
}

TEST(NerfstudioTransforms, CamerasAreWrittenAtTheInputSize) {
  const Camera working =
      Camera::FromParams(CameraModelId::kSimpleRadial, 700, 350, {600.0, 349.5, 174.5, 0.05});
  const Reconstruction reconstruction = SyntheticModel({working});
  const nlohmann::json json = TransformsThroughText(reconstruction, 1400, 700);
  ExpectCamera(json, ResizedCamera(working, 1400, 700));
  EXPECT_NEAR(json.at("fl_x").get<double>(), 1200.0, 1e-9);
  EXPECT_NEAR(json.at("cx").get<double>(), 700.0, 1e-9);  // COLMAP's: the image centre
}

TEST(NerfstudioTransforms, TheAppliedTransformTurnsYDownIntoZUp) {
  // A camera at the origin looking along COLMAP's +z, its image's down along the world's +y: in
  // nerfstudio's world (A = rows x, z, −y) it looks along +y and its up is +z.
  const Eigen::Matrix4d m = NerfstudioTransformMatrix(Rigid3d());
  const Eigen::Vector3d looking = -m.block<3, 1>(0, 2);  // OpenGL cameras look along −z
  const Eigen::Vector3d up = m.block<3, 1>(0, 1);
  EXPECT_LT((looking - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  EXPECT_LT((up - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
}

TEST(NerfstudioTransforms, AModelWithoutRegisteredImagesIsRefused) {
  Reconstruction empty;
  empty.AddCamera(Camera::FromImageSize(640, 480));
  EXPECT_THROW(NerfstudioTransforms(empty, 0, 0, [](const Image&) { return std::string(); }),
               Error);
}

}  // namespace
}  // namespace comic::sfm
