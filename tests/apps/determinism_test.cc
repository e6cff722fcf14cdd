// Same input and options -> same output, bit for bit, any thread count (issue 19): every app that
// takes --threads runs at 1 and at 2 threads (comic_sfm also twice at 2, where Ceres' threaded
// sums used to differ from run to run), and every output file is compared byte for byte. In JSON
// reports the measured run times and the echoed --threads value are the only keys left out.
// comic_inspect has no --threads: two runs are compared. comic_bench's output is timings.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <set>
#include <string>
#include <thread>

#include "tests/frontend/synthetic_stereo_scene.h"
#include "tests/test_support.h"

namespace {

namespace fs = std::filesystem;
using comic::test::AppPath;
using comic::test::ExampleDir;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Measured times (wall or CPU seconds, e.g. image_set_matching's matching_cpu_s) and the thread
// count itself are the only things allowed to differ.
void DropVolatileKeys(nlohmann::json* json) {
  static const std::set<std::string> kVolatile = {"time_s", "wall_time_s", "export_time_s",
                                                  "threads", "num_threads"};
  if (json->is_object()) {
    for (auto it = json->begin(); it != json->end();) {
      if (kVolatile.count(it.key()) > 0 || EndsWith(it.key(), "_cpu_s")) {
        it = json->erase(it);
      } else {
        DropVolatileKeys(&it.value());
        ++it;
      }
    }
  } else if (json->is_array()) {
    for (auto& item : *json) DropVolatileKeys(&item);
  }
}

// The echoed command line (report.md, evaluation.json of comic_track_eval) names the thread count.
std::string WithoutThreadCount(std::string text) {
  for (size_t at = text.find("--threads "); at != std::string::npos;
       at = text.find("--threads ", at + 1)) {
    size_t end = at + 10;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    text.replace(at + 10, end - at - 10, "N");
  }
  return text;
}

// report.html: the page around its data, and the data (a JSON script) without the sections that
// hold measured durations and without the volatile keys of the report.json it embeds.
std::string PageWithoutDurations(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"comic-page-data\">";
  const size_t begin = html.find(open);
  if (begin == std::string::npos) return html;
  const size_t data_begin = begin + open.size();
  const size_t data_end = html.find("</script>", data_begin);
  if (data_end == std::string::npos) return html;
  nlohmann::json data = nlohmann::json::parse(html.substr(data_begin, data_end - data_begin));
  if (data.contains("sections") && data["sections"].is_array()) {
    nlohmann::json kept = nlohmann::json::array();
    for (const auto& section : data["sections"]) {
      if (!section.contains("durations")) kept.push_back(section);
    }
    data["sections"] = kept;
  }
  DropVolatileKeys(&data);
  // The options table's ["threads", N] row.
  for (auto& section : data["sections"]) {
    if (!section.contains("rows") || !section["rows"].is_array()) continue;
    for (auto& row : section["rows"]) {
      if (row.is_array() && row.size() == 2 && row[0] == "threads") row[1] = "N";
    }
  }
  return html.substr(0, data_begin) + data.dump() + html.substr(data_end);
}

// Every file below `folder` by relative path: its bytes, or for JSON its content without the
// volatile keys; in text files the echoed --threads value is masked.
std::map<std::string, std::string> OutputFiles(const std::string& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = fs::relative(entry.path(), folder).string();
    std::string bytes = ReadBytes(entry.path().string());
    const std::string extension = entry.path().extension().string();
    if (extension == ".json") {
      nlohmann::json json = nlohmann::json::parse(bytes);
      DropVolatileKeys(&json);
      bytes = json.dump();
    }
    if (extension == ".html") bytes = PageWithoutDurations(bytes);
    if (extension == ".json" || extension == ".md" || extension == ".csv" || extension == ".html") {
      bytes = WithoutThreadCount(bytes);
    }
    files[name] = bytes;
  }
  return files;
}

void ExpectSameOutputs(const std::string& a, const std::string& b, size_t min_files) {
  const auto first = OutputFiles(a);
  const auto second = OutputFiles(b);
  EXPECT_GE(first.size(), min_files);
  ASSERT_EQ(first.size(), second.size());
  for (const auto& [name, bytes] : first) {
    const auto it = second.find(name);
    ASSERT_NE(it, second.end()) << name << " missing in " << b;
    EXPECT_FALSE(bytes.empty()) << name;
    EXPECT_TRUE(bytes == it->second) << name << " differs between " << a << " and " << b;
  }
}

bool HasTwoThreads() { return std::thread::hardware_concurrency() >= 2; }

// Runs `command` with {out} replaced by one fixed path in `dir`, then moves that folder to
// `folder`: every run writes to the same path, so outputs that name their folder still compare.
void RunInto(const ScopedTempDir& dir, std::string command, const std::string& folder) {
  const std::string out = dir.File("run");
  fs::create_directories(out);
  for (size_t at = command.find("{out}"); at != std::string::npos; at = command.find("{out}")) {
    command.replace(at, 5, out);
  }
  const auto result = RunCommand(command);
  ASSERT_EQ(result.exit_code, 0) << command << "\n" << result.output;
  fs::rename(out, dir.File(folder));
}

TEST(Determinism, ComicDetectAtOneAndTwoThreads) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  for (const char* threads : {"1", "2"}) {
    RunInto(dir,
            AppPath("comic_detect") + " " + ExampleDir() + "/image_l/000003.png --threads " +
                threads + " --overlay {out}/overlay.png --json {out}/features.json",
            std::string("t") + threads);
  }
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 2);
}

TEST(Determinism, ComicSfmAtOneAndTwoThreadsAndTwiceAtTwo) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  for (const char* run : {"1", "2", "2b"}) {
    const std::string threads = std::string(run).substr(0, 1);
    RunInto(dir,
            AppPath("comic_sfm") + " " + ExampleDir() + "/image_l --gt " + ExampleDir() +
                "/poses.txt --quiet --threads " + threads + " --output {out}",
            std::string("t") + run);
  }
  // cameras.txt, images.txt, points3D.txt, points.ply, trajectory.png, report.json.
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 6);
  ExpectSameOutputs(dir.File("t2"), dir.File("t2b"), 6);
}

// CoMIC's detection runs on --threads in comic_sfm (issue 17); the model must not change.
TEST(Determinism, ComicSfmWithCoMICAtOneAndTwoThreads) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  for (const char* threads : {"1", "2"}) {
    RunInto(dir,
            AppPath("comic_sfm") + " " + ExampleDir() + "/image_l --last 5 --detector comic --gt " +
                ExampleDir() + "/poses.txt --quiet --threads " + threads + " --output {out}",
            std::string("t") + threads);
  }
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 6);
}

// Refined distortion and principal point (the automatically differentiated costs of an OPENCV
// camera): the same outputs at 1 and 2 threads.
TEST(Determinism, ComicSfmRefiningAnOpenCvCameraAtOneAndTwoThreads) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  for (const char* threads : {"1", "2"}) {
    RunInto(dir,
            AppPath("comic_sfm") + " " + ExampleDir() + "/image_l --intrinsics " + ExampleDir() +
                "/calib.txt --camera-model OPENCV --refine-distortion --refine-principal-point "
                "--quiet --threads " +
                threads + " --output {out}",
            std::string("t") + threads);
  }
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 6);
}

// A video with --write-frames: the model and the frames written (issue 17).
TEST(Determinism, ComicSfmOnAVideoWithWriteFramesAtOneAndTwoThreads) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  const std::string video = dir.File("clip.avi");
  {
    cv::VideoWriter writer;
    for (int i = 0; i < 6; ++i) {
      char name[32];
      std::snprintf(name, sizeof(name), "/image_l/%06d.png", i);
      const cv::Mat frame = cv::imread(ExampleDir() + name, cv::IMREAD_COLOR);
      if (!writer.isOpened()) {
        writer.open(video, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, frame.size(), true);
      }
      writer.write(frame);
    }
  }
  for (const char* threads : {"1", "2"}) {
    RunInto(dir,
            AppPath("comic_sfm") + " " + video + " --intrinsics " + ExampleDir() +
                "/calib.txt --write-frames --quiet --threads " + threads + " --output {out}",
            std::string("t") + threads);
  }
  // The six of the model and six frames.
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 12);
}

// Issue 16: a combined detector with a window pairing (each component tracked on its own, the
// pairs beyond the next frame verified) is as repeatable as one detector.
TEST(Determinism, ComicSfmCombinedDetectorWithWindowAtOneAndTwoThreads) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  for (const char* threads : {"1", "2"}) {
    RunInto(dir,
            AppPath("comic_sfm") + " " + ExampleDir() + "/image_l --gt " + ExampleDir() +
                "/poses.txt --last 7 --detector harris+hessian --matching window:3 --quiet "
                "--threads " +
                threads + " --output {out}",
            std::string("t") + threads);
  }
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 6);
}

TEST(Determinism, ComicTrackEvalAtOneAndTwoThreads) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  for (const char* threads : {"1", "2"}) {
    RunInto(dir,
            AppPath("comic_track_eval") + " " + ExampleDir() +
                "/image_l --last 6 --resize-height 0 --detectors comic,harris --comic-matchers "
                "split --n 2 --frame-step 2 --overlay-frames 1 --threads " +
                threads + " --output {out}",
            std::string("t") + threads);
  }
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 8);
}

TEST(Determinism, ComicExportColmapAtOneAndTwoThreads) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  for (const char* threads : {"1", "2"}) {
    RunInto(dir,
            AppPath("comic_export_colmap") + " " + ExampleDir() + "/image_l --last 5 --threads " +
                threads + " --colmap-db {out}/tracks.db",
            std::string("t") + threads);
  }
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 1);
}

TEST(Determinism, ComicStereoEvalAtOneAndTwoThreads) {
  if (!HasTwoThreads()) GTEST_SKIP() << "one hardware thread";
  ScopedTempDir dir;
  const comic::io::MiddleburyPair scene = comic::test::SyntheticStereoScene::Make();
  cv::Mat stored;
  scene.disparity.convertTo(stored, CV_8U, 4.0);
  cv::imwrite(dir.File("left.png"), scene.left_gray);
  cv::imwrite(dir.File("right.png"), scene.right_gray);
  cv::imwrite(dir.File("disp.png"), stored);
  for (const char* threads : {"1", "2"}) {
    RunInto(dir,
            AppPath("comic_stereo_eval") + " " + dir.File("left.png") + " " +
                dir.File("right.png") + " --disparity " + dir.File("disp.png") +
                " --disparity-scale 4 --quiet --threads " + threads + " --output {out}",
            std::string("t") + threads);
  }
  ExpectSameOutputs(dir.File("t1"), dir.File("t2"), 9);
}

TEST(Determinism, ComicInspectTwice) {
  ScopedTempDir dir;
  for (const char* run : {"a", "b"}) {
    RunInto(
        dir,
        AppPath("comic_inspect") + " " + ExampleDir() + "/image_l --contact-sheet {out}/sheet.png",
        run);
  }
  ExpectSameOutputs(dir.File("a"), dir.File("b"), 1);
}

TEST(Determinism, ComicRenderTwiceWithEveryEffect) {
  ScopedTempDir dir;
  for (const char* run : {"a", "b"}) {
    RunInto(dir,
            AppPath("comic_render") + " " + comic::test::SourceDir() +
                "/scenes/test_street.json --photos " + ExampleDir() +
                "/image_l --frames 3 --noise 2 --shot-noise 0.5 --exposure-drift 0.2 "
                "--shutter 0.5 --blur-samples 3 --stereo-pairs 1 -q --output {out}",
            run);
  }
  ExpectSameOutputs(dir.File("a"), dir.File("b"), 20);
}

}  // namespace
