// comic_render end to end: help; a short street rendered with the bundled photographs, then
// comic_sfm run on the frames with the rendered truth exactly as written (--gt poses.txt, with
// calib.txt beside it, and --masks masks/) reconstructs them.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

std::string Scene() { return comic::test::SourceDir() + "/scenes/test_street.json"; }

TEST(ComicRender, HelpDocumentsEveryOption) {
  const auto result = RunCommand(AppPath("comic_render") + " --help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* option :
       {"--photos", "--seed", "--frames", "--output", "--supersampling", "--noise", "--shot-noise",
        "--exposure-drift", "--shutter", "--blur-samples", "--blur-every", "--depth-format",
        "--occlusion-band", "--occlusion-depth-ratio", "--frames-only", "--stereo-pairs",
        "--stereo-baseline"}) {
    EXPECT_NE(result.output.find(option), std::string::npos) << option;
  }
}

TEST(ComicRender, ComicSfmReadsTheRenderedTruthUnchanged) {
  ScopedTempDir dir;
  const std::string out = dir.File("street");
  const auto render = RunCommand(AppPath("comic_render") + " " + Scene() + " --photos " +
                                 comic::test::ExampleDir() + "/image_l --frames 10 -q -o " + out);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  EXPECT_NE(render.output.find("10 frames 640x480"), std::string::npos) << render.output;
  for (const char* file :
       {"poses.txt", "calib.txt", "scene.json", "colmap/cameras.txt", "images/000009.png",
        "depth/000009.png", "ids/000009.png", "boundaries/000009.png", "masks/000009.png"}) {
    EXPECT_TRUE(comic::io::PathExists(out + "/" + file)) << file;
  }
  const auto sfm =
      RunCommand(AppPath("comic_sfm") + " " + out + "/images --gt " + out + "/poses.txt --masks " +
                 out + "/masks -q --model-format txt " + "--output " + dir.File("sfm"));
  ASSERT_EQ(sfm.exit_code, 0) << sfm.output;
  // The intrinsics came from calib.txt beside poses.txt.
  EXPECT_NE(sfm.output.find("PINHOLE fx=500 fy=500 cx=319.5 cy=239.5 (ground truth"),
            std::string::npos)
      << sfm.output;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("sfm/report.json")));
  EXPECT_EQ(report["registered_frames"], 10) << report.dump(1);
  // Exact truth, a calibrated camera and 8 m of driving: the trajectory is found to centimetres.
  EXPECT_LT(report["ground_truth"]["ate_rmse"].get<double>(), 0.05)
      << report["ground_truth"].dump();
  EXPECT_TRUE(report.contains("boundary_points3D")) << "--masks gave no boundary split";
}

TEST(ComicRender, BadInputGivesOneLineAndWritesNothing) {
  ScopedTempDir dir;
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::string photo = comic::test::ExampleDir() + "/image_l/000000.png";
  const std::vector<Case> cases = {
      {Scene() + " -o " + dir.File("out"), 2, "--photos is required"},
      {dir.File("none.json") + " --photos " + photo + " -o " + dir.File("out"), 1,
       "no such scene file"},
      {Scene() + " --photos " + photo + " --supersampling 0 -o " + dir.File("out"), 2,
       "supersampling must be in 1..8"},
      {Scene() + " --photos " + photo + " --seed -1 -o " + dir.File("out"), 2, "--seed"},
      {Scene() + " --photos " + dir.File("empty") + " -o " + dir.File("out"), 2, "no images"},
      // The output inside a --photos folder would write among the photographs.
      {Scene() + " --photos " + dir.File("empty") + " -o " + dir.File("empty/out"), 2,
       "lies inside the input --photos"},
  };
  std::filesystem::create_directories(dir.File("empty"));
  for (const Case& c : cases) {
    const auto result = RunCommand(AppPath("comic_render") + " " + c.args);
    EXPECT_EQ(result.exit_code, c.exit_code) << c.args << "\n" << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n" << result.output;
    EXPECT_EQ(comic::test::CountLines(result.output), 1) << result.output;
    EXPECT_FALSE(comic::io::PathExists(dir.File("out")));
    EXPECT_FALSE(comic::io::PathExists(dir.File("empty/out")));
  }
}

}  // namespace
