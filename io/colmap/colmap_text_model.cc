#include "io/colmap/colmap_text_model.h"

#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::io {
namespace {

// Writes doubles with enough digits to read them back exactly while it lives, then restores
// the stream's precision.
class PreciseDoubles {
 public:
  explicit PreciseDoubles(std::ostream& out)
      : out_(out), precision_(out.precision(std::numeric_limits<double>::max_digits10)) {}
  ~PreciseDoubles() { out_.precision(precision_); }

 private:
  std::ostream& out_;
  std::streamsize precision_;
};

// The text `write` puts on a stream.
template <typename Write>
std::string TextOf(const ColmapTextModel& model, Write write) {
  std::ostringstream out;
  write(model, out);
  return out.str();
}

// Calls `parse(line_stream, line_number)` for every non-empty, non-comment line of a file, or,
// with `keep_empty`, for every non-comment line (images.txt has possibly empty 2-D point lines).
template <typename Parse>
void ForEachDataLine(const std::string& path, bool keep_empty, Parse parse) {
  std::istringstream in(ReadFileToString(path));
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && line[0] == '#') continue;
    if (!keep_empty && line.find_first_not_of(" \t") == std::string::npos) continue;
    std::istringstream fields(line);
    parse(fields, line_number);
  }
}

[[noreturn]] void Malformed(const std::string& path, int line_number, const std::string& what) {
  throw Error(ErrorKind::kInvalidData,
              path + ":" + std::to_string(line_number) + ": malformed line (" + what + ")");
}

// True if nothing but whitespace is left on the line.
bool AtEnd(std::istringstream& fields) {
  fields >> std::ws;
  return fields.eof();
}

}  // namespace

void CheckColmapImageName(const std::string& name, const std::string& what) {
  COMIC_CHECK(!name.empty() && name.find_first_of(" \t\r\n\v\f") == std::string::npos, kInvalidData,
              what << ": frame name '" << name
                   << "' is empty or holds whitespace, which a COLMAP model cannot hold (its "
                      "images.txt splits names at spaces); rename the frames, e.g. with '_'");
}

void ColmapTextModel::Check() const {
  std::set<uint32_t> camera_ids;
  for (const ColmapCamera& camera : cameras) {
    COMIC_CHECK(camera_ids.insert(camera.camera_id).second, kInvalidData,
                "COLMAP model: camera id " << camera.camera_id << " repeats");
    COMIC_CHECK(!camera.model.empty() && camera.model.find_first_of(" \t\n") == std::string::npos,
                kInvalidData,
                "COLMAP model: camera " << camera.camera_id << " has a bad model name");
  }
  std::map<uint32_t, size_t> num_points2D;
  for (const ColmapImage& image : images) {
    COMIC_CHECK(num_points2D.emplace(image.image_id, image.points2D.size()).second, kInvalidData,
                "COLMAP model: image id " << image.image_id << " repeats");
    COMIC_CHECK(
        camera_ids.count(image.camera_id), kInvalidData,
        "COLMAP model: image " << image.image_id << " names missing camera " << image.camera_id);
    COMIC_CHECK(!image.name.empty() && image.name.find_first_of(" \t\r\n") == std::string::npos,
                kInvalidData,
                "COLMAP model: image " << image.image_id << " name '" << image.name
                                       << "' is empty or holds whitespace");
  }
  std::set<uint64_t> point_ids;
  for (const ColmapPoint3D& point : points3D) {
    COMIC_CHECK(point_ids.insert(point.point3D_id).second, kInvalidData,
                "COLMAP model: 3-D point id " << point.point3D_id << " repeats");
    for (const ColmapTrackElement& element : point.track) {
      const auto it = num_points2D.find(element.image_id);
      COMIC_CHECK(it != num_points2D.end(), kInvalidData,
                  "COLMAP model: point " << point.point3D_id << " observed in missing image "
                                         << element.image_id);
      COMIC_CHECK(element.point2D_idx < it->second, kInvalidData,
                  "COLMAP model: point " << point.point3D_id << " names 2-D point "
                                         << element.point2D_idx << " of image " << element.image_id
                                         << ", which has " << it->second);
    }
  }
}

void WriteColmapCamerasText(const ColmapTextModel& model, std::ostream& out) {
  const PreciseDoubles precise(out);
  out << "# Camera list with one line of data per camera:\n"
      << "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
      << "# Number of cameras: " << model.cameras.size() << "\n";
  for (const ColmapCamera& camera : model.cameras) {
    out << camera.camera_id << " " << camera.model << " " << camera.width << " " << camera.height;
    for (double p : camera.params) out << " " << p;
    out << "\n";
  }
}

void WriteColmapImagesText(const ColmapTextModel& model, std::ostream& out) {
  size_t observations = 0;
  for (const ColmapImage& image : model.images) {
    for (const ColmapPoint2D& point : image.points2D) observations += point.point3D_id >= 0;
  }
  const PreciseDoubles precise(out);
  out << "# Image list with two lines of data per image:\n"
      << "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
      << "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
      << "# Number of images: " << model.images.size() << ", mean observations per image: "
      << (model.images.empty() ? 0.0 : static_cast<double>(observations) / model.images.size())
      << "\n";
  for (const ColmapImage& image : model.images) {
    const Eigen::Quaterniond& q = image.cam_from_world_rotation;
    const Eigen::Vector3d& t = image.cam_from_world_translation;
    out << image.image_id << " " << q.w() << " " << q.x() << " " << q.y() << " " << q.z() << " "
        << t.x() << " " << t.y() << " " << t.z() << " " << image.camera_id << " " << image.name
        << "\n";
    for (size_t i = 0; i < image.points2D.size(); ++i) {
      const ColmapPoint2D& point = image.points2D[i];
      out << (i ? " " : "") << point.x << " " << point.y << " " << point.point3D_id;
    }
    out << "\n";
  }
}

void WriteColmapPoints3DText(const ColmapTextModel& model, std::ostream& out) {
  double track_sum = 0.0;
  for (const ColmapPoint3D& point : model.points3D) track_sum += point.track.size();
  const PreciseDoubles precise(out);
  out << "# 3D point list with one line of data per point:\n"
      << "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
      << "# Number of points: " << model.points3D.size() << ", mean track length: "
      << (model.points3D.empty() ? 0.0 : track_sum / model.points3D.size()) << "\n";
  for (const ColmapPoint3D& point : model.points3D) {
    out << point.point3D_id << " " << point.xyz.x() << " " << point.xyz.y() << " " << point.xyz.z()
        << " " << static_cast<int>(point.rgb[0]) << " " << static_cast<int>(point.rgb[1]) << " "
        << static_cast<int>(point.rgb[2]) << " " << point.error;
    for (const ColmapTrackElement& element : point.track) {
      out << " " << element.image_id << " " << element.point2D_idx;
    }
    out << "\n";
  }
}

std::string ColmapCamerasText(const ColmapTextModel& model) {
  return TextOf(model, WriteColmapCamerasText);
}

std::string ColmapImagesText(const ColmapTextModel& model) {
  return TextOf(model, WriteColmapImagesText);
}

std::string ColmapPoints3DText(const ColmapTextModel& model) {
  return TextOf(model, WriteColmapPoints3DText);
}

void WriteColmapTextModel(const ColmapTextModel& model, const std::string& folder) {
  model.Check();
  EnsureWritableDirectory(folder);
  // Streamed (a 5000-frame images.txt is 369 MB), all three on disk before the first rename.
  auto file = [&](const char* name, void (*write)(const ColmapTextModel&, std::ostream&)) {
    return StreamedFile{JoinPaths(folder, name),
                        [&model, write](std::ostream& out) { write(model, out); }};
  };
  WriteFilesAtomically({file("cameras.txt", WriteColmapCamerasText),
                        file("images.txt", WriteColmapImagesText),
                        file("points3D.txt", WriteColmapPoints3DText)});
}

ColmapTextModel ReadColmapTextModel(const std::string& folder) {
  COMIC_CHECK(IsDirectory(folder), kNotFound, folder << ": no such model folder");
  ColmapTextModel model;

  const std::string cameras_path = JoinPaths(folder, "cameras.txt");
  ForEachDataLine(cameras_path, false, [&](std::istringstream& fields, int line) {
    ColmapCamera camera;
    if (!(fields >> camera.camera_id >> camera.model >> camera.width >> camera.height)) {
      Malformed(cameras_path, line, "expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS...");
    }
    double p;
    while (fields >> p) camera.params.push_back(p);
    if (!AtEnd(fields)) Malformed(cameras_path, line, "non-numeric parameter");
    model.cameras.push_back(std::move(camera));
  });

  const std::string images_path = JoinPaths(folder, "images.txt");
  bool expect_points_line = false;
  ForEachDataLine(images_path, true, [&](std::istringstream& fields, int line) {
    if (!expect_points_line) {
      if (AtEnd(fields)) return;  // blank line between records
      ColmapImage image;
      double qw, qx, qy, qz;
      if (!(fields >> image.image_id >> qw >> qx >> qy >> qz >>
            image.cam_from_world_translation.x() >> image.cam_from_world_translation.y() >>
            image.cam_from_world_translation.z() >> image.camera_id >> image.name)) {
        Malformed(images_path, line, "expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
      }
      image.cam_from_world_rotation = Eigen::Quaterniond(qw, qx, qy, qz);
      model.images.push_back(std::move(image));
      expect_points_line = true;
      return;
    }
    ColmapImage& image = model.images.back();
    ColmapPoint2D point;
    while (fields >> point.x >> point.y >> point.point3D_id) image.points2D.push_back(point);
    if (!AtEnd(fields)) Malformed(images_path, line, "expected triples X Y POINT3D_ID");
    expect_points_line = false;
  });

  const std::string points_path = JoinPaths(folder, "points3D.txt");
  ForEachDataLine(points_path, false, [&](std::istringstream& fields, int line) {
    ColmapPoint3D point;
    int r, g, b;
    if (!(fields >> point.point3D_id >> point.xyz.x() >> point.xyz.y() >> point.xyz.z() >> r >> g >>
          b >> point.error)) {
      Malformed(points_path, line, "expected POINT3D_ID X Y Z R G B ERROR TRACK...");
    }
    if (r < 0 || r > 255 || g < 0 || g > 255 || b < 0 || b > 255) {
      Malformed(points_path, line, "colour outside 0..255");
    }
    point.rgb = {static_cast<uint8_t>(r), static_cast<uint8_t>(g), static_cast<uint8_t>(b)};
    ColmapTrackElement element;
    while (fields >> element.image_id >> element.point2D_idx) point.track.push_back(element);
    if (!AtEnd(fields)) Malformed(points_path, line, "expected pairs IMAGE_ID POINT2D_IDX");
    model.points3D.push_back(std::move(point));
  });

  model.Check();
  return model;
}

}  // namespace comic::io
