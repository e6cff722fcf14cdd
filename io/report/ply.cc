#include "io/report/ply.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>

#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::io {
namespace {

const char* kVertexPropertiesAscii =
    "property double x\nproperty double y\nproperty double z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
const char* kVertexPropertiesBinary =
    "property float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";

bool HostIsLittleEndian() {
  const uint16_t one = 1;
  uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// Bytes of a property type in a binary PLY, 0 for one we do not read.
size_t PropertySize(const std::string& type) {
  if (type == "float" || type == "float32") return 4;
  if (type == "double" || type == "float64") return 8;
  if (type == "uchar" || type == "uint8") return 1;
  return 0;
}

}  // namespace

PlyFormat ParsePlyFormat(const std::string& name) {
  if (name == "ascii") return PlyFormat::kAscii;
  if (name == "binary") return PlyFormat::kBinaryLittleEndian;
  throw Error(ErrorKind::kInvalidArgument,
              "unknown PLY format '" + name + "' (expected ascii or binary)");
}

std::string PlyText(const std::vector<PlyPoint>& points) {
  std::string text;
  text += "ply\nformat ascii 1.0\ncomment written by comic-sfm\n";
  text += "element vertex " + std::to_string(points.size()) + "\n";
  text += kVertexPropertiesAscii;
  char line[160];
  for (const PlyPoint& point : points) {
    COMIC_CHECK(point.xyz.allFinite(), kInvalidArgument, "PLY: non-finite point coordinate");
    std::snprintf(line, sizeof(line), "%.17g %.17g %.17g %d %d %d\n", point.xyz.x(), point.xyz.y(),
                  point.xyz.z(), point.rgb[0], point.rgb[1], point.rgb[2]);
    text += line;
  }
  return text;
}

std::string PlyBinary(const std::vector<PlyPoint>& points) {
  std::string bytes = "ply\nformat binary_little_endian 1.0\ncomment written by comic-sfm\n";
  bytes += "element vertex " + std::to_string(points.size()) + "\n";
  bytes += kVertexPropertiesBinary;
  const size_t header_size = bytes.size();
  bytes.resize(header_size + points.size() * 15);
  char* out = bytes.data() + header_size;
  const bool little_endian = HostIsLittleEndian();
  for (const PlyPoint& point : points) {
    for (int k = 0; k < 3; ++k) {
      const float value = static_cast<float>(point.xyz[k]);
      COMIC_CHECK(std::isfinite(value), kInvalidArgument,
                  "PLY: point coordinate " << point.xyz[k] << " is not a finite float");
      uint8_t raw[4];
      std::memcpy(raw, &value, 4);
      if (!little_endian) std::swap(raw[0], raw[3]), std::swap(raw[1], raw[2]);
      std::memcpy(out, raw, 4);
      out += 4;
    }
    for (int c = 0; c < 3; ++c) *out++ = static_cast<char>(point.rgb[c]);
  }
  return bytes;
}

void WritePly(const std::string& path, const std::vector<PlyPoint>& points, PlyFormat format) {
  // Serialised first, so that bad input leaves no file behind.
  WriteFileAtomically(path, format == PlyFormat::kAscii ? PlyText(points) : PlyBinary(points));
}

std::vector<PlyPoint> ReadPly(const std::string& path) {
  const std::string contents = ReadFileToString(path);
  size_t offset = 0;  // of the next header line
  int line_number = 0;
  std::string line;
  const auto next_line = [&]() {
    const size_t end = contents.find('\n', offset);
    COMIC_CHECK(end != std::string::npos, kInvalidData, path << ": PLY header ends early");
    line = contents.substr(offset, end - offset);
    offset = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return line;
  };
  COMIC_CHECK(next_line() == "ply", kInvalidData, path << ": not a PLY file");
  const std::string format_line = next_line();
  const bool binary = format_line == "format binary_little_endian 1.0";
  COMIC_CHECK(binary || format_line == "format ascii 1.0", kInvalidData,
              path << ": only ASCII and binary little-endian PLY files are read");
  size_t num_vertices = 0;
  bool in_vertex = false;
  std::vector<std::string> properties;
  std::vector<size_t> property_sizes;
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
      property_sizes.push_back(PropertySize(type));
    }
  }
  const bool has_color = properties.size() == 6;
  COMIC_CHECK((properties.size() == 3 || has_color) && properties[0] == "x" &&
                  properties[1] == "y" && properties[2] == "z" &&
                  (!has_color ||
                   (properties[3] == "red" && properties[4] == "green" && properties[5] == "blue")),
              kInvalidData, path << ": expected vertex properties x y z [red green blue]");
  std::vector<PlyPoint> points;
  if (binary) {
    size_t vertex_size = 0;
    for (size_t i = 0; i < property_sizes.size(); ++i) {
      const bool ok =
          i < 3 ? (property_sizes[i] == 4 || property_sizes[i] == 8) : property_sizes[i] == 1;
      COMIC_CHECK(ok, kInvalidData,
                  path << ": binary PLY: x y z must be float or double, colours uchar");
      vertex_size += property_sizes[i];
    }
    COMIC_CHECK((contents.size() - offset) / vertex_size >= num_vertices, kInvalidData,
                path << ": " << num_vertices << " vertices announced, "
                     << (contents.size() - offset) / vertex_size << " found");
    const bool little_endian = HostIsLittleEndian();
    points.reserve(num_vertices);
    const char* in = contents.data() + offset;
    for (size_t i = 0; i < num_vertices; ++i) {
      PlyPoint point;
      for (int k = 0; k < 3; ++k) {
        uint8_t raw[8];
        const size_t size = property_sizes[k];
        std::memcpy(raw, in, size);
        in += size;
        if (!little_endian) std::reverse(raw, raw + size);
        if (size == 4) {
          float value;
          std::memcpy(&value, raw, 4);
          point.xyz[k] = value;
        } else {
          std::memcpy(&point.xyz[k], raw, 8);
        }
      }
      for (int c = 0; c < 3 && has_color; ++c) point.rgb[c] = static_cast<uint8_t>(*in++);
      points.push_back(point);
    }
    return points;
  }
  std::istringstream in(contents.substr(offset));
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
