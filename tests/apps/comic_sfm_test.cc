// comic_sfm end to end on the bundled KITTI example: outputs (COLMAP text and binary models, the
// latter also read by the real `colmap model_analyzer`; binary and ASCII PLY; report, plot),
// progress lines, bit-for-bit repeatable results, --compare, and bad input failing early with
// one line.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_database.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/file_utils.h"
#include "io/report/ply.h"
#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

std::string Example() { return comic::test::ExampleDir(); }

int CountOccurrences(const std::string& text, const std::string& what) {
  int count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

// The last line of a command's output (without its newline).
std::string LastLine(const std::string& text) {
  std::string trimmed = text;
  while (!trimmed.empty() && trimmed.back() == '\n') trimmed.pop_back();
  const size_t start = trimmed.rfind('\n');
  return start == std::string::npos ? trimmed : trimmed.substr(start + 1);
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

TEST(ComicSfm, HelpDocumentsEveryOption) {
  const auto result = RunCommand(AppPath("comic_sfm") + " --help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* option : {"--detector",
                             "--compare",
                             "--detectors",
                             "--intrinsics",
                             "--gt",
                             "--gt-format",
                             "--output",
                             "--resize-height",
                             "--first",
                             "--last",
                             "--stride",
                             "--max-features",
                             "--search-radius",
                             "--unpredicted-radius",
                             "--prediction",
                             "--coarse-radius",
                             "--max-cost",
                             "--matching",
                             "--refine-focal",
                             "--no-retriangulate",
                             "--local-ba-images",
                             "--init-angle",
                             "--init-max-gap",
                             "--threads",
                             "--regions",
                             "--masks",
                             "--boundary-band",
                             "--plot-plane",
                             "--model-format",
                             "--ply-format",
                             "--undistort",
                             "--quiet"}) {
    EXPECT_NE(result.output.find(option), std::string::npos) << option;
  }
}

// Without a calibration (the truth used for evaluation only): COLMAP's SIMPLE_RADIAL default,
// every frame registered, and the forward drive reported focal-unobservable with the prior kept,
// in report.json, the summary line and the COLMAP model.
TEST(ComicSfm, WithoutIntrinsicsReportsTheFocalUnobservableOnForwardMotion) {
  ScopedTempDir dir;
  const auto result =
      RunCommand(AppPath("comic_sfm") + " " + Example() + "/image_l --gt " + Example() +
                 "/poses.txt --ignore-gt-intrinsics --quiet --output " + dir.File("a"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("12/12 frames registered"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("camera SIMPLE_RADIAL f=1471.2"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("focal unobservable"), std::string::npos) << result.output;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("a/report.json")));
  const nlohmann::json& camera = report.at("camera");
  EXPECT_EQ(camera.at("focal_observable"), false);
  EXPECT_LT(camera.at("max_viewing_angle_deg").get<double>(), 5.0);
  EXPECT_EQ(camera.at("final").at("model"), "SIMPLE_RADIAL");
  EXPECT_DOUBLE_EQ(camera.at("focal_length_px").get<double>(), 1.2 * 1226);
  const comic::io::ColmapTextModel model = comic::io::ReadColmapTextModel(dir.File("a"));
  ASSERT_EQ(model.cameras.size(), 1u);
  EXPECT_EQ(model.cameras[0].model, "SIMPLE_RADIAL");
  EXPECT_EQ(model.cameras[0].params.size(), 4u);
}

// A calibration with distortion (OpenCV YAML) reaches the COLMAP model as OPENCV.
TEST(ComicSfm, OpenCvCalibrationWritesAnOpenCvCamera) {
  ScopedTempDir dir;
  {
    std::ofstream yaml(dir.File("calib.yml"));
    yaml << "%YAML:1.0\n---\nimage_width: 1226\nimage_height: 370\n"
            "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
            "   data: [ 707.0912, 0., 601.8873, 0., 707.0912, 183.1104, 0., 0., 1. ]\n"
            "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n"
            "   data: [ 0.001, 0., 0., 0., 0. ]\n";
  }
  const auto result = RunCommand(AppPath("comic_sfm") + " " + Example() + "/image_l --intrinsics " +
                                 dir.File("calib.yml") + " --quiet --output " + dir.File("a"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("12/12 frames registered"), std::string::npos) << result.output;
  const comic::io::ColmapTextModel model = comic::io::ReadColmapTextModel(dir.File("a"));
  ASSERT_EQ(model.cameras.size(), 1u);
  EXPECT_EQ(model.cameras[0].model, "OPENCV");
  EXPECT_EQ(model.cameras[0].params, (std::vector<double>{707.0912, 707.0912, 601.8873 + 0.5,
                                                          183.1104 + 0.5, 0.001, 0, 0, 0}));
}

TEST(ComicSfm, ReconstructsTheBundledExampleRepeatably) {
  ScopedTempDir dir;
  const std::string command = AppPath("comic_sfm") + " " + Example() + "/image_l --gt " +
                              Example() + "/poses.txt --output ";
  const auto result = RunCommand(command + dir.File("a"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // One progress line per registered frame (the initial pair's two included).
  EXPECT_EQ(CountOccurrences(result.output, "[harris] registered "), 12) << result.output;
  EXPECT_NE(result.output.find("12/12 frames registered"), std::string::npos) << result.output;
  // The last line, the summary, ends with where the page is, and the page is there.
  const std::string last = LastLine(result.output);
  EXPECT_EQ(last.rfind("[harris] success: 12/12 frames registered", 0), 0u) << last;
  EXPECT_TRUE(EndsWith(last, "; page: " + dir.File("a") + "/report.html")) << last;
  EXPECT_TRUE(comic::io::IsRegularFile(dir.File("a/report.html")));

  const comic::io::ColmapTextModel model = comic::io::ReadColmapTextModel(dir.File("a"));
  ASSERT_EQ(model.cameras.size(), 1u);
  EXPECT_EQ(model.cameras[0].model, "PINHOLE");
  // calib.txt beside poses.txt: fx = 707.0912, cx = 601.8873 (+ 0.5 in COLMAP's convention).
  EXPECT_DOUBLE_EQ(model.cameras[0].params[0], 707.0912);
  EXPECT_DOUBLE_EQ(model.cameras[0].params[2], 601.8873 + 0.5);
  EXPECT_EQ(model.images.size(), 12u);
  EXPECT_GT(model.points3D.size(), 500u);
  const std::vector<comic::io::PlyPoint> cloud = comic::io::ReadPly(dir.File("a/points.ply"));
  EXPECT_EQ(cloud.size(), model.points3D.size());
  // By default the PLY is binary (float xyz, uchar rgb) and the model is also in COLMAP's binary
  // format under sparse/0/, with exactly the text model's numbers.
  EXPECT_EQ(comic::io::ReadFileToString(dir.File("a/points.ply"))
                .rfind("ply\nformat binary_little_endian 1.0\n", 0),
            0u);
  const comic::io::ColmapTextModel binary =
      comic::io::ReadColmapBinaryModel(dir.File("a/sparse/0"));
  EXPECT_EQ(comic::io::ColmapCamerasText(binary), comic::io::ColmapCamerasText(model));
  EXPECT_EQ(comic::io::ColmapImagesText(binary), comic::io::ColmapImagesText(model));
  EXPECT_EQ(comic::io::ColmapPoints3DText(binary), comic::io::ColmapPoints3DText(model));
  if (RunCommand("command -v colmap").exit_code == 0) {
    // The real COLMAP reads the binary model (only the .bin files are in sparse/0/).
    EXPECT_FALSE(comic::io::PathExists(dir.File("a/sparse/0/cameras.txt")));
    const auto analyzed = RunCommand("QT_QPA_PLATFORM=offscreen colmap model_analyzer --path " +
                                     dir.File("a/sparse/0"));
    ASSERT_EQ(analyzed.exit_code, 0) << analyzed.output;
    EXPECT_NE(analyzed.output.find("Cameras: 1"), std::string::npos) << analyzed.output;
    EXPECT_NE(analyzed.output.find("Registered images: 12"), std::string::npos) << analyzed.output;
    EXPECT_NE(analyzed.output.find("Points: " + std::to_string(model.points3D.size())),
              std::string::npos)
        << analyzed.output;
  }
  const cv::Mat plot = cv::imread(dir.File("a/trajectory.png"));
  EXPECT_EQ(plot.cols, 900);

  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("a/report.json")));
  EXPECT_EQ(report["status"], "success");
  EXPECT_EQ(report["registered_frames"], 12);
  EXPECT_EQ(report["points3D"]["points"], model.points3D.size());
  EXPECT_LT(report["ground_truth"]["ate_fraction_of_path"].get<double>(), 0.01);
  EXPECT_EQ(report["detector"], "harris");
  EXPECT_EQ(report["options"]["max_features"], 2000);
  // A clean drive: the patch tracker, every pair verified, holds every frame; descriptors are
  // not tried.
  EXPECT_EQ(report["matcher_attempts"].size(), 1u) << report["matcher_attempts"].dump();
  EXPECT_EQ(report["options"]["matcher"], "patches");
  EXPECT_EQ(report["options"]["verify_min_gap"], 1);

  // Same input and options: the same model, bit for bit, with any --threads (the default, 0, is
  // one per core; 1 here).
  ASSERT_EQ(RunCommand(command + dir.File("b") + " --quiet --threads 1").exit_code, 0);
  for (const char* file :
       {"cameras.txt", "images.txt", "points3D.txt", "points.ply", "sparse/0/cameras.bin",
        "sparse/0/images.bin", "sparse/0/points3D.bin"}) {
    EXPECT_EQ(comic::io::ReadFileToString(dir.File(std::string("a/") + file)),
              comic::io::ReadFileToString(dir.File(std::string("b/") + file)))
        << file;
  }
}

TEST(ComicSfm, ModelAndPlyFormatsAreChosenByFlags) {
  ScopedTempDir dir;
  const std::string command = AppPath("comic_sfm") + " " + Example() + "/image_l --last 5 --gt " +
                              Example() + "/poses.txt --quiet --output ";
  const auto text =
      RunCommand(command + dir.File("txt") + " --model-format txt --ply-format ascii");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_TRUE(comic::io::IsRegularFile(dir.File("txt/cameras.txt")));
  EXPECT_FALSE(comic::io::PathExists(dir.File("txt/sparse")));
  EXPECT_EQ(
      comic::io::ReadFileToString(dir.File("txt/points.ply")).rfind("ply\nformat ascii 1.0\n", 0),
      0u);
  const auto binary = RunCommand(command + dir.File("bin") + " --model-format bin");
  ASSERT_EQ(binary.exit_code, 0) << binary.output;
  EXPECT_FALSE(comic::io::PathExists(dir.File("bin/cameras.txt")));
  const comic::io::ColmapTextModel model =
      comic::io::ReadColmapBinaryModel(dir.File("bin/sparse/0"));
  // Same run, same numbers: the binary model holds what the text one holds.
  EXPECT_EQ(comic::io::ColmapImagesText(model),
            comic::io::ColmapImagesText(comic::io::ReadColmapTextModel(dir.File("txt"))));
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("bin/report.json")));
  EXPECT_EQ(report["outputs"],
            nlohmann::json({"sparse/0/cameras.bin", "sparse/0/images.bin", "sparse/0/points3D.bin",
                            "points.ply", "trajectory.png", "transforms.json", "trajectory_tum.txt",
                            "report.html"}));
  // The PLYs hold the same points, the binary one to float precision.
  const auto ascii_cloud = comic::io::ReadPly(dir.File("txt/points.ply"));
  const auto binary_cloud = comic::io::ReadPly(dir.File("bin/points.ply"));
  ASSERT_EQ(ascii_cloud.size(), binary_cloud.size());
  ASSERT_FALSE(ascii_cloud.empty());
  for (size_t i = 0; i < ascii_cloud.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(binary_cloud[i].xyz[k], static_cast<float>(ascii_cloud[i].xyz[k]));
    }
    EXPECT_EQ(binary_cloud[i].rgb, ascii_cloud[i].rgb);
  }
}

TEST(ComicSfm, CompareWritesOneTable) {
  ScopedTempDir dir;
  const auto result =
      RunCommand(AppPath("comic_sfm") + " " + Example() + "/image_l --last 5 --gt " + Example() +
                 "/poses.txt --compare --detectors harris,fast --quiet --output " + dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::string markdown = comic::io::ReadFileToString(dir.File("compare.md"));
  EXPECT_NE(markdown.find("| harris"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| fast"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("ATE % of path"), std::string::npos) << markdown;
  EXPECT_EQ(comic::test::CountLines(comic::io::ReadFileToString(dir.File("compare.csv"))), 3);
  const nlohmann::json json =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("compare.json")));
  EXPECT_EQ(json["table"].size(), 2u);
  EXPECT_EQ(json["runs"].size(), 2u);
  EXPECT_TRUE(comic::io::IsRegularFile(dir.File("harris/report.json")));
  EXPECT_TRUE(comic::io::IsRegularFile(dir.File("fast/report.json")));
  // Each detector's summary line ends with its page, the last line with the table's.
  EXPECT_NE(result.output.find("; page: " + dir.File("harris") + "/report.html\n"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("; page: " + dir.File("fast") + "/report.html\n"), std::string::npos)
      << result.output;
  EXPECT_EQ(LastLine(result.output),
            "comic_sfm: page: " + dir.File("report.html") + " (each detector's in its folder)");
  EXPECT_TRUE(comic::io::IsRegularFile(dir.File("report.html")));
  EXPECT_TRUE(comic::io::IsRegularFile(dir.File("harris/report.html")));
}

// Issue 16: --matching auto calls the bundled clip a video (sequential, as before) and the same
// frames stored out of order an image set (every pair matched), prints the choice and records it
// in report.json; an explicit tracker flag still wins over the pairing's set-up.
TEST(ComicSfm, MatchingAutoTellsTheClipFromItsFramesOutOfOrder) {
  ScopedTempDir dir;
  // The patch tracker: FAST's descriptors on these 8 frames leave the initial pair 23 points,
  // under 30 (docs/matching.md); the pairing choice is what this test is about.
  const auto video = RunCommand(AppPath("comic_sfm") + " " + Example() +
                                "/image_l --last 7 --detector fast --matcher patches --output " +
                                dir.File("video"));
  ASSERT_EQ(video.exit_code, 0) << video.output;
  EXPECT_NE(video.output.find("matching sequential (auto: "), std::string::npos) << video.output;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("video/report.json")));
  EXPECT_EQ(report["options"]["matching"]["requested"], "auto");
  EXPECT_EQ(report["options"]["matching"]["chosen"], "sequential");
  EXPECT_TRUE(report["options"]["matching"]["looks_like_video"].get<bool>());
  EXPECT_EQ(report["options"]["match_window"], 1);

  // Frames 0..7 stored as 0, 4, 1, 5, 2, 6, 3, 7: consecutive files are 3-4 frames apart.
  const int order[] = {0, 4, 1, 5, 2, 6, 3, 7};
  comic::io::EnsureWritableDirectory(dir.File("shuffled"));
  for (int k = 0; k < 8; ++k) {
    char source[32], target[32];
    std::snprintf(source, sizeof(source), "/image_l/%06d.png", order[k]);
    std::snprintf(target, sizeof(target), "/shuffled/%02d.png", k);
    comic::io::WriteFileAtomically(dir.path() + target,
                                   comic::io::ReadFileToString(Example() + source));
  }
  const auto set = RunCommand(AppPath("comic_sfm") + " " + dir.File("shuffled") +
                              " --detector fast --search-radius 30 --output " + dir.File("set"));
  ASSERT_TRUE(set.exit_code == 0 || set.exit_code == 1) << set.output;
  EXPECT_NE(set.output.find("matching exhaustive (auto: "), std::string::npos) << set.output;
  const nlohmann::json set_report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("set/report.json")));
  EXPECT_EQ(set_report["options"]["matching"]["chosen"], "exhaustive");
  EXPECT_FALSE(set_report["options"]["matching"]["looks_like_video"].get<bool>());
  EXPECT_EQ(set_report["options"]["match_window"], 7);  // every pair of 8 frames
  EXPECT_EQ(set_report["options"]["match_turned"], true);
  EXPECT_EQ(set_report["options"]["search_radius"], 30.0);  // given: kept
}

// The Middlebury temple sparse ring (docs/sfm.md): 16 views 23 degrees apart, ring neighbours up
// to 12 files apart, views 12-16 stored upside down. The image-set options close the ring; without
// the 180-degree matching the two latitude groups never link.
TEST(ComicSfm, TempleSparseRingClosesWithTheImageSetOptions) {
  COMIC_REQUIRE_SHARED_DATA();
  const std::string temple = comic::test::SharedDataDir() + "/middlebury_mview_templeSparseRing";
  const std::string command = AppPath("comic_sfm") + " " + temple + " --gt " + temple +
                              "/templeSR_par.txt --detector hessian --match-window 16 "
                              "--verify-min-gap 1 --prediction coarse-to-fine --coarse-radius 200 "
                              "--search-radius 40 --resize-height 960 --quiet --output ";
  ScopedTempDir dir;
  const auto turned = RunCommand(command + dir.File("turned") + " --match-turned");
  ASSERT_EQ(turned.exit_code, 0) << turned.output;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("turned/report.json")));
  EXPECT_EQ(report["registered_frames"], 16);
  EXPECT_LT(report["ground_truth"]["ate_fraction_of_path"].get<double>(), 0.005);
  EXPECT_LT(report["ground_truth"]["mean_rotation_error_deg"].get<double>(), 1.0);
  EXPECT_LT(report["points3D"]["mean_reprojection_error_px"].get<double>(), 1.0);

  const auto upright = RunCommand(command + dir.File("upright"));
  ASSERT_EQ(upright.exit_code, 0) << upright.output;
  const nlohmann::json upright_report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("upright/report.json")));
  EXPECT_LT(upright_report["registered_frames"].get<int>(), 16);
}

// Issue 17: a progress line per frame during detection and tracking (stdout is not a terminal
// here), with elapsed time and an estimate of what remains; --quiet keeps only the line that
// says where the intrinsics came from.
TEST(ComicSfm, ReportsProgressPerFrameAndQuietKeepsTheIntrinsicsLine) {
  ScopedTempDir dir;
  const std::string command = AppPath("comic_sfm") + " " + Example() + "/image_l --last 5 --gt " +
                              Example() + "/poses.txt --output ";
  const auto result = RunCommand(command + dir.File("a"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (int frame = 1; frame <= 6; ++frame) {
    EXPECT_EQ(CountOccurrences(result.output, "[harris] detection and tracking: frame " +
                                                  std::to_string(frame) + "/6, "),
              1)
        << frame << "\n"
        << result.output;
  }
  EXPECT_EQ(CountOccurrences(result.output, " s elapsed, about "), 5) << result.output;
  EXPECT_EQ(CountOccurrences(result.output, " s left"), 5) << result.output;
  // Progress comes before the mapper's lines.
  EXPECT_LT(result.output.find("frame 6/6"), result.output.find("[harris] registered "));

  const auto quiet = RunCommand(command + dir.File("b") + " --quiet");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find("detection and tracking"), std::string::npos) << quiet.output;
  EXPECT_EQ(quiet.output.find("] registered "), std::string::npos) << quiet.output;
  // The start-up line says where the intrinsics came from (the summary line repeats the camera).
  EXPECT_EQ(CountOccurrences(quiet.output, "6 frames 1226x370, camera PINHOLE fx=707.091"), 1)
      << quiet.output;
  EXPECT_NE(quiet.output.find("(ground truth " + Example() + "/poses.txt)"), std::string::npos)
      << quiet.output;
}

// Issue 16: with no tracker flags, --matching auto calls the temple ring an image set and its
// exhaustive set-up closes the ring at the stored 640x480 (docs/sfm.md: hessian 16/16, ATE
// 0.030 % of the path).
TEST(ComicSfm, TempleSparseRingClosesWithNoTrackerFlags) {
  COMIC_REQUIRE_SHARED_DATA();
  const std::string temple = comic::test::SharedDataDir() + "/middlebury_mview_templeSparseRing";
  ScopedTempDir dir;
  const auto result =
      RunCommand(AppPath("comic_sfm") + " " + temple + " --gt " + temple +
                 "/templeSR_par.txt --detector hessian --quiet --output " + dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("report.json")));
  EXPECT_EQ(report["options"]["matching"]["chosen"], "exhaustive");
  // The patches succeed (and their model passes its self-check): descriptors are not tried.
  EXPECT_EQ(report["status"], "success");
  EXPECT_EQ(report["matcher_attempts"].size(), 1u);
  EXPECT_EQ(report["options"]["matcher"], "patches");
  EXPECT_FALSE(report["self_check"]["suspect"].get<bool>());
  EXPECT_GE(report["self_check"]["pairs_checked"].get<int>(), 10);
  EXPECT_EQ(report["registered_frames"], 16);
  EXPECT_LT(report["ground_truth"]["ate_fraction_of_path"].get<double>(), 0.005);
  EXPECT_LT(report["ground_truth"]["mean_rotation_error_deg"].get<double>(), 1.0);
}

// An image set whose patch matching gives no success is matched by descriptors too (auto): both
// tries are in report.json, in order, and the run says so on stderr.
TEST(ComicSfm, AnImageSetThePatchesFailIsMatchedByDescriptorsToo) {
  COMIC_REQUIRE_SHARED_DATA();
  const std::string lego = comic::test::SharedDataDir() + "/nerf_synthetic_lego";
  ScopedTempDir dir;
  const auto result = RunCommand(AppPath("comic_sfm") + " " + lego + "/train --detector comic " +
                                 "--last 19 --quiet --output " + dir.path());
  EXPECT_EQ(result.exit_code, 1) << result.output;  // neither finds an initial pair in 20 views
  EXPECT_NE(result.output.find("matching by descriptors too"), std::string::npos) << result.output;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("report.json")));
  ASSERT_EQ(report["matcher_attempts"].size(), 2u) << report["matcher_attempts"].dump();
  EXPECT_EQ(report["matcher_attempts"][0]["matcher"], "patches");
  EXPECT_EQ(report["matcher_attempts"][1]["matcher"], "descriptors");
  EXPECT_EQ(report["matcher_attempts"][0]["status"], "no_initial_pair");
}

TEST(ComicSfm, UnreconstructableInputIsReportedNotCrashed) {
  ScopedTempDir dir;
  // One frame: nothing to reconstruct. Exit 1, a clear message, and the report still written.
  const auto result = RunCommand(AppPath("comic_sfm") + " " + Example() +
                                 "/image_l --last 0 --quiet --output " + dir.path());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("too few frames"), std::string::npos) << result.output;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("report.json")));
  EXPECT_EQ(report["status"], "too_few_frames");
  EXPECT_FALSE(comic::io::PathExists(dir.File("points3D.txt")));
}

// Issue 29: names are either refused before any work (whitespace) or work end to end. UTF-8
// frame names reach the model (text and binary) and the database as they are on disk.
TEST(ComicSfm, Utf8FrameNamesWorkEndToEnd) {
  ScopedTempDir dir;
  const std::string frames = dir.File("frames");
  comic::io::EnsureWritableDirectory(frames);
  const std::string prefix =
      "stra\xc3\x9f"
      "e_\xe5\xb8\xa7_";  // straße_帧_
  for (int k = 0; k < 4; ++k) {
    std::filesystem::copy_file(Example() + "/image_l/00000" + std::to_string(k) + ".png",
                               frames + "/" + prefix + std::to_string(k) + ".png");
  }
  const std::string out = dir.File("out");
  const auto result = RunCommand(AppPath("comic_sfm") + " " + frames + " --intrinsics " +
                                 Example() + "/calib.txt --detector fast --threads 1 --quiet " +
                                 "--output " + out + " --colmap-db " + dir.File("t.db"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const comic::io::ColmapTextModel text = comic::io::ReadColmapTextModel(out);
  const comic::io::ColmapTextModel binary = comic::io::ReadColmapBinaryModel(out + "/sparse/0");
  ASSERT_EQ(text.images.size(), 4u);
  ASSERT_EQ(binary.images.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(text.images[k].name, prefix + std::to_string(k) + ".png");
    EXPECT_EQ(binary.images[k].name, text.images[k].name);
  }
  comic::io::ColmapDatabase database = comic::io::ColmapDatabase::Open(dir.File("t.db"));
  EXPECT_EQ(database.ReadAllImages().front().name, prefix + "0.png");
}

// Issue 17: frames without parallax (one frame four times) end in one error line that names the
// failing check of the initial pair and what to try; report.json holds the diagnosis and the
// tracks found are written as a COLMAP database.
TEST(ComicSfm, NoParallaxIsDiagnosedAndTheTracksAreStillWritten) {
  ScopedTempDir dir;
  comic::io::EnsureWritableDirectory(dir.File("still"));
  for (const char* name : {"a.png", "b.png", "c.png", "d.png"}) {
    std::filesystem::copy_file(Example() + "/image_l/000000.png", dir.File("still/") + name);
  }
  const std::string out = dir.File("out");
  const int status = std::system((AppPath("comic_sfm") + " " + dir.File("still") + " --output " +
                                  out + " >" + dir.File("stdout") + " 2>" + dir.File("stderr"))
                                     .c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = comic::io::ReadFileToString(dir.File("stderr"));
  EXPECT_EQ(comic::test::CountLines(err), 1) << err;
  EXPECT_NE(err.find("no initial pair: best pair "), std::string::npos) << err;
  EXPECT_NE(err.find("; try "), std::string::npos) << err;
  const std::string printed = comic::io::ReadFileToString(dir.File("stdout"));
  EXPECT_NE(printed.find("what was found: " + out + "/tracks.db"), std::string::npos) << printed;
  const nlohmann::json report =
      nlohmann::json::parse(comic::io::ReadFileToString(out + "/report.json"));
  EXPECT_EQ(report["status"], "no_initial_pair");
  EXPECT_EQ(report["diagnosis"]["stage"], "initial_pair");
  EXPECT_EQ(err.find(report["diagnosis"]["message"].get<std::string>()), err.find("no initial"));
  EXPECT_EQ(report["outputs"][0], "tracks.db");
  EXPECT_EQ(report["outputs"].back(), "report.html");  // a failed run gets its page too
  EXPECT_TRUE(comic::io::IsRegularFile(out + "/report.html"));
  EXPECT_EQ(comic::io::ColmapDatabase::Open(out + "/tracks.db").ReadAllImages().size(), 4u);
  EXPECT_FALSE(comic::io::PathExists(out + "/points3D.txt"));
}

TEST(ComicSfm, BadInputGivesOneLineErrorAndNonZeroExit) {
  ScopedTempDir dir;
  comic::io::WriteFileAtomically(dir.File("bad_intrinsics.txt"), "700 700 600\n");
  comic::io::WriteFileAtomically(dir.File("a_file"), "x");
  const std::string frames = Example() + "/image_l";
  const std::string out = " --output " + dir.File("out");
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"", 2, "missing argument FRAMES"},
      {"/nonexistent/frames" + out, 1, "no such file or folder"},
      {frames + out + " --detector sift", 2, "unknown detector"},
      {frames + out + " --compare --detector harris", 2, "exclude each other"},
      {frames + out + " --detectors harris", 2, "--detectors needs --compare"},
      {frames + out + " --compare --detectors harris,bogus", 2, "bogus"},
      {frames + out + " --gt /nonexistent/poses.txt", 1, "no such file or folder"},
      {frames + out + " --gt " + Example() + "/poses.txt --gt-format bundler", 2,
       "unknown ground-truth format"},
      // A format that exists but is not the file's: the reader says what it needs.
      {frames + out + " --gt " + Example() + "/poses.txt --gt-format colmap", 1,
       "not a COLMAP model"},
      {frames + out + " --matcher sift", 2, "--matcher: unknown matcher"},
      {frames + out + " --intrinsics " + dir.File("bad_intrinsics.txt"), 1, "expected intrinsics"},
      {frames + " --output " + dir.File("a_file"), 1, "a_file"},
      {frames + out + " --plot-plane up", 2, "--plot-plane"},
      {frames + out + " --model-format json", 2, "--model-format"},
      {frames + out + " --ply-format binary_big_endian", 2, "--ply-format"},
      {frames + out + " --prediction psychic", 2, "psychic"},
      {frames + out + " --local-ba-images 1", 2, "--local-ba-images must be >= 2"},
      {frames + out + " --threads -1", 2, "--threads must be >= 0"},
      {frames + out + " --regions a --masks b", 2, "exclude each other"},
      {frames + out + " --max-features x", 2, "expected an integer"},
  };
  for (const Case& c : cases) {
    const auto result = RunCommand(AppPath("comic_sfm") + " " + c.args + " --quiet");
    EXPECT_EQ(result.exit_code, c.exit_code) << c.args << "\n" << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n" << result.output;
    EXPECT_EQ(comic::test::CountLines(result.output), 1) << c.args << "\n" << result.output;
  }
}

}  // namespace
