#include "sfm/colmap/colmap_runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "sfm/synthetic_scene.h"
#include "sfm/trajectory_evaluation.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

using comic::test::ScopedTempDir;

// A fake model folder whose images.bin declares `num_registered` images.
void WriteFakeModel(const std::string& folder, uint64_t num_registered) {
  std::filesystem::create_directories(folder);
  std::ofstream out(folder + "/images.bin", std::ios::binary);
  out.write(reinterpret_cast<const char*>(&num_registered), sizeof(num_registered));
}

TEST(ShellCommandLine, QuotesOnlyWhatTheShellWouldSplitOrExpand) {
  EXPECT_EQ(ShellCommandLine({"colmap", "mapper", "--database_path", "out/db.db"}),
            "colmap mapper --database_path out/db.db");
  EXPECT_EQ(ShellCommandLine({"a b", "it's", "$HOME", "", "x=1,y@2%"}),
            "'a b' 'it'\\''s' '$HOME' '' x=1,y@2%");
  // The quoting survives a round trip through the shell.
  const auto echoed =
      comic::test::RunCommand("printf '%s|' " + ShellCommandLine({"a b", "it's", "$HOME", "*"}));
  EXPECT_EQ(echoed.output, "a b|it's|$HOME|*|");
}

TEST(ColmapMapperOptions, RecommendationsFollowTheExport) {
  ColmapExportSummary summary;
  summary.known_intrinsics = true;
  summary.num_pairs_allowing_default_init = 0;
  summary.max_init_triangulation_angle_deg = 3.17;
  const ColmapMapperOptions forward = RecommendedColmapMapperOptions(summary);
  EXPECT_EQ(forward.init_max_forward_motion, 1.0);
  EXPECT_DOUBLE_EQ(forward.init_min_tri_angle, 1.5);
  EXPECT_FALSE(forward.ba_refine_focal_length);
  EXPECT_FALSE(forward.ba_refine_principal_point);
  EXPECT_FALSE(forward.ba_refine_extra_params);
  EXPECT_EQ(forward.num_threads, -1);
  EXPECT_EQ(forward.min_model_size, 3);  // summary.num_images == 0

  summary.num_images = 12;
  EXPECT_EQ(RecommendedColmapMapperOptions(summary).min_model_size, 3);
  summary.num_images = 30;
  EXPECT_EQ(RecommendedColmapMapperOptions(summary).min_model_size, 8);
  summary.num_images = 51;
  EXPECT_EQ(RecommendedColmapMapperOptions(summary).min_model_size, 10);

  summary.known_intrinsics = false;
  summary.num_pairs_allowing_default_init = 4;
  summary.max_init_triangulation_angle_deg = 25.0;
  const ColmapMapperOptions sideways = RecommendedColmapMapperOptions(summary);
  EXPECT_EQ(sideways.init_max_forward_motion, 0.95);
  EXPECT_EQ(sideways.init_min_tri_angle, 16.0);
  EXPECT_TRUE(sideways.ba_refine_focal_length);
  EXPECT_TRUE(sideways.ba_refine_extra_params);

  summary.max_init_triangulation_angle_deg = 0.1;  // never below 0.1 degrees
  EXPECT_DOUBLE_EQ(RecommendedColmapMapperOptions(summary).init_min_tri_angle, 0.1);

  ColmapMapperOptions bad;
  bad.init_max_forward_motion = 1.5;
  EXPECT_THROW(bad.Check(), Error);
  bad = ColmapMapperOptions();
  bad.num_threads = 0;
  EXPECT_THROW(bad.Check(), Error);
  bad = ColmapMapperOptions();
  bad.min_model_size = 1;
  EXPECT_THROW(bad.Check(), Error);
}

TEST(ColmapMapperArguments, ListEveryOptionExplicitly) {
  ColmapMapperOptions options;
  options.num_threads = 2;
  options.init_max_forward_motion = 1.0;
  options.init_min_tri_angle = 1.5;
  options.ba_refine_focal_length = false;
  options.ba_refine_extra_params = false;
  EXPECT_EQ(ShellCommandLine(ColmapMapperArguments("a.db", "images", "sparse", options)),
            "mapper --database_path a.db --image_path images --output_path sparse "
            "--Mapper.num_threads 2 --Mapper.init_max_forward_motion 1 "
            "--Mapper.init_min_tri_angle 1.5 --Mapper.ba_refine_focal_length 0 "
            "--Mapper.ba_refine_principal_point 0 --Mapper.ba_refine_extra_params 0 "
            "--Mapper.min_model_size 10");
  // Issue 29: the printed command for a database in comic_sfm's --output wrote over its sparse/0;
  // it writes into a folder of COLMAP's own beside the database.
  EXPECT_EQ(ColmapMapperOutputBeside("out/tracks.db"), "out/colmap/sparse");
  EXPECT_EQ(ColmapMapperOutputBeside("kitti.db"), "colmap/sparse");
  EXPECT_EQ(ColmapMapperCommandLine("my db.db", "images", "out/sparse", ColmapMapperOptions()),
            "mkdir -p out/sparse && colmap mapper --database_path 'my db.db' --image_path images "
            "--output_path out/sparse --Mapper.init_max_forward_motion 0.95 "
            "--Mapper.init_min_tri_angle 16 --Mapper.ba_refine_focal_length 1 "
            "--Mapper.ba_refine_principal_point 0 --Mapper.ba_refine_extra_params 1 "
            "--Mapper.min_model_size 10");
}

TEST(ParseColmapModelAnalyzerOutput, ReadsEveryFieldWithOrWithoutGlogPrefixes) {
  const std::string plain =
      "Cameras: 1\nImages: 51\nRegistered images: 50\nPoints: 5429\nObservations: 40559\n"
      "Mean track length: 7.469429\nMean observations per image: 795.274510\n"
      "Mean reprojection error: 0.493352px\n";
  const ColmapModelStats stats =
      ParseColmapModelAnalyzerOutput("$ colmap model_analyzer\n" + plain);
  EXPECT_EQ(stats.num_cameras, 1);
  EXPECT_EQ(stats.num_images, 51);
  EXPECT_EQ(stats.num_registered_images, 50);
  EXPECT_EQ(stats.num_points3D, 5429);
  EXPECT_EQ(stats.num_observations, 40559);
  EXPECT_DOUBLE_EQ(stats.mean_track_length, 7.469429);
  EXPECT_DOUBLE_EQ(stats.mean_observations_per_image, 795.27451);
  EXPECT_DOUBLE_EQ(stats.mean_reprojection_error, 0.493352);

  std::string glog;
  std::istringstream lines(plain);
  for (std::string line; std::getline(lines, line);) {
    glog += "I1126 11:39:03.517539 14668 model.cc:12] " + line + "\n";
  }
  EXPECT_EQ(ParseColmapModelAnalyzerOutput(glog).num_registered_images, 50);
  EXPECT_DOUBLE_EQ(ParseColmapModelAnalyzerOutput(glog).mean_reprojection_error, 0.493352);
  EXPECT_THROW(ParseColmapModelAnalyzerOutput("Cameras: 1\n"), Error);
}

// A log in COLMAP 3.8's layout (PrintHeading1 titles between lines of '=', a "Time : x [s]" line
// per bundle adjustment report): reports under "Global bundle adjustment" are global, the others
// local; only the last mapper run counts.
TEST(ParseColmapBundleAdjustmentTimes, SumsReportsByHeadingOfTheLastMapperRun) {
  const std::string bar(78, '=');
  const auto heading = [&](const std::string& title) {
    return "\n" + bar + "\n" + title + "\n" + bar + "\n";
  };
  const auto ba = [](double seconds) {
    return "\nBundle adjustment report\n" + std::string(78, '-') +
           "\n    Residuals : 100\n         Time : " + std::to_string(seconds) +
           " [s]\n Initial cost : 0.5 [px]\n";
  };
  const std::string first_run =
      "$ colmap mapper --database_path a.db\n" + heading("Global bundle adjustment") + ba(100.0);
  const std::string last_run =
      "$ colmap mapper --database_path b.db\n" + heading("Initializing with image pair #1 and #2") +
      heading("Global bundle adjustment") + ba(0.5) + heading("Registering image #3 (3)") +
      ba(0.25) + ba(0.125) + heading("Retriangulation") + heading("Global bundle adjustment") +
      ba(1.0) + "$ colmap model_analyzer --path x\nTime : 9 [s]\n";
  const ColmapBundleAdjustmentTimes times = ParseColmapBundleAdjustmentTimes(first_run + last_run);
  EXPECT_EQ(times.num_global, 2);
  EXPECT_DOUBLE_EQ(times.global_s, 1.5);
  EXPECT_EQ(times.num_local, 2);
  EXPECT_DOUBLE_EQ(times.local_s, 0.375);
  const ColmapBundleAdjustmentTimes none = ParseColmapBundleAdjustmentTimes("no reports\n");
  EXPECT_EQ(none.num_local + none.num_global, 0);
}

TEST(FindLargestColmapModel, PicksTheModelWithMostRegisteredImagesNotSparse0) {
  ScopedTempDir dir;
  EXPECT_FALSE(FindLargestColmapModel(dir.path()));
  EXPECT_FALSE(FindLargestColmapModel(dir.File("missing")));
  WriteFakeModel(dir.File("0"), 3);
  WriteFakeModel(dir.File("1"), 40);
  WriteFakeModel(dir.File("2"), 40);  // a tie goes to the lower number
  WriteFakeModel(dir.File("10"), 7);
  WriteFakeModel(dir.File("snapshot"), 99);            // not a numbered model
  std::filesystem::create_directories(dir.File("3"));  // no images file
  const auto largest = FindLargestColmapModel(dir.path());
  ASSERT_TRUE(largest);
  EXPECT_EQ(std::filesystem::path(*largest).filename(), "1");
  EXPECT_EQ(NumRegisteredImagesOfColmapModel(dir.File("10")), 7);
  EXPECT_THROW(NumRegisteredImagesOfColmapModel(dir.File("3")), Error);
}

TEST(RunColmap, ReportsFailuresWithTheCommandTheLastLineAndTheLog) {
  ScopedTempDir dir;
  const std::string log = dir.File("run.log");
  // Any program goes through the same path: a shell standing in for colmap.
  RunColmap({"-c", "echo display=$QT_QPA_PLATFORM; echo to-stderr >&2"}, log, "/bin/sh");
  const std::string text = io::ReadFileToString(log);
  EXPECT_NE(text.find("$ /bin/sh -c"), std::string::npos) << text;
  EXPECT_NE(text.find("display=offscreen"), std::string::npos) << text;
  EXPECT_NE(text.find("to-stderr"), std::string::npos) << text;
  try {
    RunColmap({"-c", "echo working; echo 'ERROR: no good initial pair'; exit 3"}, log, "/bin/sh");
    ADD_FAILURE() << "no error for exit status 3";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kExternal);
    const std::string what = e.what();
    EXPECT_NE(what.find("exit status 3"), std::string::npos) << what;
    EXPECT_NE(what.find("ERROR: no good initial pair"), std::string::npos) << what;
    EXPECT_NE(what.find(log), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
  try {
    RunColmap({"mapper"}, log, "comic-no-such-program");
    ADD_FAILURE() << "no error for a missing program";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kExternal);
    EXPECT_NE(std::string(e.what()).find("cannot start"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(IsColmapAvailable("comic-no-such-program"));
  EXPECT_TRUE(IsColmapAvailable("sh"));
  EXPECT_TRUE(IsColmapAvailable("/bin/sh"));
}

// The real COLMAP on a synthetic forward-moving sequence (like the KITTI clip) exported with
// known intrinsics: with the recommended options it registers every frame, its model analyzer
// agrees with the model it wrote, and its poses match the truth.
TEST(RunColmapMapper, ReconstructsASyntheticForwardSequenceWithTheRecommendedOptions) {
  if (!IsColmapAvailable()) GTEST_SKIP() << "colmap is not installed";
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kForward;
  scene_options.num_frames = 10;
  scene_options.num_points = 1500;
  scene_options.outlier_ratio = 0.05;
  scene_options.noise_px = 0.3;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  ScopedTempDir dir;
  std::filesystem::create_directories(dir.File("images"));  // COLMAP only reads colours there
  const ColmapExportSummary summary = ExportTracksToColmapDatabase(
      scene.tracks, scene.camera, ColmapExportOptions(), dir.File("db.db"), false);
  ColmapMapperOptions options = RecommendedColmapMapperOptions(summary);
  EXPECT_EQ(options.init_max_forward_motion, 1.0) << "forward motion not detected";
  options.num_threads = 2;
  const std::string log = dir.File("colmap.log");
  const auto model =
      RunColmapMapper(dir.File("db.db"), dir.File("images"), dir.File("sparse"), options, log);
  ASSERT_TRUE(model) << io::ReadFileToString(log);
  const ColmapModelStats stats = AnalyzeColmapModel(*model, log);
  EXPECT_EQ(stats.num_images, 10);
  EXPECT_EQ(stats.num_registered_images, 10);
  EXPECT_LT(stats.mean_reprojection_error, 1.0);
  EXPECT_GT(stats.num_points3D, 500);
  // The real mapper's log holds local and global bundle adjustment reports with their times.
  const ColmapBundleAdjustmentTimes ba_times =
      ParseColmapBundleAdjustmentTimes(io::ReadFileToString(log));
  EXPECT_GT(ba_times.num_local, 0);
  EXPECT_GT(ba_times.num_global, 0);
  EXPECT_GE(ba_times.local_s, 0.0);
  EXPECT_GE(ba_times.global_s, 0.0);

  // Read back as text; the camera is ours, held fixed; poses match the truth up to Sim(3).
  ConvertColmapModel(*model, dir.File("text"), "TXT", log);
  const io::ColmapTextModel text = io::ReadColmapTextModel(dir.File("text"));
  ASSERT_EQ(text.cameras.size(), 1u);
  EXPECT_EQ(text.cameras[0].model, "PINHOLE");
  EXPECT_DOUBLE_EQ(text.cameras[0].params[2], scene.camera.cx + 0.5);
  std::vector<std::optional<Rigid3d>> estimated(scene.cams_from_world.size());
  std::vector<std::optional<Rigid3d>> truth(scene.cams_from_world.begin(),
                                            scene.cams_from_world.end());
  for (const io::ColmapImage& image : text.images) {
    estimated.at(image.image_id - 1) =
        Rigid3d(image.cam_from_world_rotation, image.cam_from_world_translation);
  }
  const auto evaluation = EvaluateTrajectory(estimated, truth);
  ASSERT_TRUE(evaluation);
  EXPECT_EQ(evaluation->frames.size(), 10u);
  EXPECT_LT(evaluation->ate_fraction_of_path, 0.01);
  EXPECT_LT(evaluation->mean_rotation_error_deg, 0.2);

  // A second run into the same folder is refused: models are never mixed.
  EXPECT_THROW(
      RunColmapMapper(dir.File("db.db"), dir.File("images"), dir.File("sparse"), options, log),
      Error);
}

// No parallax at all (a camera panning on the spot): COLMAP finds no initial pair, exits with
// status 1, and that is reported as "no model", not as an error.
TEST(RunColmapMapper, NoInitialPairGivesNoModel) {
  if (!IsColmapAvailable()) GTEST_SKIP() << "colmap is not installed";
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kPureRotation;
  scene_options.num_frames = 4;
  scene_options.num_points = 400;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  ScopedTempDir dir;
  std::filesystem::create_directories(dir.File("images"));
  ExportTracksToColmapDatabase(scene.tracks, scene.camera, ColmapExportOptions(), dir.File("db.db"),
                               false);
  ColmapMapperOptions options;
  options.num_threads = 2;
  const std::string log = dir.File("colmap.log");
  const auto model =
      RunColmapMapper(dir.File("db.db"), dir.File("images"), dir.File("sparse"), options, log);
  EXPECT_FALSE(model);
  EXPECT_NE(io::ReadFileToString(log).find("No good initial image pair found"), std::string::npos);
  // A database COLMAP cannot read is an error, not "no model".
  io::WriteFileAtomically(dir.File("bad.db"), "not a database\n");
  EXPECT_THROW(
      RunColmapMapper(dir.File("bad.db"), dir.File("images"), dir.File("sparse2"), options, log),
      Error);
}

}  // namespace
}  // namespace comic::sfm
