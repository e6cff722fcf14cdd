#include "python/model_columns.h"

#include <pybind11/numpy.h>

#include <cstdint>

namespace comic::python {

py::dict ModelToColumns(const io::ColmapTextModel& model) {
  py::dict result;
  {
    const size_t n = model.cameras.size();
    py::array_t<uint32_t> id(n);
    py::array_t<int32_t> width(n), height(n);
    py::list names, params;
    for (size_t i = 0; i < n; ++i) {
      const io::ColmapCamera& c = model.cameras[i];
      id.mutable_at(i) = c.camera_id;
      width.mutable_at(i) = c.width;
      height.mutable_at(i) = c.height;
      names.append(c.model);
      params.append(py::array_t<double>(c.params.size(), c.params.data()));
    }
    py::dict cameras;
    cameras["camera_id"] = id;
    cameras["model"] = names;
    cameras["width"] = width;
    cameras["height"] = height;
    cameras["params"] = params;
    result["cameras"] = cameras;
  }
  {
    const size_t n = model.images.size();
    py::array_t<uint32_t> id(n), camera_id(n), num_points2D(n);
    py::array_t<double> qvec({static_cast<py::ssize_t>(n), py::ssize_t{4}});
    py::array_t<double> tvec({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    py::list names;
    size_t num_observations = 0;
    for (const io::ColmapImage& image : model.images) num_observations += image.points2D.size();
    py::array_t<uint32_t> obs_image(num_observations);
    py::array_t<double> obs_x(num_observations), obs_y(num_observations);
    py::array_t<int64_t> obs_point(num_observations);
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
      const io::ColmapImage& image = model.images[i];
      id.mutable_at(i) = image.image_id;
      camera_id.mutable_at(i) = image.camera_id;
      num_points2D.mutable_at(i) = static_cast<uint32_t>(image.points2D.size());
      const Eigen::Quaterniond& q = image.cam_from_world_rotation;
      qvec.mutable_at(i, 0) = q.w();
      qvec.mutable_at(i, 1) = q.x();
      qvec.mutable_at(i, 2) = q.y();
      qvec.mutable_at(i, 3) = q.z();
      for (int c = 0; c < 3; ++c) tvec.mutable_at(i, c) = image.cam_from_world_translation[c];
      names.append(image.name);
      for (const io::ColmapPoint2D& point : image.points2D) {
        obs_image.mutable_at(k) = image.image_id;
        obs_x.mutable_at(k) = point.x;
        obs_y.mutable_at(k) = point.y;
        obs_point.mutable_at(k) = point.point3D_id;
        ++k;
      }
    }
    py::dict images;
    images["image_id"] = id;
    images["camera_id"] = camera_id;
    images["qvec"] = qvec;
    images["tvec"] = tvec;
    images["name"] = names;
    images["num_points2D"] = num_points2D;
    result["images"] = images;
    py::dict points2D;
    points2D["image_id"] = obs_image;
    points2D["x"] = obs_x;
    points2D["y"] = obs_y;
    points2D["point3D_id"] = obs_point;
    result["points2D"] = points2D;
  }
  {
    const size_t n = model.points3D.size();
    py::array_t<uint64_t> id(n);
    py::array_t<double> xyz({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    py::array_t<uint8_t> rgb({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    py::array_t<double> error(n);
    py::array_t<uint32_t> track_length(n);
    for (size_t i = 0; i < n; ++i) {
      const io::ColmapPoint3D& p = model.points3D[i];
      id.mutable_at(i) = p.point3D_id;
      for (int c = 0; c < 3; ++c) {
        xyz.mutable_at(i, c) = p.xyz[c];
        rgb.mutable_at(i, c) = p.rgb[c];
      }
      error.mutable_at(i) = p.error;
      track_length.mutable_at(i) = static_cast<uint32_t>(p.track.size());
    }
    py::dict points;
    points["point3D_id"] = id;
    points["xyz"] = xyz;
    points["rgb"] = rgb;
    points["error"] = error;
    points["track_length"] = track_length;
    result["points3D"] = points;
  }
  return result;
}

}  // namespace comic::python
