// PLY point clouds: exact ASCII round trip, binary little-endian round trip to float precision,
// header layout other tools rely on, and malformed files.
#include "io/report/ply.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

TEST(Ply, RoundTripIsExact) {
  test::ScopedTempDir dir;
  std::vector<PlyPoint> points = {{Eigen::Vector3d(0.1, -2.0 / 3.0, 1e-7), {255, 0, 17}},
                                  {Eigen::Vector3d(1e6, 3.14159265358979, -42), {0, 128, 255}}};
  WritePly(dir.File("cloud.ply"), points);
  const std::vector<PlyPoint> read = ReadPly(dir.File("cloud.ply"));
  ASSERT_EQ(read.size(), points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(read[i].xyz, points[i].xyz);
    EXPECT_EQ(read[i].rgb, points[i].rgb);
  }
  const std::string text = ReadFileToString(dir.File("cloud.ply"));
  EXPECT_EQ(text.rfind("ply\nformat ascii 1.0\n", 0), 0u);
  EXPECT_NE(text.find("element vertex 2\n"), std::string::npos);
  EXPECT_NE(text.find("property uchar red\n"), std::string::npos);
}

TEST(Ply, BinaryRoundTripKeepsFloats) {
  test::ScopedTempDir dir;
  std::vector<PlyPoint> points = {{Eigen::Vector3d(0.1, -2.0 / 3.0, 1e-7), {255, 0, 17}},
                                  {Eigen::Vector3d(1e6, 3.14159265358979, -42), {0, 128, 255}},
                                  {Eigen::Vector3d(0.5, 0.25, 10), {1, 2, 3}}};
  WritePly(dir.File("cloud.ply"), points, PlyFormat::kBinaryLittleEndian);
  const std::vector<PlyPoint> read = ReadPly(dir.File("cloud.ply"));
  ASSERT_EQ(read.size(), points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(read[i].xyz[k], static_cast<double>(static_cast<float>(points[i].xyz[k])));
    }
    EXPECT_EQ(read[i].rgb, points[i].rgb);
  }
  const std::string bytes = ReadFileToString(dir.File("cloud.ply"));
  EXPECT_EQ(bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  const std::string header_end = "property uchar blue\nend_header\n";
  const size_t body = bytes.find(header_end) + header_end.size();
  EXPECT_NE(bytes.find("property float x\n"), std::string::npos);
  // 15 bytes a point: float x y z, uchar r g b; the last point's x is 0.5f = 0x3f000000 (LE).
  ASSERT_EQ(bytes.size(), body + 3 * 15);
  EXPECT_EQ(bytes.substr(body + 30, 4), std::string("\x00\x00\x00\x3f", 4));
  EXPECT_EQ(static_cast<uint8_t>(bytes[body + 44]), 3);
  EXPECT_EQ(ParsePlyFormat("binary"), PlyFormat::kBinaryLittleEndian);
  EXPECT_EQ(ParsePlyFormat("ascii"), PlyFormat::kAscii);
  EXPECT_THROW(ParsePlyFormat("binary_big_endian"), Error);
}

TEST(Ply, BadBinaryInput) {
  test::ScopedTempDir dir;
  WritePly(dir.File("cloud.ply"), {{Eigen::Vector3d(1, 2, 3), {4, 5, 6}}},
           PlyFormat::kBinaryLittleEndian);
  const std::string bytes = ReadFileToString(dir.File("cloud.ply"));
  WriteFileAtomically(dir.File("short.ply"), bytes.substr(0, bytes.size() - 1));
  EXPECT_THROW(ReadPly(dir.File("short.ply")), Error);
  // A double that is too large for a float is refused, and no file is left behind.
  EXPECT_THROW(WritePly(dir.File("big.ply"), {{Eigen::Vector3d(1e300, 0, 0), {0, 0, 0}}},
                        PlyFormat::kBinaryLittleEndian),
               Error);
  EXPECT_FALSE(PathExists(dir.File("big.ply")));
  WriteFileAtomically(dir.File("int.ply"),
                      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty int x\n"
                      "property int y\nproperty int z\nend_header\n" +
                          std::string(12, '\0'));
  EXPECT_THROW(ReadPly(dir.File("int.ply")), Error);
}

TEST(Ply, EmptyCloudAndBadInput) {
  test::ScopedTempDir dir;
  WritePly(dir.File("empty.ply"), {});
  EXPECT_TRUE(ReadPly(dir.File("empty.ply")).empty());
  EXPECT_THROW(WritePly(dir.File("nan.ply"), {{Eigen::Vector3d(NAN, 0, 0), {0, 0, 0}}}), Error);
  EXPECT_FALSE(PathExists(dir.File("nan.ply")));
  WriteFileAtomically(dir.File("short.ply"),
                      "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty "
                      "double y\nproperty double z\nend_header\n1 2 3\n");
  EXPECT_THROW(ReadPly(dir.File("short.ply")), Error);
  WriteFileAtomically(dir.File("binary.ply"), "ply\nformat binary_little_endian 1.0\n");
  EXPECT_THROW(ReadPly(dir.File("binary.ply")), Error);
  EXPECT_THROW(ReadPly(dir.File("missing.ply")), Error);
  EXPECT_THROW(WritePly("/nonexistent/dir/cloud.ply", {}), Error);
}

}  // namespace
}  // namespace comic::io
