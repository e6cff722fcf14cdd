#include "sfm/colmap/colmap_comparison.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "sfm/synthetic_scene.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

using comic::test::ScopedTempDir;

TEST(ColmapComparisonOptions, RejectsBadValues) {
  ColmapComparisonOptions options;
  EXPECT_NO_THROW(options.Check());
  options.colmap_threads = 0;
  EXPECT_THROW(options.Check(), Error);
  options = ColmapComparisonOptions();
  options.export_options.pair_window = 0;
  EXPECT_THROW(options.Check(), Error);
}

TEST(ColmapComparison, TableHasOneRowPerMethodAndEmptyCellsWithoutGroundTruth) {
  ColmapComparison comparison;
  ColmapComparisonRow ours;
  ours.method = "comic-sfm";
  ours.num_frames = 12;
  ours.num_registered = 11;
  ours.num_points3D = 800;
  ours.mean_track_length = 4.5;
  ours.mean_reprojection_error_px = 0.4;
  ours.ate_rmse = 0.05;
  ours.ate_fraction_of_path = 0.004;
  ours.rotation_error_deg = 0.1;
  ours.wall_time_s = 2.0;
  ColmapComparisonRow colmap = ours;
  colmap.method = "COLMAP 3.8 mapper";
  colmap.ate_rmse.reset();
  colmap.ate_fraction_of_path.reset();
  colmap.rotation_error_deg.reset();
  comparison.rows = {ours, colmap};
  const io::ReportTable table = comparison.Table();
  ASSERT_EQ(table.NumRows(), 2u);
  EXPECT_EQ(std::get<std::string>(table.At(0, 1)), "11/12");
  EXPECT_DOUBLE_EQ(std::get<double>(table.At(0, 6)), 0.4);  // ATE as % of the path
  EXPECT_TRUE(std::holds_alternative<std::monostate>(table.At(1, 5)));
  const std::string markdown = table.ToMarkdown();
  EXPECT_NE(markdown.find("COLMAP 3.8 mapper"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("mean reprojection error (px)"), std::string::npos) << markdown;
}

// The whole comparison with the real COLMAP on a synthetic hand-held sequence with known
// cameras: both mappers register every frame and land near the truth, and our model read back
// through COLMAP has the same frames, points and poses as ours.
TEST(ColmapComparison, RunsBothMappersAndReadsOurModelBackThroughColmap) {
  if (!IsColmapAvailable()) GTEST_SKIP() << "colmap is not installed";
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kHandHeld;
  scene_options.num_frames = 10;
  scene_options.num_points = 1500;
  scene_options.outlier_ratio = 0.05;
  scene_options.noise_px = 0.3;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  const std::vector<std::optional<Rigid3d>> truth(scene.cams_from_world.begin(),
                                                  scene.cams_from_world.end());
  ScopedTempDir dir;
  std::filesystem::create_directories(dir.File("images"));
  ColmapComparisonOptions options;
  options.colmap_threads = 2;
  const ColmapComparison comparison = CompareWithColmap(
      scene.tracks, scene.camera, true, truth, dir.File("images"), dir.File("work"), options);

  ASSERT_EQ(comparison.rows.size(), 3u);
  const ColmapComparisonRow& ours = comparison.rows[0];
  const ColmapComparisonRow& colmap = comparison.rows[1];
  const ColmapComparisonRow& read_back = comparison.rows[2];
  EXPECT_EQ(ours.method, "comic-sfm");
  EXPECT_EQ(colmap.method, "COLMAP 3.8 mapper");
  EXPECT_EQ(read_back.method, "comic-sfm read by COLMAP");
  for (const ColmapComparisonRow& row : comparison.rows) {
    EXPECT_EQ(row.num_frames, 10) << row.method;
    EXPECT_EQ(row.num_registered, 10) << row.method;
    EXPECT_GT(row.num_points3D, 300) << row.method;
    EXPECT_GT(row.mean_track_length, 2.0) << row.method;
    EXPECT_LT(row.mean_reprojection_error_px, 1.0) << row.method;
    ASSERT_TRUE(row.ate_fraction_of_path) << row.method;
    EXPECT_LT(*row.ate_fraction_of_path, 0.01) << row.method;
    ASSERT_TRUE(row.rotation_error_deg) << row.method;
    EXPECT_LT(*row.rotation_error_deg, 0.5) << row.method;
  }
  // Every frame is common to both models here, so the common-frame ATE is the ATE.
  for (const ColmapComparisonRow& row : comparison.rows) {
    ASSERT_TRUE(row.common_ate_rmse) << row.method;
    EXPECT_EQ(row.num_common_frames, 10) << row.method;
    EXPECT_NEAR(*row.common_ate_rmse, *row.ate_rmse, 1e-12) << row.method;
  }
  ASSERT_TRUE(ours.wall_time_s && colmap.wall_time_s);
  EXPECT_FALSE(read_back.wall_time_s);
  // COLMAP reads exactly what we wrote.
  EXPECT_EQ(read_back.num_points3D, ours.num_points3D);
  EXPECT_NEAR(read_back.mean_track_length, ours.mean_track_length, 1e-5);
  EXPECT_NEAR(read_back.mean_reprojection_error_px, ours.mean_reprojection_error_px, 1e-5);
  EXPECT_NEAR(*read_back.ate_rmse, *ours.ate_rmse, 1e-6);
  EXPECT_NEAR(*read_back.rotation_error_deg, *ours.rotation_error_deg, 1e-6);

  ASSERT_TRUE(comparison.colmap_model_path);
  EXPECT_TRUE(io::IsRegularFile(io::JoinPaths(*comparison.colmap_model_path, "images.bin")));
  EXPECT_NE(comparison.colmap_mapper_command.find("--Mapper.ba_refine_focal_length 0"),
            std::string::npos);
  EXPECT_EQ(comparison.export_summary.num_images, 10);
  EXPECT_TRUE(io::IsRegularFile(dir.File("work/ours_text/points3D.txt")));
  EXPECT_TRUE(io::IsRegularFile(dir.File("work/ours_bin/points3D.bin")));
  EXPECT_EQ(comparison.Table().NumRows(), 3u);

  // A folder holding a comparison is not reused.
  EXPECT_THROW(CompareWithColmap(scene.tracks, scene.camera, true, truth, dir.File("images"),
                                 dir.File("work"), options),
               Error);
}

}  // namespace
}  // namespace comic::sfm
