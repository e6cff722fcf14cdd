// A sparse reconstruction: cameras (intrinsics), images (poses cam_from_world and their 2-D
// points), and 3-D points with their tracks of observations and colours. Pixel coordinates follow
// OpenCV's convention (top-left pixel centre at (0, 0)); the COLMAP conversion shifts by 0.5.
//
//   Reconstruction reconstruction;
//   const camera_t camera_id = reconstruction.AddCamera(camera);
//   reconstruction.AddImage(image);          // with its points2D, not yet registered
//   reconstruction.RegisterImage(image_id);  // once its pose is known
//   reconstruction.AddPoint3D(xyz, {{image_id1, idx1}, {image_id2, idx2}});
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sfm/camera.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

using camera_t = uint32_t;
using image_t = uint32_t;
using point2D_t = uint32_t;
using point3D_t = uint64_t;

inline constexpr point3D_t kInvalidPoint3DId = std::numeric_limits<point3D_t>::max();

struct Point2D {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // pixels, OpenCV convention
  point3D_t point3D_id = kInvalidPoint3DId;      // the 3-D point it observes, if any

  bool HasPoint3D() const { return point3D_id != kInvalidPoint3DId; }
};

struct TrackElement {
  image_t image_id = 0;
  point2D_t point2D_idx = 0;

  bool operator==(const TrackElement& other) const {
    return image_id == other.image_id && point2D_idx == other.point2D_idx;
  }
};

struct Point3D {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // point3D_in_world
  std::array<uint8_t, 3> color = {0, 0, 0};       // RGB
  double error = -1.0;                            // mean reprojection error, pixels (-1: unknown)
  std::vector<TrackElement> track;                // observations, at most one per image
};

struct Image {
  image_t image_id = 0;
  camera_t camera_id = 0;
  std::string name;
  Rigid3d cam_from_world;
  bool registered = false;
  std::vector<Point2D> points2D;

  size_t NumPoints3D() const;
};

// Projects `point3D_in_world` to pixels. Returns std::nullopt when the point is not in front of
// the camera (depth <= 1e-12 in camera units).
std::optional<Eigen::Vector2d> ProjectPoint(const Camera& camera, const Rigid3d& cam_from_world,
                                            const Eigen::Vector3d& point3D_in_world);

class Reconstruction {
 public:
  // Adds a camera with a fresh id (1, 2, ...) or the given non-zero one (must be new) and returns
  // its id. Throws comic::Error for an invalid camera or a used id.
  camera_t AddCamera(const Camera& camera, camera_t camera_id = 0);
  // Adds an image with a fresh id (image.image_id == 0) or its own (must be new); its camera must
  // exist and its points2D must not reference 3-D points yet. Returns the id.
  image_t AddImage(Image image);
  // Adds a 3-D point observed by `track` (each element an existing image and point2D without a
  // 3-D point, at most one per image) and links the 2-D points to it. The id is fresh, or the
  // given one (must be new). Returns the id.
  point3D_t AddPoint3D(const Eigen::Vector3d& xyz, const std::vector<TrackElement>& track,
                       const std::array<uint8_t, 3>& color = {0, 0, 0},
                       point3D_t point3D_id = kInvalidPoint3DId);
  // Adds one observation to an existing point (the image must not observe it already).
  void AddObservation(point3D_t point3D_id, const TrackElement& element);
  // Removes one observation; the point is deleted when fewer than two observations remain.
  void DeleteObservation(image_t image_id, point2D_t point2D_idx);
  // Removes a point and unlinks its observations.
  void DeletePoint3D(point3D_t point3D_id);

  // A 2-D point linked to (`linked`) or unlinked from a 3-D point.
  struct LinkChange {
    TrackElement element;
    bool linked = false;
  };
  // From now on every link and unlink of a 2-D point, implicit ones included (a point deleted
  // with its last observations), is recorded in order until TakeLinkChanges(): the owner of a
  // growing model keeps counts over it current without walking every point after every change
  // (IncrementalMapper::NextImageCandidates).
  // RecordLinkChanges(false) stops and drops what was recorded.
  void RecordLinkChanges(bool record) {
    record_link_changes_ = record;
    if (!record) link_changes_ = {};
  }
  // The changes recorded since the last call, oldest first.
  std::vector<LinkChange> TakeLinkChanges() { return std::exchange(link_changes_, {}); }

  void RegisterImage(image_t image_id);
  // Marks the image unregistered and removes all its observations.
  void DeRegisterImage(image_t image_id);

  bool ExistsCamera(camera_t id) const { return cameras_.count(id) > 0; }
  bool ExistsImage(image_t id) const { return images_.count(id) > 0; }
  bool ExistsPoint3D(point3D_t id) const { return points3D_.count(id) > 0; }

  // Accessors throw comic::Error(kInvalidArgument) for an unknown id.
  const Camera& camera(camera_t id) const;
  Camera& camera(camera_t id);
  const Image& image(image_t id) const;
  Image& image(image_t id);
  const Point3D& point3D(point3D_t id) const;
  Point3D& point3D(point3D_t id);

  // Ordered by id, so every loop over them is deterministic.
  const std::map<camera_t, Camera>& cameras() const { return cameras_; }
  const std::map<image_t, Image>& images() const { return images_; }
  const std::map<point3D_t, Point3D>& points3D() const { return points3D_; }

  size_t NumImages() const { return images_.size(); }
  size_t NumRegisteredImages() const;
  std::vector<image_t> RegisteredImageIds() const;  // ascending
  size_t NumPoints3D() const { return points3D_.size(); }
  size_t NumObservations() const;
  // Observations per 3-D point (0 when there are no points).
  double ComputeMeanTrackLength() const;
  // Mean over all observations of the reprojection error in pixels (0 when there are none).
  double ComputeMeanReprojectionError() const;

  // Reprojection error in pixels of one observation of a registered image;
  // +infinity when the point is behind the camera.
  double ReprojectionError(image_t image_id, point2D_t point2D_idx) const;
  // Sets Point3D::error of every point to the mean reprojection error of its observations.
  void UpdatePoint3DErrors();

 private:
  std::map<camera_t, Camera> cameras_;
  std::map<image_t, Image> images_;
  std::map<point3D_t, Point3D> points3D_;
  camera_t next_camera_id_ = 1;
  image_t next_image_id_ = 1;
  point3D_t next_point3D_id_ = 1;
  bool record_link_changes_ = false;
  std::vector<LinkChange> link_changes_;

  // Links (or with kInvalidPoint3DId unlinks) one 2-D point of `image`, recording the change.
  void SetPoint3DId(Image& image, point2D_t point2D_idx, point3D_t point3D_id);
};

}  // namespace comic::sfm
