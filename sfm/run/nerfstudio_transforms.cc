#include "sfm/run/nerfstudio_transforms.h"

#include <set>

#include "io/core/error.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

namespace {

nlohmann::json Rows(const Eigen::MatrixXd& matrix) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < matrix.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < matrix.cols(); ++c) row.push_back(matrix(r, c));
    rows.push_back(row);
  }
  return rows;
}

// nerfstudio reads every model of ours as OPENCV: the parameters a model lacks are 0, one focal
// length is both.
void AddCamera(const Camera& camera, nlohmann::json* json) {
  (*json)["camera_model"] = "OPENCV";
  (*json)["fl_x"] = camera.fx;
  (*json)["fl_y"] = camera.fy;
  (*json)["cx"] = camera.cx + kColmapPixelOffset;
  (*json)["cy"] = camera.cy + kColmapPixelOffset;
  (*json)["w"] = camera.width;
  (*json)["h"] = camera.height;
  (*json)["k1"] = camera.k1;
  (*json)["k2"] = camera.k2;
  (*json)["p1"] = camera.p1;
  (*json)["p2"] = camera.p2;
}

}  // namespace

Eigen::Matrix3d NerfstudioAppliedTransform() {
  Eigen::Matrix3d applied;
  applied << 1, 0, 0,  //
      0, 0, 1,         //
      0, -1, 0;
  return applied;
}

Eigen::Matrix4d NerfstudioTransformMatrix(const Rigid3d& cam_from_world) {
  const Rigid3d world_from_cam = cam_from_world.Inverse();
  Eigen::Matrix4d c2w = Eigen::Matrix4d::Identity();
  c2w.topLeftCorner<3, 3>() = world_from_cam.RotationMatrix();
  c2w.topRightCorner<3, 1>() = world_from_cam.translation;
  c2w.block<3, 2>(0, 1) *= -1.0;
  Eigen::Matrix4d applied = Eigen::Matrix4d::Identity();
  applied.topLeftCorner<3, 3>() = NerfstudioAppliedTransform();
  return applied * c2w;
}

nlohmann::json NerfstudioTransforms(const Reconstruction& reconstruction, int width, int height,
                                    const std::function<std::string(const Image&)>& file_path) {
  const std::vector<image_t> registered = reconstruction.RegisteredImageIds();
  COMIC_CHECK(!registered.empty(), kInvalidArgument,
              "transforms.json: the model has no registered image");
  const auto camera_of = [&](const Image& image) {
    const Camera& camera = reconstruction.camera(image.camera_id);
    return width > 0 && height > 0 ? ResizedCamera(camera, width, height) : camera;
  };
  std::set<camera_t> cameras;
  for (image_t id : registered) cameras.insert(reconstruction.image(id).camera_id);
  nlohmann::json json = nlohmann::json::object();
  const bool one_camera = cameras.size() == 1;
  if (one_camera) AddCamera(camera_of(reconstruction.image(registered.front())), &json);
  json["frames"] = nlohmann::json::array();
  for (image_t id : registered) {
    const Image& image = reconstruction.image(id);
    nlohmann::json frame = {
        {"file_path", file_path(image)},
        {"transform_matrix", Rows(NerfstudioTransformMatrix(image.cam_from_world))},
        {"colmap_im_id", id}};
    if (!one_camera) AddCamera(camera_of(image), &frame);
    json["frames"].push_back(frame);
  }
  Eigen::Matrix<double, 3, 4> applied = Eigen::Matrix<double, 3, 4>::Zero();
  applied.leftCols<3>() = NerfstudioAppliedTransform();
  json["applied_transform"] = Rows(applied);
  return json;
}

}  // namespace comic::sfm
