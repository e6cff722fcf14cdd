// A video all the way to COLMAP (issue 17): comic_sfm and comic_export_colmap on a short MJPG
// clip (the codec every Debian OpenCV writes) made from the bundled KITTI frames. --write-frames
// writes each frame once as frame_000000.png ..., the names images.txt and the database use, and
// the real `colmap image_undistorter` then finds and writes every frame of the model.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <set>
#include <string>
#include <vector>

#include "io/colmap/colmap_database.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::ExampleDir;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

constexpr int kFrames = 6;

// The first kFrames frames of the bundled example as an MJPG .avi.
std::string WriteExampleClip(const ScopedTempDir& dir) {
  const std::string video = dir.File("clip.avi");
  cv::VideoWriter writer;
  for (int i = 0; i < kFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "/image_l/%06d.png", i);
    const cv::Mat frame = cv::imread(ExampleDir() + name, cv::IMREAD_COLOR);
    if (!writer.isOpened()) {
      writer.open(video, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, frame.size(), true);
      EXPECT_TRUE(writer.isOpened());
    }
    writer.write(frame);
  }
  return video;
}

std::vector<std::string> ExpectedNames() {
  std::vector<std::string> names;
  for (int i = 0; i < kFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%06d.png", i);
    names.push_back(name);
  }
  return names;
}

std::set<std::string> ModelImageNames(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& image : comic::io::ReadColmapTextModel(folder).images) names.insert(image.name);
  return names;
}

TEST(ComicSfmVideo, WriteFramesLetsColmapImageUndistorterWriteEveryFrame) {
  ScopedTempDir dir;
  const std::string video = WriteExampleClip(dir);
  const std::string out = dir.File("out");
  const auto result = RunCommand(AppPath("comic_sfm") + " " + video + " --intrinsics " +
                                 ExampleDir() + "/calib.txt --write-frames --output " + out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // Each frame once, as PNG, named as the model names it.
  EXPECT_EQ(comic::io::ListFiles(out + "/images"), ExpectedNames());
  const std::vector<std::string> expected = ExpectedNames();
  EXPECT_EQ(ModelImageNames(out), std::set<std::string>(expected.begin(), expected.end()));
  EXPECT_EQ(cv::imread(out + "/images/frame_000000.png").size(), cv::Size(1226, 370));
  EXPECT_NE(result.output.find("frames as PNG in " + out + "/images"), std::string::npos)
      << result.output;

  const std::string undistorted = dir.File("undistorted");
  const auto colmap =
      RunCommand("QT_QPA_PLATFORM=offscreen colmap image_undistorter --image_path " + out +
                 "/images --input_path " + out + "/sparse/0 --output_path " + undistorted);
  ASSERT_EQ(colmap.exit_code, 0) << colmap.output;
  EXPECT_EQ(comic::io::ListFiles(undistorted + "/images"), ExpectedNames()) << colmap.output;
}

TEST(ComicSfmVideo, WriteFramesTakesAFolderAndColmapDbUsesItAsImagePath) {
  ScopedTempDir dir;
  const std::string video = WriteExampleClip(dir);
  const std::string frames = dir.File("frames");
  const auto result =
      RunCommand(AppPath("comic_sfm") + " " + video + " --intrinsics " + ExampleDir() +
                 "/calib.txt --quiet --write-frames=" + frames + " --colmap-db " +
                 dir.File("tracks.db") + " --output " + dir.File("out"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(comic::io::ListFiles(frames), ExpectedNames());
  EXPECT_FALSE(comic::io::PathExists(dir.File("out/images")));
  EXPECT_NE(result.output.find("--image_path " + frames), std::string::npos) << result.output;
  const auto database = comic::io::ColmapDatabase::Open(dir.File("tracks.db"));
  std::vector<std::string> names;
  for (const auto& image : database.ReadAllImages()) names.push_back(image.name);
  EXPECT_EQ(names, ExpectedNames());
}

TEST(ComicSfmVideo, ColmapDbOfAVideoWritesTheFramesBesideTheModel) {
  ScopedTempDir dir;
  const std::string video = WriteExampleClip(dir);
  const auto result = RunCommand(AppPath("comic_sfm") + " " + video + " --intrinsics " +
                                 ExampleDir() + "/calib.txt --quiet --colmap-db " +
                                 dir.File("tracks.db") + " --output " + dir.File("out"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // COLMAP needs the image files: the frames are written even without --write-frames.
  EXPECT_EQ(comic::io::ListFiles(dir.File("out/images")), ExpectedNames());
  EXPECT_NE(result.output.find("--image_path " + dir.File("out/images")), std::string::npos)
      << result.output;
}

TEST(ComicExportColmapVideo, WritesTheFramesBesideTheDatabaseUnderTheNamesItUses) {
  ScopedTempDir dir;
  const std::string video = WriteExampleClip(dir);
  const auto result = RunCommand(AppPath("comic_export_colmap") + " " + video + " --colmap-db " +
                                 dir.File("db/tracks.db") + " --quiet");
  // The database's folder must exist, as for any --colmap-db.
  EXPECT_NE(result.exit_code, 0);
  comic::io::EnsureWritableDirectory(dir.File("db"));
  const auto exported = RunCommand(AppPath("comic_export_colmap") + " " + video + " --colmap-db " +
                                   dir.File("db/tracks.db") + " --quiet");
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_EQ(comic::io::ListFiles(dir.File("db/images")), ExpectedNames());
  {
    // Closed before the --overwrite below: a database open in another process is never replaced.
    const auto database = comic::io::ColmapDatabase::Open(dir.File("db/tracks.db"));
    std::vector<std::string> names;
    for (const auto& image : database.ReadAllImages()) names.push_back(image.name);
    EXPECT_EQ(names, ExpectedNames());
  }
  EXPECT_NE(exported.output.find("--image_path " + dir.File("db/images")), std::string::npos)
      << exported.output;
  // Not quiet: progress lines while detecting and tracking.
  const auto verbose = RunCommand(AppPath("comic_export_colmap") + " " + video + " --colmap-db " +
                                  dir.File("db/tracks.db") + " --overwrite");
  ASSERT_EQ(verbose.exit_code, 0) << verbose.output;
  EXPECT_NE(verbose.output.find("detection and tracking: frame 6/6"), std::string::npos)
      << verbose.output;
}

}  // namespace
