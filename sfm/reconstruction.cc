#include "sfm/reconstruction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/core/error.h"

namespace comic::sfm {

size_t Image::NumPoints3D() const {
  return static_cast<size_t>(std::count_if(points2D.begin(), points2D.end(),
                                           [](const Point2D& p) { return p.HasPoint3D(); }));
}

std::optional<Eigen::Vector2d> ProjectPoint(const Camera& camera, const Rigid3d& cam_from_world,
                                            const Eigen::Vector3d& point3D_in_world) {
  const Eigen::Vector3d point_in_cam = cam_from_world * point3D_in_world;
  if (point_in_cam.z() <= 1e-12) return std::nullopt;
  if (!camera.HasDistortion()) {  // the pinhole path, kept as it was (same rounding)
    return Eigen::Vector2d(camera.fx * point_in_cam.x() / point_in_cam.z() + camera.cx,
                           camera.fy * point_in_cam.y() / point_in_cam.z() + camera.cy);
  }
  return camera.ImageFromCam(
      Eigen::Vector2d(point_in_cam.x() / point_in_cam.z(), point_in_cam.y() / point_in_cam.z()));
}

camera_t Reconstruction::AddCamera(const Camera& camera, camera_t camera_id) {
  camera.Check();
  if (camera_id == 0) camera_id = next_camera_id_;
  COMIC_CHECK(cameras_.count(camera_id) == 0, kInvalidArgument,
              "reconstruction: camera id " << camera_id << " already exists");
  cameras_[camera_id] = camera;
  next_camera_id_ = std::max(next_camera_id_, camera_id + 1);
  return camera_id;
}

image_t Reconstruction::AddImage(Image image) {
  if (image.image_id == 0) image.image_id = next_image_id_;
  COMIC_CHECK(images_.count(image.image_id) == 0, kInvalidArgument,
              "reconstruction: image id " << image.image_id << " already exists");
  COMIC_CHECK(
      cameras_.count(image.camera_id) > 0, kInvalidArgument,
      "reconstruction: image " << image.image_id << " uses unknown camera " << image.camera_id);
  for (const Point2D& point2D : image.points2D) {
    COMIC_CHECK(!point2D.HasPoint3D(), kInvalidArgument,
                "reconstruction: a new image's points2D must not reference 3-D points");
  }
  const image_t id = image.image_id;
  next_image_id_ = std::max(next_image_id_, id + 1);
  images_.emplace(id, std::move(image));
  return id;
}

point3D_t Reconstruction::AddPoint3D(const Eigen::Vector3d& xyz,
                                     const std::vector<TrackElement>& track,
                                     const std::array<uint8_t, 3>& color, point3D_t point3D_id) {
  if (point3D_id == kInvalidPoint3DId) point3D_id = next_point3D_id_;
  COMIC_CHECK(points3D_.count(point3D_id) == 0, kInvalidArgument,
              "reconstruction: point3D id " << point3D_id << " already exists");
  // Validate the whole track before linking anything, so a bad track leaves no trace.
  for (size_t i = 0; i < track.size(); ++i) {
    const Image& img = image(track[i].image_id);
    COMIC_CHECK(track[i].point2D_idx < img.points2D.size(), kInvalidArgument,
                "reconstruction: point2D " << track[i].point2D_idx << " out of range in image "
                                           << img.image_id);
    COMIC_CHECK(!img.points2D[track[i].point2D_idx].HasPoint3D(), kInvalidArgument,
                "reconstruction: point2D " << track[i].point2D_idx << " of image " << img.image_id
                                           << " already observes a 3-D point");
    for (size_t j = 0; j < i; ++j) {
      COMIC_CHECK(track[j].image_id != track[i].image_id, kInvalidArgument,
                  "reconstruction: a track observes image " << img.image_id << " twice");
    }
  }
  Point3D point;
  point.xyz = xyz;
  point.color = color;
  point.track = track;
  for (const TrackElement& element : track) {
    SetPoint3DId(images_.at(element.image_id), element.point2D_idx, point3D_id);
  }
  points3D_.emplace(point3D_id, std::move(point));
  next_point3D_id_ = std::max(next_point3D_id_, point3D_id + 1);
  return point3D_id;
}

void Reconstruction::AddObservation(point3D_t point3D_id, const TrackElement& element) {
  Point3D& point = point3D(point3D_id);
  Image& img = image(element.image_id);
  COMIC_CHECK(element.point2D_idx < img.points2D.size(), kInvalidArgument,
              "reconstruction: point2D " << element.point2D_idx << " out of range in image "
                                         << img.image_id);
  COMIC_CHECK(!img.points2D[element.point2D_idx].HasPoint3D(), kInvalidArgument,
              "reconstruction: point2D " << element.point2D_idx << " of image " << img.image_id
                                         << " already observes a 3-D point");
  for (const TrackElement& existing : point.track) {
    COMIC_CHECK(
        existing.image_id != element.image_id, kInvalidArgument,
        "reconstruction: point " << point3D_id << " already observed in image " << img.image_id);
  }
  point.track.push_back(element);
  SetPoint3DId(img, element.point2D_idx, point3D_id);
}

void Reconstruction::DeleteObservation(image_t image_id, point2D_t point2D_idx) {
  Image& img = image(image_id);
  COMIC_CHECK(
      point2D_idx < img.points2D.size() && img.points2D[point2D_idx].HasPoint3D(), kInvalidArgument,
      "reconstruction: image " << image_id << " point2D " << point2D_idx << " has no 3-D point");
  const point3D_t point3D_id = img.points2D[point2D_idx].point3D_id;
  Point3D& point = points3D_.at(point3D_id);
  if (point.track.size() <= 2) {
    DeletePoint3D(point3D_id);
    return;
  }
  point.track.erase(
      std::remove(point.track.begin(), point.track.end(), TrackElement{image_id, point2D_idx}),
      point.track.end());
  SetPoint3DId(img, point2D_idx, kInvalidPoint3DId);
}

void Reconstruction::DeletePoint3D(point3D_t point3D_id) {
  const Point3D& point = point3D(point3D_id);
  for (const TrackElement& element : point.track) {
    SetPoint3DId(images_.at(element.image_id), element.point2D_idx, kInvalidPoint3DId);
  }
  points3D_.erase(point3D_id);
}

void Reconstruction::SetPoint3DId(Image& image, point2D_t point2D_idx, point3D_t point3D_id) {
  image.points2D[point2D_idx].point3D_id = point3D_id;
  if (record_link_changes_) {
    link_changes_.push_back({{image.image_id, point2D_idx}, point3D_id != kInvalidPoint3DId});
  }
}

void Reconstruction::RegisterImage(image_t image_id) { image(image_id).registered = true; }

void Reconstruction::DeRegisterImage(image_t image_id) {
  Image& img = image(image_id);
  for (point2D_t idx = 0; idx < img.points2D.size(); ++idx) {
    if (img.points2D[idx].HasPoint3D()) DeleteObservation(image_id, idx);
  }
  img.registered = false;
}

const Camera& Reconstruction::camera(camera_t id) const {
  const auto it = cameras_.find(id);
  COMIC_CHECK(it != cameras_.end(), kInvalidArgument, "reconstruction: no camera " << id);
  return it->second;
}

Camera& Reconstruction::camera(camera_t id) {
  return const_cast<Camera&>(static_cast<const Reconstruction*>(this)->camera(id));
}

const Image& Reconstruction::image(image_t id) const {
  const auto it = images_.find(id);
  COMIC_CHECK(it != images_.end(), kInvalidArgument, "reconstruction: no image " << id);
  return it->second;
}

Image& Reconstruction::image(image_t id) {
  return const_cast<Image&>(static_cast<const Reconstruction*>(this)->image(id));
}

const Point3D& Reconstruction::point3D(point3D_t id) const {
  const auto it = points3D_.find(id);
  COMIC_CHECK(it != points3D_.end(), kInvalidArgument, "reconstruction: no point3D " << id);
  return it->second;
}

Point3D& Reconstruction::point3D(point3D_t id) {
  return const_cast<Point3D&>(static_cast<const Reconstruction*>(this)->point3D(id));
}

size_t Reconstruction::NumRegisteredImages() const {
  size_t count = 0;
  for (const auto& [id, img] : images_) count += img.registered;
  return count;
}

std::vector<image_t> Reconstruction::RegisteredImageIds() const {
  std::vector<image_t> ids;
  for (const auto& [id, img] : images_) {
    if (img.registered) ids.push_back(id);
  }
  return ids;
}

size_t Reconstruction::NumObservations() const {
  size_t count = 0;
  for (const auto& [id, point] : points3D_) count += point.track.size();
  return count;
}

double Reconstruction::ComputeMeanTrackLength() const {
  if (points3D_.empty()) return 0.0;
  return static_cast<double>(NumObservations()) / static_cast<double>(points3D_.size());
}

double Reconstruction::ComputeMeanReprojectionError() const {
  double sum = 0.0;
  size_t count = 0;
  for (const auto& [id, point] : points3D_) {
    for (const TrackElement& element : point.track) {
      sum += ReprojectionError(element.image_id, element.point2D_idx);
      ++count;
    }
  }
  return count == 0 ? 0.0 : sum / static_cast<double>(count);
}

double Reconstruction::ReprojectionError(image_t image_id, point2D_t point2D_idx) const {
  const Image& img = image(image_id);
  COMIC_CHECK(
      point2D_idx < img.points2D.size() && img.points2D[point2D_idx].HasPoint3D(), kInvalidArgument,
      "reconstruction: image " << image_id << " point2D " << point2D_idx << " has no 3-D point");
  const Point2D& point2D = img.points2D[point2D_idx];
  const auto projection =
      ProjectPoint(camera(img.camera_id), img.cam_from_world, points3D_.at(point2D.point3D_id).xyz);
  if (!projection) return std::numeric_limits<double>::infinity();
  return (*projection - point2D.xy).norm();
}

void Reconstruction::UpdatePoint3DErrors() {
  for (auto& [id, point] : points3D_) {
    double sum = 0.0;
    for (const TrackElement& element : point.track) {
      sum += ReprojectionError(element.image_id, element.point2D_idx);
    }
    point.error = point.track.empty() ? -1.0 : sum / static_cast<double>(point.track.size());
  }
}

}  // namespace comic::sfm
