#include "io/core/protected_inputs.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/core/error.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

namespace fs = std::filesystem;
using comic::test::ScopedTempDir;

class ProtectedInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_.File("frames/sub"));
    std::ofstream(dir_.File("frames/000000.png")) << "image";
    std::ofstream(dir_.File("img.png")) << "image";
  }
  ScopedTempDir dir_;
};

TEST_F(ProtectedInputs, TheSameFileByAnyNameIsTheInput) {
  const std::string image = dir_.File("img.png");
  EXPECT_TRUE(IsSameOrInside(image, image));
  EXPECT_TRUE(IsSameOrInside(dir_.File("frames/../img.png"), image));
  fs::create_symlink(image, dir_.File("link.png"));
  EXPECT_TRUE(IsSameOrInside(dir_.File("link.png"), image));
  fs::create_hard_link(image, dir_.File("hard.png"));
  EXPECT_TRUE(IsSameOrInside(dir_.File("hard.png"), image));
  // Relative to the working folder.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_.path());
  EXPECT_TRUE(IsSameOrInside("./img.png", image));
  EXPECT_TRUE(IsSameOrInside("img.png", "./frames/../img.png"));
  fs::current_path(cwd);
}

TEST_F(ProtectedInputs, PathsInsideAnInputFolderAreInside) {
  const std::string frames = dir_.File("frames");
  EXPECT_TRUE(IsSameOrInside(frames, frames));
  EXPECT_TRUE(IsSameOrInside(dir_.File("frames/000000.png"), frames));
  EXPECT_TRUE(IsSameOrInside(dir_.File("frames/trajectory.png"), frames));  // not there yet
  EXPECT_TRUE(IsSameOrInside(dir_.File("frames/new/deeper/x.json"), frames));
  EXPECT_TRUE(IsSameOrInside(dir_.File("frames/sub/../x.db"), frames));
  fs::create_directory_symlink(frames, dir_.File("frames_link"));
  EXPECT_TRUE(IsSameOrInside(dir_.File("frames_link/x.db"), frames));
}

TEST_F(ProtectedInputs, OtherPathsAreNot) {
  const std::string frames = dir_.File("frames");
  EXPECT_FALSE(IsSameOrInside(dir_.File("out"), frames));
  EXPECT_FALSE(IsSameOrInside(dir_.File("frames2/x.png"), frames));
  EXPECT_FALSE(IsSameOrInside(dir_.File("frames/../out/x.png"), frames));
  EXPECT_FALSE(IsSameOrInside(dir_.File("img.png"), frames));
  EXPECT_FALSE(IsSameOrInside(dir_.File("frames/000000.png"), dir_.File("img.png")));
  // A copy is another file; a missing input holds nothing; an unset option is skipped.
  fs::copy_file(dir_.File("img.png"), dir_.File("copy.png"));
  EXPECT_FALSE(IsSameOrInside(dir_.File("copy.png"), dir_.File("img.png")));
  EXPECT_FALSE(IsSameOrInside(dir_.File("missing/x"), dir_.File("missing")));
  EXPECT_FALSE(IsSameOrInside("", frames));
  EXPECT_FALSE(IsSameOrInside(frames, ""));
}

TEST_F(ProtectedInputs, TheErrorNamesOutputOptionAndInput) {
  const std::string image = dir_.File("img.png");
  try {
    CheckOutputsAvoidInputs({{"--overlay", ""}, {"--json", image}}, {{"IMAGE", image}});
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_EQ(std::string(e.what()), image +
                                         ": --json is the input IMAGE; refusing to write over "
                                         "an input");
  }
  try {
    CheckOutputsAvoidInputs({{"--output", dir_.File("frames/out")}},
                            {{"--gt", ""}, {"FRAMES", dir_.File("frames")}});
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--output lies inside the input FRAMES folder"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(
      CheckOutputsAvoidInputs({{"--output", dir_.File("out")}}, {{"FRAMES", dir_.File("frames")}}));
}

// comic_render fills its output folder with files of its own naming (images/000000.png,
// scene.json): an input inside that folder could be replaced, so it is refused too.
TEST_F(ProtectedInputs, AnOutputFolderMayNotHoldAnInput) {
  const std::string photo = dir_.File("frames/000000.png");
  try {
    CheckOutputFolderAvoidsInputs({"--output", dir_.File("frames")},
                                  {{"SCENE", dir_.File("img.png")}, {"--photos", photo}});
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_EQ(std::string(e.what()), dir_.File("frames") + ": --output holds the input --photos " +
                                         photo + "; refusing to write where it could be replaced");
  }
  // The output inside an input folder is refused as by CheckOutputsAvoidInputs.
  EXPECT_THROW(CheckOutputFolderAvoidsInputs({"--output", dir_.File("frames/sub")},
                                             {{"--photos", dir_.File("frames")}}),
               Error);
  // Beside the inputs, or with unset (empty) inputs, or a folder that does not exist yet: fine.
  EXPECT_NO_THROW(CheckOutputFolderAvoidsInputs({"--output", dir_.File("out")},
                                                {{"--nerf", ""}, {"--photos", photo}}));
  EXPECT_NO_THROW(CheckOutputFolderAvoidsInputs({"--output", dir_.File("frames/sub")},
                                                {{"--photos", dir_.File("img.png")}}));
}

// comic_sfm writes chosen files and folders into --output: an input at one of them, inside one
// (a model in sparse/0 when sparse/ is written) or holding one is refused; one beside them is not.
TEST_F(ProtectedInputs, WrittenPathsMayNotBeOrHoldAnInput) {
  fs::create_directories(dir_.File("proj/sparse/0"));
  fs::create_directories(dir_.File("proj/images"));
  std::ofstream(dir_.File("proj/sparse/0/cameras.txt")) << "model";
  std::ofstream(dir_.File("proj/cameras.txt")) << "calibration";
  const std::vector<NamedPath> written = {{"--output", dir_.File("proj/cameras.txt")},
                                          {"--output", dir_.File("proj/sparse")}};
  try {
    CheckWrittenPathsAvoidInputs(written, {{"--gt", dir_.File("proj/sparse/0")}});
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_EQ(std::string(e.what()),
              dir_.File("proj/sparse/0") + ": the input --gt would be replaced: --output writes " +
                  dir_.File("proj/sparse") + "; refusing (choose another --output)");
  }
  EXPECT_THROW(CheckWrittenPathsAvoidInputs(
                   written, {{"--intrinsics", dir_.File("proj/images/../cameras.txt")}}),
               Error);
  EXPECT_THROW(CheckWrittenPathsAvoidInputs(written, {{"FRAMES", dir_.File("proj/sparse")}}),
               Error);
  // The written folder inside an input folder.
  EXPECT_THROW(CheckWrittenPathsAvoidInputs({{"--write-frames", dir_.File("frames/sub")}},
                                            {{"FRAMES", dir_.File("frames")}}),
               Error);
  // A COLMAP project's images/ as FRAMES, beside what the run writes; unset paths.
  EXPECT_NO_THROW(CheckWrittenPathsAvoidInputs(
      written, {{"FRAMES", dir_.File("proj/images")}, {"--gt", ""}, {"--masks", dir_.File("x")}}));
  EXPECT_NO_THROW(
      CheckWrittenPathsAvoidInputs({{"--colmap-db", ""}}, {{"FRAMES", dir_.File("proj/images")}}));
}

}  // namespace
}  // namespace comic::io
