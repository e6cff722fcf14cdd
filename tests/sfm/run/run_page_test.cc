// report.html of a run: what each kind of run's page holds (a model with ground truth, a failed
// run, --compare), that it is written into every --output, which frames it draws, and that a
// 10 000-frame run's page stays under 20 MB.
#include "sfm/run/run_page.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "io/core/file_utils.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/run/reconstruction_run.h"
#include "sfm/run/run_page_diagnostics.h"
#include "sfm/run/run_page_frames.h"
#include "sfm/run/run_page_timeline.h"
#include "sfm/run/run_report.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

using comic::test::ExampleDir;
using comic::test::ScopedTempDir;

// The sections of `page` of `type`, in order.
std::vector<nlohmann::json> Sections(const io::HtmlPage& page, const std::string& type) {
  std::vector<nlohmann::json> found;
  for (const nlohmann::json& section : page.sections) {
    if (section["type"] == type) found.push_back(section);
  }
  return found;
}

std::string Fact(const nlohmann::json& facts, const std::string& label) {
  for (const nlohmann::json& fact : facts["facts"]) {
    if (fact["label"] == label) return fact["value"];
  }
  return "";
}

TEST(TrackFramesToDraw, SpreadsOverTheClipAndShowsWhereItWentWrong) {
  EXPECT_EQ(TrackFramesToDraw(12, 4, {}), (std::vector<int>{5, 7, 9, 11}));
  // The first unregistered frame replaces the nearest spread frame.
  EXPECT_EQ(TrackFramesToDraw(100, 4, {40, 41, 90}), (std::vector<int>{5, 40, 67, 99}));
  EXPECT_EQ(TrackFramesToDraw(2, 4, {}), (std::vector<int>{1}));
  EXPECT_TRUE(TrackFramesToDraw(12, 0, {}).empty());
  EXPECT_TRUE(TrackFramesToDraw(0, 4, {}).empty());
}

TEST(ThumbnailFrames, AllOfAShortClipAndASpreadOfALongOne) {
  EXPECT_EQ(ThumbnailFrames(3, 40), (std::vector<int>{0, 1, 2}));
  const std::vector<int> spread = ThumbnailFrames(10000, 40);
  ASSERT_EQ(spread.size(), 40u);
  EXPECT_EQ(spread.front(), 0);
  EXPECT_EQ(spread.back(), 9999);
  EXPECT_TRUE(ThumbnailFrames(10, 0).empty());
}

ReconstructionRunOptions Example(int last_frame = -1) {
  ReconstructionRunOptions options;
  options.frames = ExampleDir() + "/image_l";
  options.gt = ExampleDir() + "/poses.txt";
  options.sequence.last_frame = last_frame;
  return options;
}

// The diagnostics of a real run: a row per frame with the observations the model holds and the
// inliers the mapper reported, every observation in the histogram, the tracks shared between
// frames.
void ExpectPerFrameDiagnostics(const DetectorRun& run, const io::HtmlPage& page) {
  const Reconstruction& model = run.run.mapping.reconstruction;
  const nlohmann::json table = Sections(page, "table").at(0);
  ASSERT_EQ(table["rows"].size(), 12u);
  const std::vector<FrameDiagnostics> frames = RunFrameDiagnostics(run, 12);
  size_t observations = 0;
  int registered_by_pnp = 0;
  for (int f = 0; f < 12; ++f) {
    observations += frames[f].observations;
    registered_by_pnp += frames[f].pnp_inliers > 0;
    EXPECT_EQ(table["rows"][f][3], "registered");
    EXPECT_EQ(table["rows"][f][4], std::to_string(frames[f].observations));
    EXPECT_EQ(frames[f].observations,
              static_cast<int>(model.image(static_cast<image_t>(f + 1)).NumPoints3D()));
  }
  EXPECT_EQ(observations, model.NumObservations());
  // Every frame but the initial pair's two was registered by PnP.
  EXPECT_EQ(registered_by_pnp, 10);
  EXPECT_EQ(frames[run.run.mapping.initial_frame1].pnp_inliers, -1);
  const nlohmann::json histogram = Sections(page, "histogram").at(0);
  int64_t binned = histogram["overflow"].get<int64_t>();
  for (const nlohmann::json& count : histogram["counts"]) binned += count.get<int64_t>();
  EXPECT_EQ(binned, static_cast<int64_t>(model.NumObservations()));
  const nlohmann::json matrix = Sections(page, "heatmap").at(0);
  EXPECT_EQ(matrix["num_frames"], 12);
  EXPECT_EQ(matrix["cell_first_frames"].size(), 12u);
  EXPECT_GT(matrix["values"][1].get<int64_t>(), 0);  // frames 0 and 1 share tracks
  EXPECT_EQ(matrix["values"][0], 0);                 // a frame shares nothing with itself
}

TEST(RunPage, ShowsAModelWithItsGroundTruth) {
  const ReconstructionRunOptions options = Example();
  const ReconstructionRunResult result = RunReconstruction(options);
  ASSERT_TRUE(result.success()) << result.failure;
  const DetectorRun& run = result.runs.front();
  const io::HtmlPage page = RunPage(run, options, result.inputs);
  const std::vector<std::string> expected_types = {
      "facts", "facts", "scene",     "timeline", "lines",  "lines",  "topview",   "lines",
      "lines", "table", "histogram", "heatmap",  "images", "images", "keyvalues", "json"};
  std::vector<std::string> types;
  for (const nlohmann::json& section : page.sections) types.push_back(section["type"]);
  EXPECT_EQ(types, expected_types);
  const nlohmann::json summary = page.sections[0];
  EXPECT_EQ(Fact(summary, "status"), "success");
  EXPECT_EQ(Fact(summary, "registered"), "12 of 12 frames (100 %)");
  EXPECT_EQ(Fact(summary, "intrinsics from"), "ground truth " + ExampleDir() + "/poses.txt");
  EXPECT_NE(Fact(summary, "ATE (RMSE)").find(" m ("), std::string::npos)
      << Fact(summary, "ATE (RMSE)");
  EXPECT_TRUE(page.sections[1].value(kDurationsKey, false));  // time per stage
  // Every point in the view (a small model), every camera, the true path beside them.
  const nlohmann::json scene = Sections(page, "scene").at(0);
  EXPECT_EQ(scene["points"]["count"], run.run.mapping.reconstruction.NumPoints3D());
  EXPECT_EQ(scene["points"]["stride"], 1);
  EXPECT_EQ(scene["cameras"][0]["count"], 12);
  EXPECT_EQ(scene["paths"][0]["name"], "ground truth");
  EXPECT_EQ(scene["unit"], "m");
  // KITTI's y axis points down: up in the view is about -y.
  EXPECT_LT(scene["up"][1].get<double>(), -0.9);
  // The timeline: every frame registered in model 1.
  const nlohmann::json timeline = Sections(page, "timeline").at(0);
  EXPECT_EQ(timeline["frame_states"], nlohmann::json(std::vector<int>(12, 0)));
  EXPECT_EQ(timeline["frame_groups"], nlohmann::json(std::vector<int>(12, 0)));
  // The errors along the path are the evaluation's, in metres.
  const nlohmann::json position = Sections(page, "lines").at(0);
  EXPECT_EQ(position["y_label"], "position error (m)");
  EXPECT_EQ(position["series"][0]["y"].size(), 12u);
  EXPECT_DOUBLE_EQ(position["series"][0]["y"][3].get<double>(), run.evaluation->position_errors[3]);
  const nlohmann::json top = Sections(page, "topview").at(0);
  EXPECT_EQ(top["unit"], "m");
  EXPECT_EQ(top["right_label"], "x");
  EXPECT_EQ(top["up_label"], "z");
  // Four frames with tracks, the whole clip as thumbnails, report.json as written.
  const std::vector<nlohmann::json> images = Sections(page, "images");
  EXPECT_EQ(images.at(0)["images"].size(), 4u);
  EXPECT_EQ(images.at(1)["images"].size(), 12u);
  EXPECT_TRUE(images.at(1)["thumbnails"].get<bool>());
  EXPECT_EQ(Sections(page, "json").at(0)["document"], run.report_json);
  ExpectPerFrameDiagnostics(run, page);
}

// --keyframes: report.json lists every keyframe with its reason, and the timeline marks the
// registered keyframes (on KITTI's 12 frames, 1 m apart, every frame is one).
TEST(RunPage, MarksTheKeyframesOnTheTimeline) {
  ReconstructionRunOptions options = Example();
  options.keyframes = true;
  const ReconstructionRunResult result = RunReconstruction(options);
  ASSERT_TRUE(result.success()) << result.failure;
  DetectorRun run = result.runs.front();
  const nlohmann::json& keyframes = run.report_json.at("keyframes");
  EXPECT_EQ(keyframes["count"], 12);
  ASSERT_EQ(keyframes["reasons"].size(), 12u);
  EXPECT_EQ(keyframes["reasons"][0], "first");
  EXPECT_TRUE(keyframes["non_keyframes_lost"].empty());
  EXPECT_EQ(run.report_json["options"]["keyframes"], true);
  // Three of them as keyframes: those three cells are marked, the others plain registered.
  run.report.keyframes = {0, 5, 11};
  const io::Timeline timeline = RunTimeline(run, result.inputs.sequence->FrameNames());
  ASSERT_EQ(timeline.states.size(), 3u);
  EXPECT_EQ(timeline.states[2].key, "keyframe");
  EXPECT_EQ(timeline.states[2].style, "marked");
  std::vector<int> expected(12, 0);
  for (int f : {0, 5, 11}) expected[f] = 2;
  EXPECT_EQ(timeline.frame_states, expected);
  // Without --keyframes: no keyframes in the report, no such state.
  const ReconstructionRunResult plain = RunReconstruction(Example());
  ASSERT_TRUE(plain.success()) << plain.failure;
  EXPECT_TRUE(plain.runs.front().report_json.at("keyframes").is_null());
  EXPECT_EQ(RunTimeline(plain.runs.front(), result.inputs.sequence->FrameNames()).states.size(),
            2u);
}

// --loop-closure: the summary says what was searched and found (KITTI's 12 frames never
// return), and the end-to-start error is shown with the ground truth.
TEST(RunPage, SaysWhatLoopClosureFound) {
  ReconstructionRunOptions options = Example();
  options.loop_closure = true;
  const ReconstructionRunResult result = RunReconstruction(options);
  ASSERT_TRUE(result.success()) << result.failure;
  const io::HtmlPage page = RunPage(result.runs.front(), options, result.inputs);
  const std::string loops = Fact(page.sections[0], "loop closure");
  EXPECT_EQ(loops.rfind("no loop found among ", 0), 0u) << loops;
  EXPECT_NE(Fact(page.sections[0], "end to start").find(" m error"), std::string::npos);
  LoopClosureSummary closed;
  closed.loops.resize(5);
  closed.loops[0].query_frame = 1990;
  closed.loops[0].match_frame = 3;
  closed.num_points_fused = 180;
  closed.max_correction = 4.1;
  EXPECT_EQ(LoopClosureWords(closed).rfind("5 loops closed: frames 1990 → 3, ", 0), 0u);
  EXPECT_NE(LoopClosureWords(closed).find("…"), std::string::npos);
  EXPECT_NE(LoopClosureWords(closed).find("180 points fused"), std::string::npos);
  EXPECT_EQ(LoopClosureWords(closed).find("rejected"), std::string::npos);
  closed.rejected.resize(2);
  EXPECT_NE(LoopClosureWords(closed).find("2 verified but rejected"), std::string::npos);
  closed.loops.clear();
  EXPECT_NE(LoopClosureWords(closed).find("2 verified but rejected"), std::string::npos);
  // Without the flag: no such fact.
  const ReconstructionRunResult plain = RunReconstruction(Example());
  ASSERT_TRUE(plain.success()) << plain.failure;
  EXPECT_EQ(Fact(RunPage(plain.runs.front(), Example(), plain.inputs).sections[0], "loop closure"),
            "");
}

TEST(RunPage, ExplainsAFailedRun) {
  // One frame: no pair to start from.
  const ReconstructionRunOptions options = Example(0);
  const ReconstructionRunResult result = RunReconstruction(options);
  ASSERT_FALSE(result.success());
  const io::HtmlPage page = RunPage(result.runs.front(), options, result.inputs);
  EXPECT_EQ(Fact(page.sections[0], "status"), result.runs.front().report.status);
  EXPECT_EQ(page.sections[0]["facts"][0]["tone"], "bad");
  const std::vector<nlohmann::json> notices = Sections(page, "notice");
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_EQ(notices[0]["tone"], "bad");
  EXPECT_NE(notices[0]["text"].get<std::string>().find(result.runs.front().diagnosis.message),
            std::string::npos);
  EXPECT_TRUE(Sections(page, "scene").empty());  // nothing to draw in 3-D
  const nlohmann::json timeline = Sections(page, "timeline").at(0);
  EXPECT_EQ(timeline["frame_states"], nlohmann::json({1}));
  EXPECT_EQ(timeline["notes"][0]["first"], 0);
  EXPECT_EQ(Sections(page, "images").back()["images"].size(), 1u);  // the clip, still shown
}

TEST(RunPage, IsWrittenIntoEveryOutputAndOneForCompare) {
  ScopedTempDir dir;
  ReconstructionRunOptions options = Example(4);
  options.compare = true;
  options.detectors = "harris,fast";
  options.output = dir.File("out");
  const ReconstructionRunResult result = RunReconstruction(options);
  for (const char* page : {"report.html", "harris/report.html", "fast/report.html"}) {
    EXPECT_TRUE(io::IsRegularFile(io::JoinPaths(options.output, page))) << page;
  }
  const io::HtmlPage page = ComparisonPage(*result.comparison, result.runs, options, result.inputs);
  const nlohmann::json table = Sections(page, "table").at(0);
  EXPECT_EQ(table["links"], nlohmann::json({"harris/report.html", "fast/report.html"}));
  EXPECT_TRUE(table.value(kDurationsKey, false));
  const std::vector<nlohmann::json> bars = Sections(page, "bars");
  ASSERT_EQ(bars.size(), 2u);
  EXPECT_EQ(bars[0]["charts"][0]["y_label"], "ATE RMSE (m)");
  EXPECT_EQ(bars[0]["charts"][1]["series"][1]["name"], "fast");
  EXPECT_TRUE(bars[1].value(kDurationsKey, false));  // time per detector
  EXPECT_EQ(Sections(page, "timeline").size(), 2u);
}

// A synthetic run on `num_frames` hard-linked frames in `dir`: the largest model holds frames
// `largest`, a second model `other` (the page once drew the largest alone and called the
// other's frames unregistered).
struct TwoModelRun {
  RunInputs inputs;
  DetectorRun run;
};

TwoModelRun MakeTwoModelRun(const ScopedTempDir& dir, int num_frames,
                            const std::vector<int>& largest, const std::vector<int>& other) {
  const std::string frames = dir.File("frames");
  std::filesystem::create_directory(frames);
  cv::imwrite(dir.File("tiny.png"), cv::Mat(48, 64, CV_8UC3, cv::Scalar(90, 120, 150)));
  for (int f = 0; f < num_frames; ++f) {
    char name[32];
    std::snprintf(name, sizeof(name), "/%05d.png", f);
    EXPECT_EQ(::link(dir.File("tiny.png").c_str(), (frames + name).c_str()), 0);
  }
  TwoModelRun result;
  result.inputs.sequence = std::make_unique<io::ImageSequence>(io::ImageSequence::Open(frames));
  result.inputs.camera.camera = Camera::FromImageSize(64, 48);
  result.inputs.camera.source = "synthetic";
  DetectorRun& run = result.run;
  run.detector = "synthetic";
  run.run.input_size = cv::Size(64, 48);
  run.run.frame_size = cv::Size(64, 48);
  const auto fill = [&](const std::vector<int>& registered, Reconstruction* model) {
    const camera_t camera = model->AddCamera(result.inputs.camera.camera);
    for (int f = 0; f < num_frames; ++f) {
      Image image;
      image.camera_id = camera;
      image.name = result.inputs.sequence->FrameNames()[f];
      image.cam_from_world.translation = Eigen::Vector3d(-0.1 * f, 0, 0);
      image.points2D.resize(2);
      model->AddImage(image);
    }
    for (int f : registered) model->RegisterImage(static_cast<image_t>(f + 1));
    for (size_t k = 0; k + 1 < registered.size(); ++k) {
      const image_t a = static_cast<image_t>(registered[k] + 1);
      model->AddPoint3D(Eigen::Vector3d(0.1 * k, 0, 5.0), {{a, 0}, {a + 1, 1}}, {200, 100, 50});
    }
  };
  IncrementalReconstruction& mapping = run.run.mapping;
  fill(largest, &mapping.reconstruction);
  mapping.registered_frames = largest;
  mapping.other_models.emplace_back();
  fill(other, &mapping.other_models.back().reconstruction);
  mapping.other_models.back().registered_frames = other;
  mapping.status = ReconstructionStatus::kPartial;
  run.report =
      MakeRunReport(run.run, ComputeReconstructionStats(mapping.reconstruction), std::nullopt);
  run.report.num_frames = num_frames;  // MakeRunReport counts the tracks' frames: none here
  return result;
}

// Models that share frames (car1's two models of 234 frames): each model's count, and the frames
// only the other models hold counted once; a suspect run says why at the top.
TEST(RunPage, OverlappingModelsAreCountedOnceAndASuspectRunSaysWhy) {
  ScopedTempDir dir;
  TwoModelRun two = MakeTwoModelRun(dir, 10, {0, 1, 2, 3, 4}, {3, 4, 6, 7, 8});
  two.run.run.mapping.status = ReconstructionStatus::kSuspect;
  two.run.run.mapping.self_check.suspect = true;
  two.run.run.mapping.self_check.reason = "two rigid motions";
  ReconstructionRunOptions options;
  options.frames = dir.File("frames");
  two.run.report_json = DetectorReportJson(two.run, options, two.inputs, true);
  const nlohmann::json summary = Sections(RunPage(two.run, options, two.inputs), "facts").at(0);
  EXPECT_EQ(Fact(summary, "registered"),
            "5 of 10 frames (50 %) in the largest model; the other model holds 5 frames, 3 of them "
            "not in the largest");
  EXPECT_EQ(Fact(summary, "why suspect"), "two rigid motions");
}

// Every model on the timeline in its colour, the true count of models and of the frames they
// hold; the frames in no model alone called unregistered.
TEST(RunPage, ShowsEveryModelWithTrueCounts) {
  ScopedTempDir dir;
  TwoModelRun two = MakeTwoModelRun(dir, 10, {0, 1, 2, 3, 4}, {6, 7, 8});
  ReconstructionRunOptions options;
  options.frames = dir.File("frames");
  two.run.report_json = DetectorReportJson(two.run, options, two.inputs, true);
  const std::vector<const Reconstruction*> models = RunModels(two.run);
  ASSERT_EQ(models.size(), 2u);
  EXPECT_EQ(models[1], &two.run.run.mapping.other_models[0].reconstruction);

  const io::HtmlPage page = RunPage(two.run, options, two.inputs);
  const nlohmann::json summary = Sections(page, "facts").at(0);
  EXPECT_EQ(Fact(summary, "models"), "2");
  EXPECT_EQ(Fact(summary, "registered"),
            "5 of 10 frames (50 %) in the largest model; the other model holds 3 frames, 3 of them "
            "not in the largest");
  const nlohmann::json timeline = Sections(page, "timeline").at(0);
  EXPECT_EQ(timeline["frame_groups"], nlohmann::json({0, 0, 0, 0, 0, -1, 1, 1, 1, -1}));
  EXPECT_EQ(timeline["groups"].size(), 2u);
  EXPECT_EQ(timeline["groups"][1]["label"], "model 2 (sparse/1)");
  EXPECT_EQ(timeline["groups"][1]["color"], ModelColor(1));
  EXPECT_EQ(timeline["note"], "8 of 10 frames registered in 2 models.");
  ASSERT_EQ(timeline["notes"].size(), 2u);  // frame 5 and frame 9, nothing else
  EXPECT_EQ(timeline["notes"][0]["first"], 5);
  EXPECT_EQ(timeline["notes"][0]["last"], 5);
  EXPECT_EQ(timeline["notes"][1]["first"], 9);
  // The per-frame table names each frame's model.
  const nlohmann::json table = Sections(page, "table").at(0);
  EXPECT_EQ(table["rows"][4][2], "sparse/0");
  EXPECT_EQ(table["rows"][6][2], "sparse/1");
  EXPECT_EQ(table["rows"][5][3], "none");
}

// The intrinsics' fate in the summary line's words: a refused self-calibration is not "the motion
// did not constrain them".
TEST(RunPage, SaysTheSelfCalibrationWasRefused) {
  ScopedTempDir dir;
  TwoModelRun two = MakeTwoModelRun(dir, 4, {0, 1, 2, 3}, {});
  two.run.run.mapping.other_models.clear();
  two.inputs.camera.refine_intrinsics = true;
  two.run.report.intrinsics_rejection = "focal length 2363 px is 3.08x the prior (at most 3x)";
  ReconstructionRunOptions options;
  options.frames = dir.File("frames");
  two.run.report_json = DetectorReportJson(two.run, options, two.inputs, true);
  const nlohmann::json summary = Sections(RunPage(two.run, options, two.inputs), "facts").at(0);
  EXPECT_EQ(Fact(summary, "refined by the run"),
            "no: held at the prior (focal length 2363 px is 3.08x the prior (at most 3x))");
  EXPECT_EQ(Fact(summary, "models"), "1");
}

// A 10 000-frame run with 300 000 points (each seen by two frames) and ground truth: the page
// keeps 200 000 points, 40 thumbnails, and stays under 20 MB.
TEST(RunPage, StaysUnderTwentyMegabytesForTenThousandFrames) {
  constexpr int kFrames = 10000;
  constexpr int kPointsPerFrame = 60;
  ScopedTempDir dir;
  const std::string frames = dir.File("frames");
  std::filesystem::create_directory(frames);
  cv::Mat tiny(48, 64, CV_8UC3, cv::Scalar(90, 120, 150));
  cv::imwrite(dir.File("tiny.png"), tiny);
  for (int f = 0; f < kFrames; ++f) {  // hard links: 10 000 frames for the price of one
    char name[32];
    std::snprintf(name, sizeof(name), "/%05d.png", f);
    ASSERT_EQ(::link(dir.File("tiny.png").c_str(), (frames + name).c_str()), 0);
  }
  ReconstructionRunOptions options;
  options.frames = frames;
  RunInputs inputs;
  inputs.sequence = std::make_unique<io::ImageSequence>(io::ImageSequence::Open(frames));
  inputs.camera.camera = Camera::FromImageSize(64, 48);
  inputs.camera.source = "synthetic";
  DetectorRun run;
  run.detector = "synthetic";
  run.run.input_size = cv::Size(64, 48);  // the frames as stored = as worked
  run.run.frame_size = cv::Size(64, 48);
  Reconstruction& model = run.run.mapping.reconstruction;
  const camera_t camera = model.AddCamera(inputs.camera.camera);
  FrameGroundTruth truth;
  for (int f = 0; f < kFrames; ++f) {
    Image image;
    image.camera_id = camera;
    image.name = inputs.sequence->FrameNames()[f];
    image.cam_from_world.translation = Eigen::Vector3d(-0.1 * f, 0, 0);
    image.points2D.resize(2 * kPointsPerFrame);
    model.RegisterImage(model.AddImage(image));
    truth.cams_from_world.push_back(image.cam_from_world);
    run.run.mapping.registered_frames.push_back(f);
  }
  for (int f = 0; f + 1 < kFrames; ++f) {
    for (int k = 0; k < kPointsPerFrame; ++k) {
      const image_t a = static_cast<image_t>(f + 1);
      model.AddPoint3D(
          Eigen::Vector3d(0.1 * f, k * 0.01, 5.0),
          {{a, static_cast<point2D_t>(k)}, {a + 1, static_cast<point2D_t>(kPointsPerFrame + k)}},
          {200, 100, static_cast<uint8_t>(k)});
    }
  }
  inputs.ground_truth = truth;
  run.run.mapping.status = ReconstructionStatus::kSuccess;
  run.evaluation = EvaluateTrajectory(RegisteredPosesByName(model, inputs.sequence->FrameNames()),
                                      truth.cams_from_world);
  run.report = MakeRunReport(run.run, ComputeReconstructionStats(model), run.evaluation);
  run.report_json = DetectorReportJson(run, options, inputs, true);

  const io::HtmlPage page = RunPage(run, options, inputs);
  const nlohmann::json scene = Sections(page, "scene").at(0);
  EXPECT_EQ(scene["points"]["total"], (kFrames - 1) * kPointsPerFrame);
  EXPECT_LE(scene["points"]["count"].get<size_t>(), options.report_page.max_points);
  EXPECT_GT(scene["points"]["stride"].get<int>(), 1);  // scene.js: "showing … of … (every k-th)"
  EXPECT_EQ(scene["cameras"][0]["count"], kFrames);
  EXPECT_EQ(Sections(page, "images").back()["images"].size(), 40u);
  const size_t bytes = io::RenderHtmlPage(page, options.report_page.html).size();
  EXPECT_LT(bytes, 20u * 1000 * 1000) << bytes << " bytes";
  std::cout << "report.html of a 10 000-frame run with " << model.NumPoints3D()
            << " points: " << bytes << " bytes\n";
}

}  // namespace
}  // namespace comic::sfm
