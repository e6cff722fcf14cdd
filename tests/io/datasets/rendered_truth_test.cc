// The truth a comic_render folder holds, read back (io/datasets/rendered_truth.h): a folder made
// here file by file, as comic_render lays it out, and its mistakes.
#include "io/datasets/rendered_truth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/depth_map.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

void MakeFolder(const std::string& dir, int frames, const std::string& depth_extension) {
  for (const char* sub : {"images", "depth", "boundaries", "masks", "colmap"}) {
    EnsureWritableDirectory(JoinPaths(dir, sub));
  }
  std::string poses;
  for (int k = 0; k < frames; ++k) {
    char name[16];
    std::snprintf(name, sizeof(name), "%06d", k);
    cv::imwrite(JoinPaths(dir, std::string("images/") + name + ".png"),
                cv::Mat(30, 40, CV_8UC3, cv::Scalar(k, k, k)));
    WriteDepthMap(JoinPaths(dir, std::string("depth/") + name + "." + depth_extension),
                  cv::Mat(30, 40, CV_32F, cv::Scalar(2.0 + k)));
    cv::Mat band = cv::Mat::zeros(30, 40, CV_8UC1);
    band.col(k) = 255;
    cv::imwrite(JoinPaths(dir, std::string("boundaries/") + name + ".png"), band);
    cv::imwrite(JoinPaths(dir, std::string("masks/") + name + ".png"), 255 - band);
    poses += "1 0 0 " + std::to_string(0.5 * k) + " 0 1 0 0 0 0 1 0\n";
  }
  WriteFileAtomically(JoinPaths(dir, "poses.txt"), poses);
  WriteFileAtomically(JoinPaths(dir, "colmap/cameras.txt"), "1 PINHOLE 40 30 35 35 20 15\n");
  WriteFileAtomically(JoinPaths(dir, "scene.json"),
                      R"({"render_options": {"boundary_band_px": 2.5}})");
}

TEST(RenderedTruth, ReadsCamerasDepthAndMasksPerFrame) {
  for (const std::string extension : {"pfm", "png"}) {
    test::ScopedTempDir dir;
    MakeFolder(dir.path(), 3, extension);
    const RenderedTruth truth = OpenRenderedTruth(dir.path());
    EXPECT_EQ(truth.NumFrames(), 3u);
    EXPECT_EQ(truth.depth_extension, extension);
    EXPECT_DOUBLE_EQ(truth.band_px, 2.5);
    EXPECT_EQ(truth.camera.model, "PINHOLE");
    EXPECT_DOUBLE_EQ(truth.camera.params[2], 19.5);  // COLMAP's 20 in OpenCV's convention
    ASSERT_EQ(truth.cameras.cameras.size(), 3u);
    // poses.txt is camera-to-world: frame 2's centre is at x = 1, so t = -1.
    EXPECT_DOUBLE_EQ(truth.cameras.cameras[2].cam_from_world_translation.x(), -1.0);
    EXPECT_FLOAT_EQ(truth.Depth(1).at<float>(5, 5), 3.0f);
    EXPECT_EQ(truth.Boundaries(2).at<uint8_t>(7, 2), 255);
    EXPECT_EQ(truth.Boundaries(2).at<uint8_t>(7, 3), 0);
    EXPECT_EQ(truth.Foreground(2).at<uint8_t>(7, 3), 255);
    EXPECT_THROW(truth.Depth(3), Error);
  }
}

TEST(RenderedTruth, ACompositesObjectHasUnknownDepthInEitherFormat) {
  // A NeRF composite: masks/ is the object, whose depth is not given. A 16-bit PNG cannot say
  // "unknown" and would say "no surface" (sky); read back, it is NaN as in a PFM.
  for (const std::string extension : {"pfm", "png"}) {
    test::ScopedTempDir dir;
    MakeFolder(dir.path(), 2, extension);
    const std::string depth_path = JoinPaths(dir.path(), "depth/000001." + extension);
    cv::Mat depth(30, 40, CV_32F, cv::Scalar(3.0));
    depth.colRange(0, 1).setTo(0.0f);  // the object (masks/ is all but column 1), depth not given
    depth.colRange(2, 40).setTo(0.0f);
    WriteDepthMap(depth_path, depth);
    WriteFileAtomically(JoinPaths(dir.path(), "scene.json"),
                        R"({"render_options": {"boundary_band_px": 2}, "composite": {}})");
    const RenderedTruth truth = OpenRenderedTruth(dir.path());
    EXPECT_TRUE(truth.composite);
    const cv::Mat read = truth.Depth(1);
    EXPECT_TRUE(std::isnan(read.at<float>(5, 0))) << extension;
    EXPECT_TRUE(std::isnan(read.at<float>(5, 20))) << extension;
    EXPECT_FLOAT_EQ(read.at<float>(5, 1), 3.0f) << extension;  // the background, known
  }
  // Not a composite: 0 stays "no surface".
  test::ScopedTempDir dir;
  MakeFolder(dir.path(), 1, "png");
  WriteDepthMap(JoinPaths(dir.path(), "depth/000000.png"), cv::Mat(30, 40, CV_32F, cv::Scalar(0)));
  const RenderedTruth truth = OpenRenderedTruth(dir.path());
  EXPECT_FALSE(truth.composite);
  EXPECT_EQ(truth.Depth(0).at<float>(5, 5), 0.0f);
}

TEST(RenderedTruth, MissingOrDisagreeingPartsAreNamed) {
  test::ScopedTempDir dir;
  EXPECT_THROW(OpenRenderedTruth(dir.File("none")), Error);
  MakeFolder(dir.path(), 3, "pfm");
  WriteFileAtomically(dir.File("poses.txt"), "1 0 0 0 0 1 0 0 0 0 1 0\n");
  try {
    OpenRenderedTruth(dir.path());
    FAIL() << "one pose for three frames was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("1 poses for 3 frames"), std::string::npos) << e.what();
  }
  test::ScopedTempDir frames_only;
  EnsureWritableDirectory(frames_only.File("images"));
  try {
    OpenRenderedTruth(frames_only.path());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--frames-only"), std::string::npos) << e.what();
  }
}

// A depth map of another size than the frames, in either format, is named when the folder is
// opened (from its header, before any evaluation reads it) and by Depth() itself.
TEST(RenderedTruth, ADepthMapOfAnotherSizeIsNamedAtOpen) {
  for (const std::string extension : {"pfm", "png"}) {
    SCOPED_TRACE(extension);
    test::ScopedTempDir dir;
    MakeFolder(dir.path(), 3, extension);
    const std::string wrong = dir.File("depth/000002." + extension);
    WriteDepthMap(wrong, cv::Mat(15, 20, CV_32F, cv::Scalar(2.0)));
    try {
      OpenRenderedTruth(dir.path());
      FAIL() << "a 20x15 depth map beside 40x30 frames was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
      EXPECT_EQ(std::string(e.what()), wrong + ": 20x15, but the frames are 40x30");
    }
  }
}

}  // namespace
}  // namespace comic::io
