// Coloured point clouds as PLY files (ASCII, "x y z" as doubles and "red green blue" as uchar),
// which MeshLab, CloudCompare, Open3D and Blender open.
//
//   std::vector<PlyPoint> points = {{Eigen::Vector3d(0, 0, 1), {255, 0, 0}}};
//   comic::io::WritePly("cloud.ply", points);
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

// The PLY file as text (17 significant digits, so reading it back gives the same doubles).
std::string PlyText(const std::vector<PlyPoint>& points);

// Writes `points` to `path` atomically. Throws comic::Error(kIo) if it cannot be written and
// kInvalidArgument for a non-finite coordinate.
void WritePly(const std::string& path, const std::vector<PlyPoint>& points);

// Reads an ASCII PLY whose vertex element has the properties x, y, z (float or double) and
// optionally red, green, blue (uchar) — what WritePly writes. Throws comic::Error: kNotFound, or
// kInvalidData naming the file for another layout or malformed content.
std::vector<PlyPoint> ReadPly(const std::string& path);

}  // namespace comic::io
