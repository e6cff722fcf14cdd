// End-to-end checks of comic_detect: help, outputs on a synthetic and a bundled image, and bad
// input (one line on stderr, non-zero exit, no output written).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A 160 x 140 image with one bright square (four corners) on a dark background.
std::string WriteSquareImage(const comic::test::ScopedTempDir& dir) {
  cv::Mat image(140, 160, CV_8UC1, cv::Scalar(40));
  cv::rectangle(image, cv::Rect(50, 40, 50, 45), cv::Scalar(210), cv::FILLED);
  cv::GaussianBlur(image, image, cv::Size(7, 7), 1.0);
  const std::string path = dir.File("square.png");
  cv::imwrite(path, image);
  return path;
}

TEST(ComicDetect, HelpDocumentsEveryOption) {
  const auto result = RunCommand(AppPath("comic_detect") + " --help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* option :
       {"IMAGE", "--overlay", "--json", "--resize-height", "--scale", "--block-size", "--delta",
        "--half-length", "--max-iterations", "--convergence-tolerance", "--stop-tolerance",
        "--merge-radius", "--min-stability", "--min-cornerness", "--no-neighbour-seeds",
        "--every-path", "--full-resolution-init", "--threads", "--max-features"}) {
    EXPECT_NE(result.output.find(option), std::string::npos) << option;
  }
}

TEST(ComicDetect, WritesTheOverlayAndTheFeaturesOfASquare) {
  comic::test::ScopedTempDir dir;
  const std::string image = WriteSquareImage(dir);
  const std::string overlay = dir.File("overlay.png");
  const std::string json_path = dir.File("features.json");
  const auto result = RunCommand(AppPath("comic_detect") + " " + image + " --overlay " + overlay +
                                 " --json " + json_path);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("features: 4 (4 bright, 0 dark)"), std::string::npos)
      << result.output;

  const cv::Mat drawn = cv::imread(overlay);
  ASSERT_FALSE(drawn.empty());
  EXPECT_EQ(drawn.size(), cv::Size(160, 140));
  EXPECT_EQ(drawn.type(), CV_8UC3);
  EXPECT_GT(cv::countNonZero(drawn.reshape(1) != cv::imread(image, cv::IMREAD_COLOR).reshape(1)),
            100);  // something was drawn

  const nlohmann::json json = nlohmann::json::parse(ReadFile(json_path));
  EXPECT_EQ(json["detector"], "comic");
  EXPECT_EQ(json["width"], 160);
  EXPECT_EQ(json["height"], 140);
  EXPECT_DOUBLE_EQ(json["options"]["scale"].get<double>(), 8.4);
  ASSERT_EQ(json["features"].size(), 4u);
  const cv::Point2d corners[] = {{49.5, 39.5}, {99.5, 39.5}, {99.5, 84.5}, {49.5, 84.5}};
  for (const auto& f : json["features"]) {
    const cv::Point2d p(f["x"].get<double>(), f["y"].get<double>());
    double nearest = 1e9;
    for (const cv::Point2d& c : corners) nearest = std::min(nearest, cv::norm(p - c));
    EXPECT_LT(nearest, 1.0) << p;
    EXPECT_EQ(f["polarity"], "bright");
    EXPECT_GT(f["response"].get<double>(), 0.0);
    EXPECT_GT(f["cornerness"].get<double>(), 0.1);
    EXPECT_EQ(f["curve"].size(), 25u);
    ASSERT_EQ(f["side_mask"].size(), 23u);
    for (const auto& row : f["side_mask"]) {
      EXPECT_EQ(row.get<std::string>().size(), 23u);
      EXPECT_EQ(row.get<std::string>().find_first_not_of("+-."), std::string::npos);
    }
  }
}

TEST(ComicDetect, ResizesAndIsDeterministicWhateverTheThreadCount) {
  comic::test::ScopedTempDir dir;
  const std::string frame = comic::test::ExampleDir() + "/image_l/000000.png";
  const std::string a = dir.File("a.json"), b = dir.File("b.json");
  const auto first = RunCommand(AppPath("comic_detect") + " " + frame +
                                " --resize-height 185 --threads 1 --json " + a);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("(613x185)"), std::string::npos) << first.output;
  const auto second = RunCommand(AppPath("comic_detect") + " " + frame +
                                 " --resize-height 185 --threads 2 --json " + b);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const std::string text = ReadFile(a);
  EXPECT_EQ(text, ReadFile(b));
  const nlohmann::json json = nlohmann::json::parse(text);
  EXPECT_GT(json["features"].size(), 50u);
  const auto limited = RunCommand(AppPath("comic_detect") + " " + frame +
                                  " --resize-height 185 --max-features 7 --json " + b);
  ASSERT_EQ(limited.exit_code, 0) << limited.output;
  EXPECT_EQ(nlohmann::json::parse(ReadFile(b))["features"].size(), 7u);
}

TEST(ComicDetect, BadInputGivesOneLineErrorAndNoOutput) {
  comic::test::ScopedTempDir dir;
  const std::string image = WriteSquareImage(dir);
  const std::string corrupt = dir.File("corrupt.png");
  std::ofstream(corrupt) << "not a png";
  const std::string out = dir.File("out.png");
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"", 2, "missing argument IMAGE"},
      {dir.File("missing.png") + " --overlay " + out, 1, "no such file"},
      {corrupt + " --overlay " + out, 1, "cannot decode image"},
      {image + " --overlay /nonexistent/dir/o.png", 1, "does not exist"},
      {image + " --overlay " + out + " --json " + dir.path(), 1, "is a folder"},
      {image + " --overlay " + out + " --scale 0", 2, "scale must be > 0"},
      {image + " --overlay " + out + " --scale x", 2, "expected a number"},
      {image + " --overlay " + out + " --delta 0", 2, "delta must be >= 1"},
      {image + " --overlay " + out + " --block-size 3", 2, "--block-size must be >= 8"},
      {image + " --overlay " + out + " --min-cornerness 0.5", 2, "--min-cornerness"},
      {image + " --overlay " + out + " --threads -1", 2, "--threads must be >= 0"},
      {image + " --overlay " + out + " --resize-height -2", 2,
       "--resize-height must be 0 (original size) or in [8, 16384]"},
      {image + " --overlay " + out + " --max-features -1", 2, "--max-features must be >= 0"},
      {image + " --overlay " + out + " --bogus", 2, "unknown option --bogus"},
  };
  for (const Case& c : cases) {
    const auto result = RunCommand(AppPath("comic_detect") + " " + c.args);
    EXPECT_EQ(result.exit_code, c.exit_code) << c.args << "\n" << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n" << result.output;
    EXPECT_EQ(comic::test::CountLines(result.output), 1) << result.output;
    std::ifstream written(out);
    EXPECT_FALSE(written.good()) << "output written despite the error: " << c.args;
  }
}

TEST(ComicDetect, TinyAndUniformImagesGiveNoFeaturesAndNoError) {
  comic::test::ScopedTempDir dir;
  const std::string tiny = dir.File("tiny.png"), uniform = dir.File("uniform.png");
  cv::imwrite(tiny, cv::Mat(30, 40, CV_8UC1, cv::Scalar(100)));
  cv::imwrite(uniform, cv::Mat(200, 300, CV_8UC3, cv::Scalar(10, 200, 30)));
  for (const std::string& image : {tiny, uniform}) {
    const std::string json_path = dir.File("f.json");
    const auto result = RunCommand(AppPath("comic_detect") + " " + image + " --json " + json_path +
                                   " --overlay " + dir.File("o.png"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("features: 0"), std::string::npos) << result.output;
    EXPECT_TRUE(nlohmann::json::parse(ReadFile(json_path))["features"].empty());
  }
}

}  // namespace
