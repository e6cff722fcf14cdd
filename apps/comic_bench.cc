// comic_bench: times the CoMIC detector against OpenCV's MSER (delta 5), FAST-9 and GFTT-Harris
// on one real frame, in one run, and reports the median milliseconds per frame and the ratio
// CoMIC / MSER. A plain program rather than a timed test: timings depend on the machine.
#include <algorithm>
#include <chrono>
#include <functional>
#include <iostream>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>

#include "apps/common/arg_parser.h"
#include "frontend/comic_detector.h"
#include "frontend/parallel_for.h"
#include "io/error.h"
#include "io/file_utils.h"
#include "io/image_io.h"
#include "io/report_table.h"

namespace {

struct Timing {
  double median_ms = 0;
  double min_ms = 0;
  size_t features = 0;
};

// Runs `detect` once to warm up, then `runs` times; returns the median and minimum wall time.
Timing Time(int runs, const std::function<size_t()>& detect) {
  Timing timing;
  timing.features = detect();
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    timing.features = detect();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  std::sort(ms.begin(), ms.end());
  timing.median_ms = ms[ms.size() / 2];
  timing.min_ms = ms.front();
  return timing;
}

int Run(int argc, char** argv) {
  std::string input = "../shared/data/middlebury2003_cones/im2.png";
  std::string json_path;
  int resize_height = 700;
  int runs = 9;
  int threads = 0;
  comic::apps::ArgParser parser(
      "comic_bench", "[IMAGE] [options]",
      "Times CoMIC (1 thread and N threads), OpenCV MSER (delta 5), FAST-9 and GFTT-Harris on\n"
      "IMAGE resized to --resize-height, each run --runs times after one warm-up run, and prints\n"
      "the median milliseconds per frame and the ratio CoMIC (1 thread) / MSER. OpenCV's own\n"
      "thread pool is left as configured (cv::getNumThreads() is reported).");
  parser.AddPositional("IMAGE",
                       "a real frame [default: ../shared/data/middlebury2003_cones/im2.png]",
                       &input, /*required=*/false);
  parser.AddOption("resize-height", "H", "resize to height H (0 = original)", &resize_height);
  parser.AddOption("runs", "N", "timed runs per detector (the median is reported)", &runs);
  parser.AddOption("threads", "N", "threads for the multi-threaded CoMIC run (0 = all cores)",
                   &threads);
  parser.AddOption("json", "FILE", "also write the table as JSON", &json_path);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  COMIC_CHECK(resize_height >= 0, kInvalidArgument, "--resize-height must be >= 0");
  COMIC_CHECK(runs >= 1, kInvalidArgument, "--runs must be >= 1");
  COMIC_CHECK(threads >= 0, kInvalidArgument, "--threads must be >= 0");
  COMIC_CHECK(comic::io::PathExists(input), kNotFound,
              input << ": no such file (pass a real frame as IMAGE, e.g. "
                       "../shared/data/middlebury2003_cones/im2.png)");
  if (!json_path.empty()) comic::io::CheckWritableFile(json_path);

  const cv::Mat gray = comic::io::LoadImage(input, resize_height).gray;
  const int many = comic::frontend::ResolveNumThreads(threads, 1 << 20);
  std::cout << "image: " << input << " (" << gray.cols << "x" << gray.rows << "), " << runs
            << " runs per detector, OpenCV threads: " << cv::getNumThreads() << "\n\n";

  comic::frontend::ComicDetectorOptions one_thread;
  one_thread.num_threads = 1;
  comic::frontend::ComicDetectorOptions n_threads;
  n_threads.num_threads = many;
  const comic::frontend::ComicDetector comic_1(one_thread);
  const comic::frontend::ComicDetector comic_n(n_threads);
  const cv::Ptr<cv::MSER> mser = cv::MSER::create(/*delta=*/5);
  const cv::Ptr<cv::FastFeatureDetector> fast =
      cv::FastFeatureDetector::create(20, true, cv::FastFeatureDetector::TYPE_9_16);
  const cv::Ptr<cv::GFTTDetector> harris =
      cv::GFTTDetector::create(/*maxCorners=*/100000, /*qualityLevel=*/0.001,
                               /*minDistance=*/1, /*blockSize=*/3, /*useHarrisDetector=*/true);

  struct Entry {
    std::string name;
    int threads;
    Timing timing;
  };
  std::vector<Entry> entries;
  entries.push_back({"CoMIC", 1, Time(runs, [&] { return comic_1.Detect(gray).size(); })});
  entries.push_back({"CoMIC", many, Time(runs, [&] { return comic_n.Detect(gray).size(); })});
  entries.push_back({"OpenCV MSER (delta 5)", 1, Time(runs, [&] {
                       std::vector<std::vector<cv::Point>> regions;
                       std::vector<cv::Rect> boxes;
                       mser->detectRegions(gray, regions, boxes);
                       return regions.size();
                     })});
  entries.push_back({"FAST-9 (threshold 20)", 1, Time(runs, [&] {
                       std::vector<cv::KeyPoint> keypoints;
                       fast->detect(gray, keypoints);
                       return keypoints.size();
                     })});
  entries.push_back({"GFTT-Harris", 1, Time(runs, [&] {
                       std::vector<cv::KeyPoint> keypoints;
                       harris->detect(gray, keypoints);
                       return keypoints.size();
                     })});

  comic::io::ReportTable table({"detector", "threads", "median ms", "min ms", "features"});
  table.SetPrecision("median ms", 1);
  table.SetPrecision("min ms", 1);
  for (const Entry& e : entries) {
    table.AddRow({e.name, int64_t{e.threads}, e.timing.median_ms, e.timing.min_ms,
                  static_cast<int64_t>(e.timing.features)});
  }
  std::cout << table.ToMarkdown() << "\n";
  const double mser_ms = entries[2].timing.median_ms;
  std::cout << "CoMIC / MSER (median, 1 thread): " << entries[0].timing.median_ms / mser_ms
            << "\nCoMIC / MSER (median, " << many
            << " threads): " << entries[1].timing.median_ms / mser_ms << "\nCoMIC speed-up with "
            << many << " threads: " << entries[0].timing.median_ms / entries[1].timing.median_ms
            << "\n";
  if (!json_path.empty()) {
    comic::io::WriteFileAtomically(json_path, table.ToJson().dump(1) + "\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return comic::apps::RunMain("comic_bench", [&] { return Run(argc, argv); });
}
