#include "io/colmap/colmap_binary_model.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <sstream>
#include <type_traits>

#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::io {
namespace {

struct CameraModelInfo {
  const char* name;
  int id;
  int num_params;
};

// COLMAP's camera models (src/base/camera_models.h), in its id order.
constexpr CameraModelInfo kCameraModels[] = {{"SIMPLE_PINHOLE", 0, 3},
                                             {"PINHOLE", 1, 4},
                                             {"SIMPLE_RADIAL", 2, 4},
                                             {"RADIAL", 3, 5},
                                             {"OPENCV", 4, 8},
                                             {"OPENCV_FISHEYE", 5, 8},
                                             {"FULL_OPENCV", 6, 12},
                                             {"FOV", 7, 5},
                                             {"SIMPLE_RADIAL_FISHEYE", 8, 4},
                                             {"RADIAL_FISHEYE", 9, 5},
                                             {"THIN_PRISM_FISHEYE", 10, 12}};

const CameraModelInfo* FindModelByName(const std::string& name) {
  for (const CameraModelInfo& info : kCameraModels) {
    if (name == info.name) return &info;
  }
  return nullptr;
}

const CameraModelInfo* FindModelById(int64_t id) {
  for (const CameraModelInfo& info : kCameraModels) {
    if (id == info.id) return &info;
  }
  return nullptr;
}

// COLMAP marks a 2-D point without a 3-D point with point3D_t's largest value.
constexpr uint64_t kInvalidPoint3DId = std::numeric_limits<uint64_t>::max();

// Writes values to a stream little-endian, whatever the host's byte order.
class LittleEndianWriter {
 public:
  explicit LittleEndianWriter(std::ostream& out) : out_(out) {}
  template <typename T>
  void Put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (!HostIsLittleEndian()) std::reverse(bytes, bytes + sizeof(T));
    out_.write(reinterpret_cast<const char*>(bytes), sizeof(T));
  }
  void PutString(const std::string& text) { out_.write(text.c_str(), text.size() + 1); }

 private:
  static bool HostIsLittleEndian() {
    const uint16_t one = 1;
    uint8_t first;
    std::memcpy(&first, &one, 1);
    return first == 1;
  }
  std::ostream& out_;
};

// The bytes `write` puts on a stream.
template <typename Write>
std::string BytesOf(const ColmapTextModel& model, Write write) {
  std::ostringstream out;
  write(model, out);
  return out.str();
}

// Reads values little-endian from a file's bytes; every read past the end throws
// comic::Error(kInvalidData) naming the file and the offset.
class LittleEndianReader {
 public:
  LittleEndianReader(std::string path, std::string bytes)
      : path_(std::move(path)), bytes_(std::move(bytes)) {}

  template <typename T>
  T Get(const char* what) {
    static_assert(std::is_arithmetic_v<T>);
    Need(sizeof(T), what);
    uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, bytes_.data() + offset_, sizeof(T));
    const uint16_t one = 1;
    uint8_t first;
    std::memcpy(&first, &one, 1);
    if (first != 1) std::reverse(bytes, bytes + sizeof(T));
    offset_ += sizeof(T);
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  std::string GetString(const char* what) {
    const size_t end = bytes_.find('\0', offset_);
    COMIC_CHECK(end != std::string::npos, kInvalidData,
                path_ << ": truncated at byte " << offset_ << " (" << what << ")");
    std::string text = bytes_.substr(offset_, end - offset_);
    offset_ = end + 1;
    return text;
  }

  // A count of records of at least `min_record_bytes` each: rejects counts the rest of the file
  // cannot hold, so that a corrupt count fails cleanly instead of allocating without bound.
  uint64_t GetCount(size_t min_record_bytes, const char* what) {
    const uint64_t count = Get<uint64_t>(what);
    COMIC_CHECK(min_record_bytes == 0 || count <= (bytes_.size() - offset_) / min_record_bytes,
                kInvalidData,
                path_ << ": " << what << " " << count << " at byte " << offset_ - 8
                      << " is more than the file holds");
    return count;
  }

  void ExpectEnd() const {
    COMIC_CHECK(offset_ == bytes_.size(), kInvalidData,
                path_ << ": " << bytes_.size() - offset_ << " bytes left over after the data");
  }
  const std::string& path() const { return path_; }

 private:
  void Need(size_t size, const char* what) const {
    COMIC_CHECK(bytes_.size() - offset_ >= size, kInvalidData,
                path_ << ": truncated at byte " << offset_ << " (" << what << ")");
  }
  std::string path_;
  std::string bytes_;
  size_t offset_ = 0;
};

}  // namespace

int ColmapCameraModelId(const std::string& model_name) {
  const CameraModelInfo* info = FindModelByName(model_name);
  COMIC_CHECK(info != nullptr, kInvalidArgument,
              "unknown COLMAP camera model '" << model_name << "'");
  return info->id;
}

int ColmapCameraModelNumParams(const std::string& model_name) {
  const CameraModelInfo* info = FindModelByName(model_name);
  COMIC_CHECK(info != nullptr, kInvalidArgument,
              "unknown COLMAP camera model '" << model_name << "'");
  return info->num_params;
}

void WriteColmapCamerasBinary(const ColmapTextModel& model, std::ostream& stream) {
  LittleEndianWriter out(stream);
  out.Put<uint64_t>(model.cameras.size());
  for (const ColmapCamera& camera : model.cameras) {
    const CameraModelInfo* info = FindModelByName(camera.model);
    COMIC_CHECK(info != nullptr, kInvalidData,
                "COLMAP model: camera " << camera.camera_id << " has unknown model '"
                                        << camera.model << "'");
    COMIC_CHECK(static_cast<int>(camera.params.size()) == info->num_params, kInvalidData,
                "COLMAP model: camera " << camera.camera_id << " (" << camera.model << ") has "
                                        << camera.params.size() << " parameters, expected "
                                        << info->num_params);
    COMIC_CHECK(camera.width >= 0 && camera.height >= 0, kInvalidData,
                "COLMAP model: camera " << camera.camera_id << " has a negative size");
    out.Put<uint32_t>(camera.camera_id);
    out.Put<int32_t>(info->id);
    out.Put<uint64_t>(static_cast<uint64_t>(camera.width));
    out.Put<uint64_t>(static_cast<uint64_t>(camera.height));
    for (const double param : camera.params) out.Put<double>(param);
  }
}

void WriteColmapImagesBinary(const ColmapTextModel& model, std::ostream& stream) {
  LittleEndianWriter out(stream);
  out.Put<uint64_t>(model.images.size());
  for (const ColmapImage& image : model.images) {
    out.Put<uint32_t>(image.image_id);
    const Eigen::Quaterniond& q = image.cam_from_world_rotation;
    for (const double v : {q.w(), q.x(), q.y(), q.z()}) out.Put<double>(v);
    for (int i = 0; i < 3; ++i) out.Put<double>(image.cam_from_world_translation[i]);
    out.Put<uint32_t>(image.camera_id);
    out.PutString(image.name);
    out.Put<uint64_t>(image.points2D.size());
    for (const ColmapPoint2D& point : image.points2D) {
      out.Put<double>(point.x);
      out.Put<double>(point.y);
      out.Put<uint64_t>(point.point3D_id < 0 ? kInvalidPoint3DId
                                             : static_cast<uint64_t>(point.point3D_id));
    }
  }
}

void WriteColmapPoints3DBinary(const ColmapTextModel& model, std::ostream& stream) {
  LittleEndianWriter out(stream);
  out.Put<uint64_t>(model.points3D.size());
  for (const ColmapPoint3D& point : model.points3D) {
    out.Put<uint64_t>(point.point3D_id);
    for (int i = 0; i < 3; ++i) out.Put<double>(point.xyz[i]);
    for (const uint8_t channel : point.rgb) out.Put<uint8_t>(channel);
    out.Put<double>(point.error);
    out.Put<uint64_t>(point.track.size());
    for (const ColmapTrackElement& element : point.track) {
      out.Put<uint32_t>(element.image_id);
      out.Put<uint32_t>(element.point2D_idx);
    }
  }
}

std::string ColmapCamerasBinary(const ColmapTextModel& model) {
  return BytesOf(model, WriteColmapCamerasBinary);
}

std::string ColmapImagesBinary(const ColmapTextModel& model) {
  return BytesOf(model, WriteColmapImagesBinary);
}

std::string ColmapPoints3DBinary(const ColmapTextModel& model) {
  return BytesOf(model, WriteColmapPoints3DBinary);
}

void WriteColmapBinaryModel(const ColmapTextModel& model, const std::string& folder) {
  model.Check();
  EnsureWritableDirectory(folder);
  // Streamed, all three on disk before the first rename: a camera that cannot be written
  // (unknown model) or a full disk leaves the old model whole.
  auto file = [&](const char* name, void (*write)(const ColmapTextModel&, std::ostream&)) {
    return StreamedFile{JoinPaths(folder, name),
                        [&model, write](std::ostream& out) { write(model, out); }};
  };
  WriteFilesAtomically({file("cameras.bin", WriteColmapCamerasBinary),
                        file("images.bin", WriteColmapImagesBinary),
                        file("points3D.bin", WriteColmapPoints3DBinary)});
}

ColmapTextModel ReadColmapBinaryModel(const std::string& folder) {
  ColmapTextModel model;
  {
    const std::string path = JoinPaths(folder, "cameras.bin");
    LittleEndianReader in(path, ReadFileToString(path));
    const uint64_t count = in.GetCount(4 + 4 + 8 + 8, "camera count");
    model.cameras.reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      ColmapCamera camera;
      camera.camera_id = in.Get<uint32_t>("camera id");
      const int32_t model_id = in.Get<int32_t>("camera model id");
      const CameraModelInfo* info = FindModelById(model_id);
      COMIC_CHECK(info != nullptr, kInvalidData,
                  path << ": camera " << camera.camera_id << " has unknown model id " << model_id);
      camera.model = info->name;
      const uint64_t width = in.Get<uint64_t>("camera width");
      const uint64_t height = in.Get<uint64_t>("camera height");
      COMIC_CHECK(width <= static_cast<uint64_t>(std::numeric_limits<int>::max()) &&
                      height <= static_cast<uint64_t>(std::numeric_limits<int>::max()),
                  kInvalidData, path << ": camera " << camera.camera_id << " has a bad size");
      camera.width = static_cast<int>(width);
      camera.height = static_cast<int>(height);
      for (int p = 0; p < info->num_params; ++p) {
        camera.params.push_back(in.Get<double>("camera parameter"));
      }
      model.cameras.push_back(std::move(camera));
    }
    in.ExpectEnd();
  }
  {
    const std::string path = JoinPaths(folder, "images.bin");
    LittleEndianReader in(path, ReadFileToString(path));
    const uint64_t count = in.GetCount(4 + 7 * 8 + 4 + 1 + 8, "image count");
    model.images.reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      ColmapImage image;
      image.image_id = in.Get<uint32_t>("image id");
      const double qw = in.Get<double>("quaternion");
      const double qx = in.Get<double>("quaternion");
      const double qy = in.Get<double>("quaternion");
      const double qz = in.Get<double>("quaternion");
      image.cam_from_world_rotation = Eigen::Quaterniond(qw, qx, qy, qz);
      for (int k = 0; k < 3; ++k) {
        image.cam_from_world_translation[k] = in.Get<double>("translation");
      }
      image.camera_id = in.Get<uint32_t>("image camera id");
      image.name = in.GetString("image name");
      const uint64_t num_points = in.GetCount(8 + 8 + 8, "2-D point count");
      image.points2D.reserve(num_points);
      for (uint64_t p = 0; p < num_points; ++p) {
        ColmapPoint2D point;
        point.x = in.Get<double>("2-D point");
        point.y = in.Get<double>("2-D point");
        const uint64_t id = in.Get<uint64_t>("2-D point's 3-D point id");
        COMIC_CHECK(id == kInvalidPoint3DId ||
                        id <= static_cast<uint64_t>(std::numeric_limits<int64_t>::max()),
                    kInvalidData, path << ": image " << image.image_id << " has a bad point id");
        point.point3D_id = id == kInvalidPoint3DId ? -1 : static_cast<int64_t>(id);
        image.points2D.push_back(point);
      }
      model.images.push_back(std::move(image));
    }
    in.ExpectEnd();
  }
  {
    const std::string path = JoinPaths(folder, "points3D.bin");
    LittleEndianReader in(path, ReadFileToString(path));
    const uint64_t count = in.GetCount(8 + 3 * 8 + 3 + 8 + 8, "3-D point count");
    model.points3D.reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      ColmapPoint3D point;
      point.point3D_id = in.Get<uint64_t>("3-D point id");
      for (int k = 0; k < 3; ++k) point.xyz[k] = in.Get<double>("3-D point position");
      for (uint8_t& channel : point.rgb) channel = in.Get<uint8_t>("3-D point colour");
      point.error = in.Get<double>("3-D point error");
      const uint64_t track_length = in.GetCount(4 + 4, "track length");
      point.track.reserve(track_length);
      for (uint64_t t = 0; t < track_length; ++t) {
        ColmapTrackElement element;
        element.image_id = in.Get<uint32_t>("track image id");
        element.point2D_idx = in.Get<uint32_t>("track 2-D point index");
        point.track.push_back(element);
      }
      model.points3D.push_back(std::move(point));
    }
    in.ExpectEnd();
  }
  model.Check();
  return model;
}

}  // namespace comic::io
