// Coloured point clouds as PLY files, which MeshLab, CloudCompare, Open3D and Blender open: ASCII
// ("x y z" as doubles, exact) or binary little-endian ("x y z" as float, "red green blue" as
// uchar, 15 bytes a point: the layout COLMAP's own point-cloud export writes).
//
//   std::vector<PlyPoint> points = {{Eigen::Vector3d(0, 0, 1), {255, 0, 0}}};
//   comic::io::WritePly("cloud.ply", points, comic::io::PlyFormat::kBinaryLittleEndian);
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace comic::io {

struct PlyPoint {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  std::array<uint8_t, 3> rgb = {0, 0, 0};
};

enum class PlyFormat {
  kAscii,               // doubles with 17 significant digits: reading back gives the same doubles
  kBinaryLittleEndian,  // floats (about 7 digits), 15 bytes a point instead of about 60
};

// "ascii" / "binary" (the names the apps take) to a format; throws comic::Error(kInvalidArgument)
// for another name.
PlyFormat ParsePlyFormat(const std::string& name);

// The PLY file as text (17 significant digits, so reading it back gives the same doubles).
std::string PlyText(const std::vector<PlyPoint>& points);

// The PLY file as binary little-endian bytes (float x y z, uchar red green blue). Throws
// comic::Error(kInvalidArgument) for a coordinate that is not finite as a float.
std::string PlyBinary(const std::vector<PlyPoint>& points);

// Writes `points` to `path` atomically. Throws comic::Error(kIo) if it cannot be written and
// kInvalidArgument for a non-finite coordinate.
void WritePly(const std::string& path, const std::vector<PlyPoint>& points,
              PlyFormat format = PlyFormat::kAscii);

// Reads an ASCII or binary little-endian PLY whose vertex element has the properties x, y, z
// (float or double) and optionally red, green, blue (uchar) — what WritePly writes. Throws
// comic::Error: kNotFound, or kInvalidData naming the file for another layout or malformed
// content.
std::vector<PlyPoint> ReadPly(const std::string& path);

}  // namespace comic::io
