// comic_bench: times the CoMIC detector against OpenCV's MSER (delta 5), FAST-9 and GFTT-Harris
// on one real frame, in one run, and reports the median milliseconds per frame and the ratio
// CoMIC / MSER. A plain program rather than a timed test: timings depend on the machine. With
// --perturbations it also measures how many features each detector finds again on the same
// frame after one grey level of noise and after a 0.5 px shift.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "apps/common/arg_parser.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "frontend/comic/comic_detector.h"
#include "frontend/detector_factory.h"
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

// The share of `features` (at least 30 px from the border) with a feature of `other` within 1 px
// of where they should be, `offset` added.
double Repeated(const comic::frontend::FeatureSet& features,
                const comic::frontend::FeatureSet& other, const cv::Point2f& offset,
                const cv::Size& size) {
  int count = 0, repeated = 0;
  for (const comic::frontend::Feature& f : features) {
    if (f.x < 30 || f.y < 30 || f.x > size.width - 31 || f.y > size.height - 31) continue;
    ++count;
    for (const comic::frontend::Feature& g : other) {
      if (std::hypot(g.x - f.x - offset.x, g.y - f.y - offset.y) <= 1.0) {
        ++repeated;
        break;
      }
    }
  }
  return count > 0 ? static_cast<double>(repeated) / count : 0.0;
}

// Repeatability on the same frame under two small changes that leave every corner where it is:
// Gaussian noise of one grey level (seeded) and a shift by 0.5 px (bilinear). Every detector keeps
// as many features as CoMIC finds, by one response cut chosen on the frame and applied unchanged
// to the changed frames.
void PrintPerturbations(const cv::Mat& gray, int threads) {
  cv::Mat noise(gray.size(), CV_32F);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat noisy;
  gray.convertTo(noisy, CV_32F);
  noisy += noise;
  noisy.convertTo(noisy, CV_8U);
  cv::Mat shifted;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 0.5, 0, 1, 0);
  cv::warpAffine(gray, shifted, shift, gray.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  comic::io::ReportTable table({"detector", "features",
                                "noise 1 grey level: repeated within 1 px %",
                                "0.5 px shift: repeated within 1 px %"});
  table.SetPrecision("noise 1 grey level: repeated within 1 px %", 1);
  table.SetPrecision("0.5 px shift: repeated within 1 px %", 1);
  size_t count = 0;
  for (const std::string name : {"comic", "harris", "hessian", "fast"}) {
    comic::frontend::DetectorOptions options;
    options.name = name;
    options.comic.num_threads = threads;
    const auto detector = comic::frontend::MakeDetector(options);
    auto keep = [&](comic::frontend::FeatureSet features, float cut) {
      features.erase(std::remove_if(features.begin(), features.end(),
                                    [&](const auto& f) { return f.response < cut; }),
                     features.end());
      return features;
    };
    comic::frontend::FeatureSet base = detector->Detect(gray);
    if (name == "comic") count = base.size();
    const float cut = base.size() > count && count > 0 ? base[count - 1].response : -1e30f;
    base = keep(std::move(base), cut);
    const auto on_noisy = keep(detector->Detect(noisy), cut);
    const auto on_shifted = keep(detector->Detect(shifted), cut);
    table.AddRow({name, static_cast<int64_t>(base.size()),
                  100.0 * Repeated(base, on_noisy, {0, 0}, gray.size()),
                  100.0 * Repeated(base, on_shifted, {0.5f, 0}, gray.size())});
  }
  std::cout << "\nRepeatability on the same frame (features kept: CoMIC's count):\n\n"
            << table.ToMarkdown();
}

int Run(int argc, char** argv) {
  std::string input = "../shared/data/middlebury2003_cones/im2.png";
  std::string json_path;
  int resize_height = 700;
  int runs = 9;
  int threads = 0;
  bool perturbations = false;
  comic::apps::ArgParser parser(
      "comic_bench", "[IMAGE] [options]",
      "Times CoMIC (1 thread and N threads), OpenCV MSER (delta 5), FAST-9 and GFTT-Harris on\n"
      "IMAGE resized to --resize-height, each run --runs times after one warm-up run, and prints\n"
      "the median milliseconds per frame and the ratio CoMIC (1 thread) / MSER, then CoMIC's\n"
      "one-thread time by stage (initialisation, convergence, output). --threads sets the\n"
      "worker count of the second CoMIC run (and of --perturbations); OpenCV's own thread pool\n"
      "is left as configured (cv::getNumThreads() is reported).");
  parser.AddPositional("IMAGE",
                       "a real frame [default: ../shared/data/middlebury2003_cones/im2.png]",
                       &input, /*required=*/false);
  comic::apps::AddResizeHeightFlag(parser, &resize_height);
  parser.AddOption("runs", "N", "timed runs per detector (the median is reported)", &runs);
  comic::apps::AddThreadsFlag(parser, &threads);
  comic::apps::AddJsonFlag(parser, &json_path);
  parser.AddFlag(
      "perturbations",
      "also report, for CoMIC, Harris, Hessian and FAST at CoMIC's count, the\n"
      "                              share of features found again within 1 px after noise\n"
      "                              of 1 grey level and after a 0.5 px shift",
      &perturbations);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  COMIC_CHECK(resize_height >= 0 && resize_height <= comic::io::kMaxResizeHeight, kInvalidArgument,
              "--resize-height must be >= 0 and <= " << comic::io::kMaxResizeHeight
                                                     << " (0 = original), got " << resize_height);
  COMIC_CHECK(runs >= 1 && runs <= 1000, kInvalidArgument,
              "--runs must be >= 1 and <= 1000, got " << runs);
  comic::apps::CheckThreadCount("--threads", threads);
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
  std::vector<comic::frontend::ComicDetectionStats> stages;  // of the 1-thread runs
  entries.push_back({"CoMIC", 1, Time(runs, [&] {
                       comic::frontend::ComicDetectionStats stats;
                       const size_t count = comic_1.Detect(gray, &stats).size();
                       stages.push_back(stats);
                       return count;
                     })});
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
  // Where CoMIC's one-thread time goes: medians of each stage over the timed runs (the warm-up
  // run, first, left out).
  stages.erase(stages.begin());
  auto median_of = [&](double comic::frontend::ComicDetectionStats::*field) {
    std::vector<double> values;
    for (const auto& stats : stages) values.push_back(stats.*field);
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
  };
  const comic::frontend::ComicDetectionStats& counts = stages.front();
  const double init_ms = median_of(&comic::frontend::ComicDetectionStats::initialisation_ms);
  std::cout << std::fixed << std::setprecision(1)
            << "CoMIC stages, 1 thread (medians): initialisation " << init_ms << " ms ("
            << init_ms / mser_ms << " x MSER), convergence "
            << median_of(&comic::frontend::ComicDetectionStats::convergence_ms) << " ms ("
            << counts.num_seeds << " seeds, " << counts.num_iterations << " iterations, "
            << counts.num_settled << " settled), side masks and output "
            << median_of(&comic::frontend::ComicDetectionStats::output_ms) << " ms\n";
  if (!json_path.empty()) {
    comic::io::WriteFileAtomically(json_path, table.ToJson().dump(1) + "\n");
  }
  if (perturbations) PrintPerturbations(gray, many);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return comic::apps::RunMain("comic_bench", [&] { return Run(argc, argv); });
}
