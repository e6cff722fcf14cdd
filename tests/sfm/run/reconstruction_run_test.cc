// RunReconstruction, the run behind comic_sfm and comic.reconstruct: in memory or into a folder,
// all or nothing, a failure as a result with its report and tracks, progress through callbacks;
// masks of moving objects leave no point on them; guessed poses only for video, never counted.
#include "sfm/run/reconstruction_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/mask_folder.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

using comic::test::ExampleDir;
using comic::test::ScopedTempDir;

ReconstructionRunOptions FiveFrames() {
  ReconstructionRunOptions options;
  options.frames = ExampleDir() + "/image_l";
  options.gt = ExampleDir() + "/poses.txt";
  options.sequence.last_frame = 4;
  return options;
}

TEST(RunReconstruction, InMemoryWritesNothingAndReportsWhatItDid) {
  std::vector<std::string> events;
  RunCallbacks callbacks;
  callbacks.inputs_resolved = [&](const RunInputs& inputs) {
    events.push_back("inputs " + std::to_string(inputs.sequence->NumFrames()));
  };
  callbacks.stage_started = [&](RunStage stage, const std::string& detector) {
    if (stage == RunStage::kTracking) events.push_back("tracking " + detector);
  };
  int frames_done = 0;
  callbacks.frame_done = [&](size_t, size_t) { ++frames_done; };
  int registered = 0;
  callbacks.frame_registered = [&](const std::string&, const MapperProgress&) { ++registered; };
  callbacks.detector_finished = [&](const DetectorRun& run) {
    events.push_back("finished " + run.detector);
  };
  const ReconstructionRunResult result = RunReconstruction(FiveFrames(), callbacks);
  ASSERT_TRUE(result.success()) << result.failure;
  ASSERT_EQ(result.runs.size(), 1u);
  const DetectorRun& run = result.runs.front();
  EXPECT_EQ(run.detector, "harris");
  EXPECT_EQ(run.run.mapping.reconstruction.NumRegisteredImages(), 5u);
  EXPECT_EQ(events, (std::vector<std::string>{"inputs 5", "tracking harris", "finished harris"}));
  EXPECT_EQ(frames_done, 5);
  EXPECT_EQ(registered, 5);
  // The camera of the ground truth (KITTI's calib.txt beside poses.txt), named as its source.
  EXPECT_EQ(result.inputs.camera.source, "ground truth " + ExampleDir() + "/poses.txt");
  EXPECT_EQ(run.report_json["camera"]["source"], result.inputs.camera.source);
  EXPECT_EQ(run.report_json["status"], "success");
  EXPECT_FALSE(run.report_json.contains("outputs"));  // nothing was written
  // Every tracker option is in the report, the alignment flags too.
  EXPECT_EQ(run.report_json["options"]["align_patches"], result.inputs.tracker.align_patches);
  EXPECT_EQ(run.report_json["options"]["bridge_frames"],
            result.inputs.tracker.continuation.bridge_frames);
  EXPECT_TRUE(run.evaluation.has_value());
}

// --loop-closure on a clip that never returns: the keyframes are searched, no loop is found, and
// the model is the one without it; report.json says so (and null without the flag). The
// tracked features are described before the mapping, for the search.
TEST(RunReconstruction, LoopClosureReportsWhatItSearched) {
  ReconstructionRunOptions options = FiveFrames();
  options.sequence.last_frame = 11;
  const ReconstructionRunResult plain = RunReconstruction(options);
  options.loop_closure = true;
  const ReconstructionRunResult closed = RunReconstruction(options);
  ASSERT_TRUE(plain.success()) << plain.failure;
  ASSERT_TRUE(closed.success()) << closed.failure;
  EXPECT_TRUE(plain.runs.front().report_json.at("loop_closure").is_null());
  const nlohmann::json& report = closed.runs.front().report_json;
  EXPECT_EQ(report["options"]["loop_closure"], true);
  const nlohmann::json& loops = report.at("loop_closure");
  ASSERT_TRUE(loops.is_object());
  EXPECT_GE(loops["keyframes_searched"].get<int>(), 3);
  EXPECT_GE(loops["ruled_out_by_odometry"].get<int>(), 0);
  EXPECT_TRUE(loops["loops"].empty());
  ASSERT_TRUE(loops["rejected"].is_array());
  EXPECT_EQ(loops["verified"].get<size_t>(), loops["loops"].size() + loops["rejected"].size());
  EXPECT_EQ(loops["points_fused"], 0);
  EXPECT_TRUE(closed.runs.front().run.tracks.HasDescriptors());
  const Reconstruction& a = plain.runs.front().run.mapping.reconstruction;
  const Reconstruction& b = closed.runs.front().run.mapping.reconstruction;
  ASSERT_EQ(a.NumPoints3D(), b.NumPoints3D());
  for (const auto& [id, point] : a.points3D()) EXPECT_EQ(point.xyz, b.point3D(id).xyz);
}

TEST(RunReconstruction, WritesEveryOutputAndCommitsAtTheEnd) {
  ScopedTempDir dir;
  ReconstructionRunOptions options = FiveFrames();
  options.output = dir.File("out");
  options.model_format = "txt";
  bool existed_during_run = true;
  RunCallbacks callbacks;
  callbacks.detector_finished = [&](const DetectorRun&) {
    existed_during_run = io::PathExists(options.output);
  };
  const ReconstructionRunResult result = RunReconstruction(options, callbacks);
  ASSERT_TRUE(result.success());
  EXPECT_FALSE(existed_during_run);  // staged beside it until the run is complete
  for (const char* name : {"cameras.txt", "images.txt", "points3D.txt", "points.ply",
                           "trajectory.png", "report.html", "report.json"}) {
    EXPECT_TRUE(io::PathExists(io::JoinPaths(options.output, name))) << name;
  }
  EXPECT_FALSE(io::PathExists(io::JoinPaths(options.output, "sparse")));
  EXPECT_EQ(result.runs.front().report_json["outputs"].size(), 8u);
  EXPECT_EQ(result.runs.front().report_json["outputs"].back(), "report.html");
}

TEST(RunReconstruction, AnErrorLeavesNoOutput) {
  ScopedTempDir dir;
  io::WriteFileAtomically(dir.File("small.txt"), "# COLMAP\n1 PINHOLE 640 480 500 500 320 240\n");
  ReconstructionRunOptions options = FiveFrames();
  options.output = dir.File("out");
  options.camera.intrinsics = dir.File("small.txt");
  try {
    RunReconstruction(options);
    ADD_FAILURE() << "a calibration for 640x480 was used on 1226x370 frames";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("640x480"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(io::PathExists(options.output));
  // Nothing else in the folder: no staging folder left behind.
  const auto entries = std::filesystem::directory_iterator(dir.path());
  EXPECT_EQ(std::distance(std::filesystem::begin(entries), std::filesystem::end(entries)), 1);
}

TEST(RunReconstruction, AFailedRunIsAResultWithItsReportAndTracks) {
  ScopedTempDir dir;
  // Three copies of one frame: tracks, but no parallax.
  const std::string frame = io::ReadFileToString(ExampleDir() + "/image_l/000000.png");
  for (const char* name : {"a.png", "b.png", "c.png"}) {
    io::EnsureWritableDirectory(dir.File("frames"));
    io::WriteFileAtomically(dir.File(std::string("frames/") + name), frame);
  }
  ReconstructionRunOptions options;
  options.frames = dir.File("frames");
  options.output = dir.File("out");
  const ReconstructionRunResult result = RunReconstruction(options);
  EXPECT_FALSE(result.success());
  EXPECT_NE(result.failure.find("; try "), std::string::npos) << result.failure;
  EXPECT_NE(result.failure.find(dir.File("out") + "/report.json"), std::string::npos);
  // The error line is the run's last: it ends with where the page is, and the page is there.
  const std::string page = ", page: " + dir.File("out") + "/report.html)";
  ASSERT_GE(result.failure.size(), page.size());
  EXPECT_EQ(result.failure.substr(result.failure.size() - page.size()), page) << result.failure;
  EXPECT_TRUE(io::PathExists(dir.File("out/report.html")));
  const DetectorRun& run = result.runs.front();
  EXPECT_TRUE(run.diagnosis.failed);
  EXPECT_TRUE(run.keeps_tracks);
  EXPECT_TRUE(io::PathExists(dir.File("out/report.json")));
  EXPECT_TRUE(io::PathExists(dir.File("out/tracks.db")));
  EXPECT_FALSE(io::PathExists(dir.File("out/points3D.txt")));
  EXPECT_EQ(run.report_json["diagnosis"]["message"], run.diagnosis.message);
}

// DAVIS car-shadow with its masks of the car (issue 47): every 3-D point of every model is
// observed only outside the masks, and the report counts the features the masks removed.
TEST(RunReconstruction, MasksLeaveNoPointObservedOnTheMovingObject) {
  COMIC_REQUIRE_SHARED_DATA();
  const std::string davis = test::SharedDataDir() + "/davis2016_car-shadow";
  ReconstructionRunOptions options;
  options.frames = davis + "/JPEGImages/480p/car-shadow";
  options.masks = davis + "/Annotations/480p/car-shadow";
  // The first 16 of 40 frames: the car crosses them too, in a third of the time.
  options.sequence.last_frame = 15;
  const ReconstructionRunResult result = RunReconstruction(options);
  ASSERT_EQ(result.runs.size(), 1u);
  const DetectorRun& run = result.runs.front();
  ASSERT_TRUE(run.success()) << run.diagnosis.message;
  EXPECT_GT(run.report_json["masked_features"].get<int64_t>(), 1000);
  const io::MaskFolder masks = io::MaskFolder::Open(options.masks);
  const RunInputs& inputs = result.inputs;
  std::vector<const Reconstruction*> models = {&run.run.mapping.reconstruction};
  for (const IncrementalModel& model : run.run.mapping.other_models) {
    models.push_back(&model.reconstruction);
  }
  size_t observations = 0;
  for (const Reconstruction* model : models) {
    for (const auto& [point3D_id, point] : model->points3D()) {
      for (const TrackElement& element : point.track) {
        const int frame = static_cast<int>(element.image_id) - 1;
        const cv::Mat mask = masks.Read(inputs.source_indices.at(frame), {});
        const Eigen::Vector2d xy = model->image(element.image_id).points2D[element.point2D_idx].xy;
        const int x = static_cast<int>(std::lround(xy.x()));
        const int y = static_cast<int>(std::lround(xy.y()));
        ASSERT_TRUE(x >= 0 && y >= 0 && x < mask.cols && y < mask.rows);
        EXPECT_EQ(mask.at<uint8_t>(y, x), 0) << "point " << point3D_id << " in frame " << frame;
        ++observations;
      }
    }
  }
  EXPECT_GT(observations, 1000u);
}

// The bag clip's first 25 frames: the verified patches give a success of 24 frames, descriptors
// then one of 25 whose cameras turn about 10 deg away from it (COLMAP's own model of these frames
// sits within 1 deg of the patches'). Two successes that disagree cannot both be right: the kept
// one is suspect, its reason names the other matcher, and the attempt records the comparison.
// The bag's first 25 frames: a nearly flat scene whose initial pairs allow two poses. Left to the
// essential matrix (--no-planar-pose-choice), the two matchers' models turn apart and the kept
// one is suspect; by default the other frames choose each pair's pose and the two agree.
TEST(RunReconstruction, TwoMatchersThatDisagreeMakeTheKeptModelSuspect) {
  COMIC_REQUIRE_SHARED_DATA();
  ReconstructionRunOptions options;
  options.frames = test::SharedDataDir() + "/vot_bag";
  options.sequence.last_frame = 24;
  options.no_planar_pose_choice = true;
  const ReconstructionRunResult result = RunReconstruction(options);
  ASSERT_EQ(result.runs.size(), 1u);
  const DetectorRun& run = result.runs.front();
  ASSERT_EQ(run.matcher_attempts.size(), 2u);
  EXPECT_EQ(run.matcher_attempts[0]["status"], "success");
  EXPECT_EQ(run.matcher_attempts[1]["status"], "success");
  EXPECT_EQ(run.run.mapping.status, ReconstructionStatus::kSuspect);
  EXPECT_EQ(run.report_json["status"], "suspect");
  const nlohmann::json& other = run.matcher_attempts[run.matcher == "descriptors" ? 0 : 1];
  EXPECT_GE(other["common_frames_with_kept"].get<int>(), 20);
  EXPECT_GT(other["median_rotation_difference_to_kept_deg"].get<double>(), 2.0);
  EXPECT_NE(run.report.self_check.reason.find("matcher's model turns the cameras"),
            std::string::npos)
      << run.report.self_check.reason;
}

TEST(RunReconstruction, TheOtherFramesChooseAPlanarPairsPoseAndTheMatchersAgree) {
  COMIC_REQUIRE_SHARED_DATA();
  ReconstructionRunOptions options;
  options.frames = test::SharedDataDir() + "/vot_bag";
  options.sequence.last_frame = 24;
  const ReconstructionRunResult result = RunReconstruction(options);
  ASSERT_EQ(result.runs.size(), 1u);
  const DetectorRun& run = result.runs.front();
  ASSERT_EQ(run.matcher_attempts.size(), 2u);
  EXPECT_EQ(run.run.mapping.status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(run.report_json["status"], "success");
  const nlohmann::json& other = run.matcher_attempts[run.matcher == "descriptors" ? 0 : 1];
  EXPECT_GE(other["common_frames_with_kept"].get<int>(), 20);
  EXPECT_LT(other["median_rotation_difference_to_kept_deg"].get<double>(), 1.0);
  EXPECT_LT(other["median_relative_rotation_difference_to_kept_deg"].get<double>(), 0.5);
  // The kept model's pair was compared by its third frames, and the report says how.
  const nlohmann::json& choices = run.report_json["mapping"]["planar_pose_choices"];
  ASSERT_FALSE(choices.empty());
  EXPECT_GE(choices[0]["third_frames"].get<int>(), 10);
}

// Seven example frames, the fourth replaced by a grey one (no features: nothing registers it).
// As a video matched over a window, the tracks cross it and it gets a pose interpolated between
// its neighbours: a guess, neither registered nor counted nor in the written model (issue 47).
// As an image set (descriptors, every pair) nothing is guessed at all.
TEST(RunReconstruction, GuessedPosesOnlyForVideoAndNeverCounted) {
  ScopedTempDir dir;
  io::EnsureWritableDirectory(dir.File("frames"));
  const std::vector<std::string> names = io::ListFiles(ExampleDir() + "/image_l");
  for (int i = 0; i < 7; ++i) {
    const std::string target = dir.File("frames/" + names[i]);
    if (i == 3) {
      const cv::Size size = io::ImageSequence::Open(ExampleDir() + "/image_l").FrameSize();
      io::WriteImageAtomically(target, cv::Mat(size, CV_8UC1, cv::Scalar(128)));
    } else {
      std::filesystem::copy_file(ExampleDir() + "/image_l/" + names[i], target);
    }
  }
  ReconstructionRunOptions video;
  video.frames = dir.File("frames");
  video.camera.intrinsics = ExampleDir() + "/calib.txt";
  video.matching = "window:3";
  video.output = dir.File("video");
  const ReconstructionRunResult filled = RunReconstruction(video);
  const DetectorRun& run = filled.runs.front();
  ASSERT_TRUE(run.success()) << run.diagnosis.message;
  const IncrementalReconstruction& mapping = run.run.mapping;
  EXPECT_EQ(mapping.interpolated_frames, std::vector<int>{3});
  EXPECT_EQ(mapping.registered_frames, (std::vector<int>{0, 1, 2, 4, 5, 6}));
  EXPECT_EQ(run.report_json["registered_frames"], 6);
  EXPECT_EQ(run.report_json["interpolated_frames"], 1);
  EXPECT_EQ(run.report_json["interpolated_poses"].size(), 1u);
  EXPECT_EQ(run.report_json["interpolated_poses"][0]["frame"], 3);
  EXPECT_EQ(run.report_json["status"], "partial");  // 6/7 < 95 %
  EXPECT_EQ(io::ReadColmapTextModel(dir.File("video")).images.size(), 6u);

  ReconstructionRunOptions image_set = video;
  image_set.matching = "exhaustive";
  image_set.matcher = "descriptors";
  image_set.output = dir.File("image_set");
  const ReconstructionRunResult unfilled = RunReconstruction(image_set);
  ASSERT_TRUE(unfilled.runs.front().success());
  EXPECT_TRUE(unfilled.runs.front().run.mapping.interpolated_frames.empty());
  EXPECT_TRUE(unfilled.runs.front().run.mapping.rotation_only_frames.empty());
  EXPECT_EQ(unfilled.runs.front().report_json["interpolated_frames"], 0);
  EXPECT_EQ(unfilled.runs.front().run.mapping.unregistered_frames, std::vector<int>{3});
}

}  // namespace
}  // namespace comic::sfm
