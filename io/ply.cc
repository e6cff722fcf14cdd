#include "io/ply.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/error.h"
#include "io/file_utils.h"

namespace comic::io {

std::string PlyText(const std::vector<PlyPoint>& points) {
  std::string text;
  text += "ply\nformat ascii 1.0\ncomment written by comic-sfm\n";
  text += "element vertex " + std::to_string(points.size()) + "\n";
  text +=
      "property double x\nproperty double y\nproperty double z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  char line[160];
  for (const PlyPoint& point : points) {
    COMIC_CHECK(point.xyz.allFinite(), kInvalidArgument, "PLY: non-finite point coordinate");
    std::snprintf(line, sizeof(line), "%.17g %.17g %.17g %d %d %d\n", point.xyz.x(), point.xyz.y(),
                  point.xyz.z(), point.rgb[0], point.rgb[1], point.rgb[2]);
    text += line;
  }
  return text;
}

void WritePly(const std::string& path, const std::vector<PlyPoint>& points) {
  WriteFileAtomically(path, PlyText(points));
}

std::vector<PlyPoint> ReadPly(const std::string& path) {
  std::istringstream in(ReadFileToString(path));
  std::string line;
  int line_number = 0;
  const auto next_line = [&]() {
    COMIC_CHECK(std::getline(in, line), kInvalidData, path << ": PLY header ends early");
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return line;
  };
  COMIC_CHECK(next_line() == "ply", kInvalidData, path << ": not a PLY file");
  COMIC_CHECK(next_line() == "format ascii 1.0", kInvalidData,
              path << ": only ASCII PLY files are read");
  size_t num_vertices = 0;
  bool in_vertex = false;
  std::vector<std::string> properties;
  while (next_line() != "end_header") {
    std::istringstream fields(line);
    std::string keyword;
    fields >> keyword;
    if (keyword == "comment" || keyword.empty()) continue;
    if (keyword == "element") {
      std::string name;
      long long count = -1;
      fields >> name >> count;
      COMIC_CHECK(count >= 0, kInvalidData, path << ":" << line_number << ": bad element count");
      in_vertex = name == "vertex";
      COMIC_CHECK(in_vertex || count == 0, kInvalidData,
                  path << ":" << line_number << ": only vertex elements are read");
      if (in_vertex) num_vertices = static_cast<size_t>(count);
    } else if (keyword == "property" && in_vertex) {
      std::string type, name;
      fields >> type >> name;
      properties.push_back(name);
    }
  }
  const bool has_color = properties.size() == 6;
  COMIC_CHECK((properties.size() == 3 || has_color) && properties[0] == "x" &&
                  properties[1] == "y" && properties[2] == "z" &&
                  (!has_color ||
                   (properties[3] == "red" && properties[4] == "green" && properties[5] == "blue")),
              kInvalidData, path << ": expected vertex properties x y z [red green blue]");
  std::vector<PlyPoint> points;
  points.reserve(num_vertices);
  for (size_t i = 0; i < num_vertices; ++i) {
    COMIC_CHECK(std::getline(in, line), kInvalidData,
                path << ": " << num_vertices << " vertices announced, " << i << " found");
    ++line_number;
    std::istringstream fields(line);
    PlyPoint point;
    int rgb[3] = {0, 0, 0};
    fields >> point.xyz.x() >> point.xyz.y() >> point.xyz.z();
    if (has_color) fields >> rgb[0] >> rgb[1] >> rgb[2];
    COMIC_CHECK(!fields.fail(), kInvalidData, path << ":" << line_number << ": malformed vertex");
    for (int c = 0; c < 3; ++c) {
      COMIC_CHECK(rgb[c] >= 0 && rgb[c] <= 255, kInvalidData,
                  path << ":" << line_number << ": colour out of range");
      point.rgb[c] = static_cast<uint8_t>(rgb[c]);
    }
    points.push_back(point);
  }
  return points;
}

}  // namespace comic::io
