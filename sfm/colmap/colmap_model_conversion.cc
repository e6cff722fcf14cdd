#include "sfm/colmap/colmap_model_conversion.h"

#include <algorithm>

#include "io/core/error.h"

namespace comic::sfm {

io::ColmapTextModel ToColmapTextModel(const Reconstruction& reconstruction) {
  io::ColmapTextModel model;
  for (const auto& [camera_id, camera] : reconstruction.cameras()) {
    io::ColmapCamera colmap_camera;
    colmap_camera.camera_id = camera_id;
    colmap_camera.model = CameraModelName(camera.model);
    colmap_camera.width = camera.width;
    colmap_camera.height = camera.height;
    colmap_camera.params = camera.Params();
    // COLMAP's pixel convention for the principal point; focal and distortion are unchanged.
    const int pp = CameraModelPrincipalPointIndex(camera.model);
    colmap_camera.params[pp] += kColmapPixelOffset;
    colmap_camera.params[pp + 1] += kColmapPixelOffset;
    model.cameras.push_back(colmap_camera);
  }
  for (const auto& [image_id, image] : reconstruction.images()) {
    if (!image.registered) continue;
    io::ColmapImage colmap_image;
    colmap_image.image_id = image_id;
    colmap_image.camera_id = image.camera_id;
    colmap_image.name = image.name;
    colmap_image.cam_from_world_rotation = image.cam_from_world.rotation.normalized();
    colmap_image.cam_from_world_translation = image.cam_from_world.translation;
    colmap_image.points2D.reserve(image.points2D.size());
    for (const Point2D& point2D : image.points2D) {
      io::ColmapPoint2D colmap_point;
      colmap_point.x = point2D.xy.x() + kColmapPixelOffset;
      colmap_point.y = point2D.xy.y() + kColmapPixelOffset;
      colmap_point.point3D_id =
          point2D.HasPoint3D() ? static_cast<int64_t>(point2D.point3D_id) : int64_t{-1};
      colmap_image.points2D.push_back(colmap_point);
    }
    model.images.push_back(std::move(colmap_image));
  }
  for (const auto& [point3D_id, point] : reconstruction.points3D()) {
    io::ColmapPoint3D colmap_point;
    colmap_point.point3D_id = point3D_id;
    colmap_point.xyz = point.xyz;
    colmap_point.rgb = point.color;
    double error_sum = 0.0;
    for (const TrackElement& element : point.track) {
      COMIC_CHECK(reconstruction.image(element.image_id).registered, kInvalidArgument,
                  "COLMAP export: point " << point3D_id << " is observed in unregistered image "
                                          << element.image_id);
      colmap_point.track.push_back({element.image_id, element.point2D_idx});
      error_sum += reconstruction.ReprojectionError(element.image_id, element.point2D_idx);
    }
    colmap_point.error =
        point.track.empty() ? 0.0 : error_sum / static_cast<double>(point.track.size());
    model.points3D.push_back(std::move(colmap_point));
  }
  return model;
}

namespace {

Camera CameraFromColmap(const io::ColmapCamera& colmap_camera, bool ignore_distortion) {
  const auto model = CameraModelFromName(colmap_camera.model);
  COMIC_CHECK(model.has_value(), kInvalidData,
              "COLMAP camera " << colmap_camera.camera_id << ": unsupported camera model "
                               << colmap_camera.model << " (supported: " << CameraModelNames()
                               << ")");
  std::vector<double> p = colmap_camera.params;
  COMIC_CHECK(static_cast<int>(p.size()) == CameraModelNumParams(*model), kInvalidData,
              "COLMAP camera " << colmap_camera.camera_id << " (" << colmap_camera.model << ") has "
                               << p.size() << " parameters, expected "
                               << CameraModelNumParams(*model));
  const int pp = CameraModelPrincipalPointIndex(*model);
  p[pp] -= kColmapPixelOffset;
  p[pp + 1] -= kColmapPixelOffset;
  // ignore_distortion: the model's distortion is dropped (the pinhole part only, e.g. to compare
  // poses with a reference whose images were undistorted).
  if (ignore_distortion) std::fill(p.begin() + pp + 2, p.end(), 0.0);
  try {
    return Camera::FromParams(*model, colmap_camera.width, colmap_camera.height, p);
  } catch (const Error& error) {
    throw Error(ErrorKind::kInvalidData,
                "COLMAP camera " + std::to_string(colmap_camera.camera_id) + ": " + error.what());
  }
}

}  // namespace

Reconstruction FromColmapTextModel(const io::ColmapTextModel& model, bool ignore_distortion) {
  model.Check();
  Reconstruction reconstruction;
  for (const io::ColmapCamera& colmap_camera : model.cameras) {
    COMIC_CHECK(colmap_camera.camera_id != 0, kInvalidData, "COLMAP camera id 0 is not valid");
    reconstruction.AddCamera(CameraFromColmap(colmap_camera, ignore_distortion),
                             colmap_camera.camera_id);
  }
  for (const io::ColmapImage& colmap_image : model.images) {
    COMIC_CHECK(colmap_image.image_id != 0, kInvalidData, "COLMAP image id 0 is not valid");
    Image image;
    image.image_id = colmap_image.image_id;
    image.camera_id = colmap_image.camera_id;
    image.name = colmap_image.name;
    image.cam_from_world = Rigid3d(colmap_image.cam_from_world_rotation.normalized(),
                                   colmap_image.cam_from_world_translation);
    image.registered = true;
    for (const io::ColmapPoint2D& colmap_point : colmap_image.points2D) {
      Point2D point2D;
      point2D.xy =
          Eigen::Vector2d(colmap_point.x - kColmapPixelOffset, colmap_point.y - kColmapPixelOffset);
      image.points2D.push_back(point2D);
    }
    reconstruction.AddImage(std::move(image));
  }
  for (const io::ColmapPoint3D& colmap_point : model.points3D) {
    COMIC_CHECK(colmap_point.point3D_id != kInvalidPoint3DId, kInvalidData,
                "COLMAP point id " << colmap_point.point3D_id << " is not valid");
    std::vector<TrackElement> track;
    for (const io::ColmapTrackElement& element : colmap_point.track) {
      track.push_back({element.image_id, element.point2D_idx});
    }
    try {
      reconstruction.AddPoint3D(colmap_point.xyz, track, colmap_point.rgb, colmap_point.point3D_id);
    } catch (const Error& error) {
      throw Error(ErrorKind::kInvalidData,
                  "COLMAP point " + std::to_string(colmap_point.point3D_id) + ": " + error.what());
    }
    reconstruction.point3D(colmap_point.point3D_id).error = colmap_point.error;
  }
  // The 2-D points' links to 3-D points must agree with the tracks.
  for (const io::ColmapImage& colmap_image : model.images) {
    const Image& image = reconstruction.image(colmap_image.image_id);
    for (size_t i = 0; i < colmap_image.points2D.size(); ++i) {
      const int64_t expected = colmap_image.points2D[i].point3D_id;
      const bool linked = image.points2D[i].HasPoint3D();
      COMIC_CHECK((expected < 0 && !linked) ||
                      (expected >= 0 && linked &&
                       image.points2D[i].point3D_id == static_cast<point3D_t>(expected)),
                  kInvalidData,
                  "COLMAP image " << colmap_image.image_id << " point2D " << i
                                  << ": its POINT3D_ID disagrees with the tracks in points3D.txt");
    }
  }
  return reconstruction;
}

}  // namespace comic::sfm
