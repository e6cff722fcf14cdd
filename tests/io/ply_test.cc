// PLY point clouds: exact round trip, header layout other tools rely on, and malformed files.
#include "io/ply.h"

#include <gtest/gtest.h>

#include "io/error.h"
#include "io/file_utils.h"
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
