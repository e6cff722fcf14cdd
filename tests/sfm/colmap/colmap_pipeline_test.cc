// COLMAP's own pipeline (SIFT, matcher, mapper) on the bundled frames with the real `colmap`, read
// back and measured like our runs, and the side-by-side table.
#include "sfm/colmap/colmap_pipeline.h"

#include <gtest/gtest.h>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/datasets/ground_truth_cameras.h"
#include "sfm/colmap/colmap_runner.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

TEST(ColmapPipeline, RunsColmapOnTheFramesAndComparesItsModelsWithOurs) {
  if (!IsColmapAvailable()) GTEST_SKIP() << "colmap is not installed";
  const test::ScopedTempDir folder;
  const std::string frames = test::ExampleDir() + "/image_l";
  // Three frames (COLMAP's SIFT on one thread takes seconds per frame): too few for COLMAP's
  // default initialisation under forward motion, so the run tests the plumbing and the case of
  // no model; docs/sfm.md has the runs on the evaluation clips.
  const std::vector<std::string> names = {"000000.png", "000002.png", "000004.png"};
  // The ground truth of those frames (every second of poses.txt).
  const io::GroundTruthCameras truth =
      io::ReadGroundTruthCameras(test::ExampleDir() + "/poses.txt", io::GroundTruthFormat::kAuto);
  std::vector<std::optional<Rigid3d>> poses;
  for (size_t i = 0; i < names.size(); ++i) {
    const io::GroundTruthCamera& camera = truth.cameras[2 * i];
    poses.push_back(Rigid3d(Eigen::Quaterniond(camera.cam_from_world_rotation),
                            camera.cam_from_world_translation));
  }
  ColmapPipelineOptions options;
  const ColmapPipelineRun run =
      RunColmapPipeline(frames, names, folder.File("colmap"), poses, options);
  ASSERT_EQ(run.commands.size(), 3u);
  EXPECT_NE(run.commands[0].find("feature_extractor"), std::string::npos);
  EXPECT_NE(run.commands[0].find("--SiftExtraction.num_threads 1"), std::string::npos);
  EXPECT_NE(run.commands[1].find("sequential_matcher"), std::string::npos);
  EXPECT_NE(run.commands[2].find("--Mapper.num_threads 1"), std::string::npos);
  EXPECT_EQ(run.num_frames, 3);
  EXPECT_GT(run.extraction_time_s, 0.0);
  // Whatever COLMAP's defaults make of three forward frames, the counts agree with each other.
  EXPECT_LE(run.num_registered_largest, run.num_registered_all);
  EXPECT_LE(run.num_registered_all, 3);
  if (run.largest_model_path) {
    ASSERT_FALSE(run.num_registered_per_model.empty());
    EXPECT_EQ(run.num_registered_per_model.front(), run.num_registered_largest);
    if (run.num_registered_largest >= 3) {
      ASSERT_TRUE(run.trajectory.has_value());
      EXPECT_LT(run.trajectory->ate_fraction_of_path, 0.05);
    }
  } else {
    EXPECT_EQ(run.num_registered_largest, 0);
  }
  // A folder that holds a run is refused.
  EXPECT_THROW(RunColmapPipeline(frames, names, folder.File("colmap"), poses, options), Error);

  SfmRunReport ours;
  ours.detector = "harris";
  ours.status = "success";
  ours.num_frames = 3;
  ours.stats.num_registered = 3;
  SfmModelReport model;
  model.registered_frames = {0, 1, 2};
  ours.models = {model};
  const io::ReportTable table = ColmapPipelineTable(ours, run);
  const std::string markdown = table.ToMarkdown();
  EXPECT_NE(markdown.find("comic-sfm --detector harris | success | 3/3 | 3/3 | 1"),
            std::string::npos)
      << markdown;
  EXPECT_NE(markdown.find("COLMAP 3.8 (SIFT, sequential matching, mapper)"), std::string::npos)
      << markdown;
}

}  // namespace
}  // namespace comic::sfm
