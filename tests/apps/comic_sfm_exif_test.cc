// comic_sfm on photos that state their focal length in EXIF: the bundled example's first frames
// as JPEGs with FocalLengthIn35mmFilm, run without --intrinsics, start from the EXIF focal
// (f35 / 35 · max(w, h), as COLMAP), and report.json and the inputs line say so.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "io/core/file_utils.h"
#include "tests/io/image/exif_test_jpeg.h"
#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

// The example's first `count` frames as JPEGs carrying FocalLengthIn35mmFilm `focal_35mm`.
void WriteExifFrames(const std::string& folder, int count, uint16_t focal_35mm) {
  for (int i = 0; i < count; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d", i);
    const cv::Mat image =
        cv::imread(comic::test::ExampleDir() + "/image_l/" + name + ".png", cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(image.empty()) << name;
    std::vector<uchar> jpeg;
    ASSERT_TRUE(cv::imencode(".jpg", image, jpeg, {cv::IMWRITE_JPEG_QUALITY, 95}));
    comic::test::ExifTestTags tags;
    tags.focal_length_35mm = focal_35mm;
    std::ofstream file(folder + "/" + name + ".jpg", std::ios::binary);
    file << comic::test::WithExifSegment(std::string(jpeg.begin(), jpeg.end()),
                                         comic::test::ExifTiff(tags, i % 2 == 0));
  }
}

TEST(ComicSfmExif, TheExifFocalIsThePriorAndTheReportSaysSo) {
  ScopedTempDir dir;
  const std::string frames = dir.File("frames");
  std::filesystem::create_directories(frames);
  // 20 mm equivalent on 1226 px: 700.6 px, near KITTI's 707.1 (the guess would be 1471.2).
  WriteExifFrames(frames, 6, 20);
  const double expected = 20.0 / 35.0 * 1226;
  const auto result =
      RunCommand(AppPath("comic_sfm") + " " + frames + " --quiet --output " + dir.File("out"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("(EXIF FocalLengthIn35mmFilm 20 mm in 000000.jpg, 6 of 6 frames "
                               "read agree, refined once the model constrains it)"),
            std::string::npos)
      << result.output;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("out/report.json")));
  const nlohmann::json& camera = report.at("camera");
  EXPECT_EQ(camera.at("prior_from"), "exif");
  EXPECT_EQ(camera.at("source").get<std::string>().rfind("EXIF FocalLengthIn35mmFilm 20 mm", 0),
            0u);
  EXPECT_EQ(camera.at("prior").at("model"), "SIMPLE_RADIAL");
  EXPECT_DOUBLE_EQ(camera.at("prior").at("params").at(0).get<double>(), expected);
  // The page's summary states it in the same words.
  EXPECT_NE(comic::io::ReadFileToString(dir.File("out/report.html"))
                .find("EXIF FocalLengthIn35mmFilm 20 mm in 000000.jpg"),
            std::string::npos);
}

// A calibration file still comes first: the EXIF focal is not read.
TEST(ComicSfmExif, IntrinsicsComeBeforeTheExifFocal) {
  ScopedTempDir dir;
  const std::string frames = dir.File("frames");
  std::filesystem::create_directories(frames);
  WriteExifFrames(frames, 6, 20);
  const auto result =
      RunCommand(AppPath("comic_sfm") + " " + frames + " --intrinsics " +
                 comic::test::ExampleDir() + "/calib.txt --quiet --output " + dir.File("out"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.find("EXIF"), std::string::npos) << result.output;
  const nlohmann::json camera =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("out/report.json"))).at("camera");
  EXPECT_EQ(camera.at("prior_from"), "file");
  EXPECT_DOUBLE_EQ(camera.at("prior").at("params").at(0).get<double>(), 707.0912);
}

}  // namespace
