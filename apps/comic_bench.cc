// comic_bench: times the CoMIC detectors (the default direct search "comic", and Algorithm 1,
// "comic-paper") against OpenCV's MSER (delta 5), FAST-9 and GFTT-Harris on one real frame, in
// one run, and reports the median milliseconds per frame and the ratios CoMIC / MSER. A plain
// program rather than a timed test: timings depend on the machine. With
// --perturbations it also measures how many features each detector finds again on the same
// frame after one grey level of noise and after a 0.5 px shift. With --match-pair it also times
// the patch matcher (one frame pair, 2000 features per frame, every cost in the same run).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <iomanip>
#include <iostream>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/common/arg_parser.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "frontend/comic/comic_detector.h"
#include "frontend/comic/comic_direct_detector.h"
#include "frontend/detector_factory.h"
#include "frontend/matching/patch_matcher.h"
#include "frontend/parallel_for.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/protected_inputs.h"
#include "io/image/image_io.h"
#include "io/report/json_text.h"
#include "io/report/report_table.h"

namespace {

struct Timing {
  double median_ms = 0;
  double min_ms = 0;
  // Process CPU time (every thread's, std::clock): on a loaded machine it moves less than the
  // wall time, which counts the time other processes hold the cores.
  double median_cpu_ms = 0;
  size_t features = 0;
};

// Runs `detect` once to warm up, then `runs` times; returns the median and minimum wall time and
// the median process CPU time.
Timing Time(int runs, const std::function<size_t()>& detect) {
  Timing timing;
  timing.features = detect();
  std::vector<double> ms;
  std::vector<double> cpu_ms;
  for (int i = 0; i < runs; ++i) {
    const std::clock_t cpu_start = std::clock();
    const auto start = std::chrono::steady_clock::now();
    timing.features = detect();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
    cpu_ms.push_back(1000.0 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
  }
  std::sort(ms.begin(), ms.end());
  std::sort(cpu_ms.begin(), cpu_ms.end());
  timing.median_ms = ms[ms.size() / 2];
  timing.min_ms = ms.front();
  timing.median_cpu_ms = cpu_ms[cpu_ms.size() / 2];
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

// Where comic's repeatability is lost (docs/comic_detector.md): every feature of `base` (its
// strongest features, response >= cut, away from the border) not found again within 1 px in
// `changed` (>= cut) is put in the first class that explains it, using both detections' run
// records: its place in `changed` holds a feature below the cut (the response cut); a run there
// was merged into a stronger neighbour or dropped for a thin side; a run of the same polarity
// and overlapping levels lies within 3 px but its span changed (a run break or extension) or,
// with the same span, its position moved; no run within 3 px (vanished). Values in points of
// repeatability (% of the base features).
struct LossSplit {
  double cut = 0, merged = 0, thin_side = 0, run_changed = 0, moved = 0, vanished = 0;
};

LossSplit SplitLosses(const comic::frontend::FeatureSet& base,
                      const comic::frontend::ComicDirectDetectionStats& base_stats,
                      const comic::frontend::FeatureSet& changed,
                      const comic::frontend::ComicDirectDetectionStats& changed_stats,
                      const cv::Point2f& offset, float cut, const cv::Size& size) {
  using Fate = comic::frontend::ComicDirectRunRecord::Fate;
  auto distance = [](const cv::Point2f& a, const cv::Point2f& b) {
    return std::hypot(a.x - b.x, a.y - b.y);
  };
  LossSplit split;
  int count = 0;
  for (const comic::frontend::Feature& f : base) {
    if (f.response < cut) continue;
    if (f.x < 30 || f.y < 30 || f.x > size.width - 31 || f.y > size.height - 31) continue;
    ++count;
    const cv::Point2f want(f.x + offset.x, f.y + offset.y);
    bool found = false, below = false;
    for (const comic::frontend::Feature& g : changed) {
      if (distance({g.x, g.y}, want) <= 1.0) (g.response >= cut ? found : below) = true;
    }
    if (found) continue;
    if (below) {
      ++split.cut;
      continue;
    }
    const comic::frontend::ComicDirectRunRecord* own = nullptr;
    for (const auto& r : base_stats.runs) {
      if (r.fate == Fate::kOutput && r.position.x == f.x && r.position.y == f.y) own = &r;
    }
    bool explained = false;
    for (const auto& r : changed_stats.runs) {
      if ((r.fate == Fate::kMerged || r.fate == Fate::kThinSide) &&
          distance(r.position, want) <= 1.0) {
        ++(r.fate == Fate::kMerged ? split.merged : split.thin_side);
        explained = true;
        break;
      }
    }
    if (explained) continue;
    const comic::frontend::ComicDirectRunRecord* nearest = nullptr;
    double nearest_distance = 3.0;
    for (const auto& r : changed_stats.runs) {
      if (own == nullptr || r.polarity != own->polarity || r.fate == Fate::kNoStability) continue;
      const int lo = std::min(own->first_level, own->last_level);
      const int hi = std::max(own->first_level, own->last_level);
      if (std::max(r.first_level, r.last_level) < lo ||
          std::min(r.first_level, r.last_level) > hi) {
        continue;
      }
      const double d = distance(r.position, want);
      if (d <= nearest_distance) {
        nearest_distance = d;
        nearest = &r;
      }
    }
    if (nearest == nullptr) {
      ++split.vanished;
    } else if (nearest->first_level == own->first_level && nearest->last_level == own->last_level) {
      ++split.moved;
    } else {
      ++split.run_changed;
    }
  }
  const double scale = count > 0 ? 100.0 / count : 0.0;
  for (double* v : {&split.cut, &split.merged, &split.thin_side, &split.run_changed, &split.moved,
                    &split.vanished}) {
    *v *= scale;
  }
  return split;
}

// Repeatability on the same frame under two small changes that leave every corner where it is:
// Gaussian noise of one grey level (seeded) and a shift by 0.5 px (bilinear). Every detector keeps
// the same number of features, by one response cut chosen on the frame and applied unchanged to
// the changed frames: its `count` strongest (0: as many as CoMIC finds). Repeatability falls with
// the count for every detector, so it is comparable only at equal counts.
void PrintPerturbations(const cv::Mat& gray, int threads, int count,
                        const std::vector<std::string>& detectors) {
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
  size_t kept = count > 0 ? static_cast<size_t>(count) : 0;
  comic::io::ReportTable losses(
      {"comic: lost to", "noise 1 grey level, points", "0.5 px shift, points"});
  losses.SetPrecision("noise 1 grey level, points", 1);
  losses.SetPrecision("0.5 px shift, points", 1);
  for (const std::string& name : detectors) {
    comic::frontend::DetectorOptions options;
    options.name = name;
    options.comic.num_threads = threads;
    options.comic_paper.num_threads = threads;
    const auto detector = comic::frontend::MakeDetector(options);
    auto keep = [&](comic::frontend::FeatureSet features, float cut) {
      features.erase(std::remove_if(features.begin(), features.end(),
                                    [&](const auto& f) { return f.response < cut; }),
                     features.end());
      return features;
    };
    if (name == "comic") {
      // The same detector with its runs recorded (the features do not change).
      const comic::frontend::ComicDirectDetector comic(options.comic);
      comic::frontend::ComicDirectDetectionStats stats[3];
      const cv::Mat* images[3] = {&gray, &noisy, &shifted};
      comic::frontend::FeatureSet found[3];
      for (int i = 0; i < 3; ++i) {
        stats[i].record_runs = true;
        found[i] = comic.Detect(*images[i], &stats[i]);
      }
      if (kept == 0) kept = found[0].size();
      const float cut = found[0].size() > kept && kept > 0 ? found[0][kept - 1].response : -1e30f;
      const LossSplit on_noisy =
          SplitLosses(found[0], stats[0], found[1], stats[1], {0, 0}, cut, gray.size());
      const LossSplit on_shifted =
          SplitLosses(found[0], stats[0], found[2], stats[2], {0.5f, 0}, cut, gray.size());
      for (const auto& [what, field] : std::vector<std::pair<std::string, double LossSplit::*>>{
               {"a feature there, below the response cut", &LossSplit::cut},
               {"a run there, merged into a stronger feature (2 px)", &LossSplit::merged},
               {"a run there, < 40 px on a side of its curve", &LossSplit::thin_side},
               {"its run broken or extended (other levels)", &LossSplit::run_changed},
               {"its run, same levels, position moved > 1 px", &LossSplit::moved},
               {"no run within 3 px (vanished)", &LossSplit::vanished}}) {
        losses.AddRow({what, on_noisy.*field, on_shifted.*field});
      }
    }
    comic::frontend::FeatureSet base = detector->Detect(gray);
    if (kept == 0) kept = base.size();
    const float cut = base.size() > kept && kept > 0 ? base[kept - 1].response : -1e30f;
    base = keep(std::move(base), cut);
    const auto on_noisy = keep(detector->Detect(noisy), cut);
    const auto on_shifted = keep(detector->Detect(shifted), cut);
    table.AddRow({name, static_cast<int64_t>(base.size()),
                  100.0 * Repeated(base, on_noisy, {0, 0}, gray.size()),
                  100.0 * Repeated(base, on_shifted, {0.5f, 0}, gray.size())});
  }
  std::cout << "\nRepeatability on the same frame (features kept: "
            << (count > 0 ? "the " + std::to_string(count) + " strongest" : "CoMIC's count")
            << "):\n\n"
            << table.ToMarkdown();
  if (std::find(detectors.begin(), detectors.end(), "comic") != detectors.end()) {
    std::cout << "\nWhere comic's losses go (points of repeatability):\n\n" << losses.ToMarkdown();
  }
}

// Matcher speed (issue 15): ms per frame pair for the patch matcher with the radius gate
// (r = 20 px, T = 400) between `gray` and `gray2`, on each detector's `count` strongest features
// per frame, for every cost. Per cost: preparing one frame's patches (PreparePatches: grey values
// and, for the calibrated cost, every feature's level-line sides), matching two prepared frames,
// their sum "per pair in a sequence" (the tracker prepares each frame once and matches it to the
// frame before and after it) and a "cold pair" (MatchFeatures from the two images, both frames
// prepared inside the call). The costs are timed round-robin, run by run, so that a change of load
// on a shared machine hits every cost alike; the ratios compare the costs of one run.
void PrintMatcherTimes(const cv::Mat& gray, const cv::Mat& gray2, int count, int runs) {
  namespace fe = comic::frontend;
  comic::io::ReportTable table({"detector", "features (1 / 2)", "cost", "prepare ms / frame",
                                "match ms / pair", "per pair in a sequence ms", "sequence / full",
                                "cold pair ms", "cold / full", "matches"});
  for (const char* column :
       {"prepare ms / frame", "match ms / pair", "per pair in a sequence ms", "cold pair ms"}) {
    table.SetPrecision(column, 1);
  }
  table.SetPrecision("sequence / full", 2);
  table.SetPrecision("cold / full", 2);
  const std::vector<fe::MatchCost> costs = {fe::MatchCost::kFullPatch,
                                            fe::MatchCost::kSplitMinOfFourPairings,
                                            fe::MatchCost::kCalibratedSides};
  auto ms_since = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  for (const std::string name : {"comic", "harris", "hessian"}) {
    fe::DetectorOptions options;
    options.name = name;
    const auto detector = fe::MakeDetector(options);
    auto strongest = [&](const cv::Mat& image) {
      fe::FeatureSet features = detector->Detect(image);
      fe::SortByResponse(&features);
      if (static_cast<int>(features.size()) > count) features.resize(count);
      return features;
    };
    const fe::FeatureSet f1 = strongest(gray), f2 = strongest(gray2);
    std::vector<std::vector<double>> prepare_ms(costs.size()), match_ms(costs.size()),
        cold_ms(costs.size());
    std::vector<size_t> matches(costs.size(), 0);
    for (int run = -1; run < runs; ++run) {  // run -1 warms up
      for (size_t c = 0; c < costs.size(); ++c) {
        fe::PatchMatcherOptions matcher;
        matcher.cost = costs[c];
        auto start = std::chrono::steady_clock::now();
        const fe::PatchSet p1 = fe::PreparePatches(gray, f1, matcher);
        const double prepare = ms_since(start);
        const fe::PatchSet p2 = fe::PreparePatches(gray2, f2, matcher);
        start = std::chrono::steady_clock::now();
        const size_t prepared = fe::MatchFeatures(f1, p1, f2, p2, matcher).size();
        const double match = ms_since(start);
        start = std::chrono::steady_clock::now();
        matches[c] = fe::MatchFeatures(gray, f1, gray2, f2, matcher).size();
        const double cold = ms_since(start);
        COMIC_CHECK(prepared == matches[c], kInvalidData,
                    "prepared and cold matching disagree (" << prepared << " against " << matches[c]
                                                            << " matches)");
        if (run < 0) continue;
        prepare_ms[c].push_back(prepare);
        match_ms[c].push_back(match);
        cold_ms[c].push_back(cold);
      }
    }
    const double full_sequence = median(prepare_ms[0]) + median(match_ms[0]);
    const double full_cold = median(cold_ms[0]);
    for (size_t c = 0; c < costs.size(); ++c) {
      const double sequence = median(prepare_ms[c]) + median(match_ms[c]);
      table.AddRow({name, std::to_string(f1.size()) + " / " + std::to_string(f2.size()),
                    fe::MatchCostName(costs[c]), median(prepare_ms[c]), median(match_ms[c]),
                    sequence, sequence / full_sequence, median(cold_ms[c]),
                    median(cold_ms[c]) / full_cold, static_cast<int64_t>(matches[c])});
    }
  }
  std::cout << "\nPatch matcher, one frame pair, radius gate r = 20 px, T = 400, up to " << count
            << " features per frame (medians of " << runs << " round-robin runs):\n\n"
            << table.ToMarkdown();
}

// The command line, bound to the parser by AddFlags; Check() validates it and fills the lists.
struct Flags {
  void Check();

  std::string input = "../shared/data/middlebury2003_cones/im2.png";
  std::string json_path;
  int resize_height = 700;
  int runs = 9;
  int threads = 0;
  bool perturbations = false;
  std::string counts_list;
  std::string detector_list;
  std::string match_pair;
  int match_features = 2000;
  bool match_only = false;
  std::vector<int> counts;                          // parsed from counts_list
  std::vector<std::string> perturbation_detectors;  // parsed from detector_list
};

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("IMAGE",
                       "a real frame [default: ../shared/data/middlebury2003_cones/im2.png]",
                       &flags.input, /*required=*/false);
  comic::apps::AddResizeHeightFlag(parser, &flags.resize_height);
  parser.AddOption("runs", "N", "timed runs per detector (the median is reported)", &flags.runs);
  comic::apps::AddThreadsFlag(parser, &flags.threads);
  comic::apps::AddJsonFlag(parser, &flags.json_path);
  parser.AddFlag(
      "perturbations",
      "also report, for comic, comic-paper, Harris, Hessian and FAST (or --detectors)\n"
      "                              at CoMIC's count (or --keep), the\n"
      "                              share of features found again within 1 px after noise\n"
      "                              of 1 grey level and after a 0.5 px shift",
      &flags.perturbations);
  // Not --count: comic_track_eval's --count is a target count on the object in frame 0, and one
  // option name has one meaning across the apps (tests/apps/option_vocabulary_test.cc).
  parser.AddOption(
      "keep", "LIST",
      "with --perturbations: cut every detector to its N strongest features, one\n"
      "                              table per N of the comma-separated LIST (default: "
      "CoMIC's count)",
      &flags.counts_list);
  comic::apps::AddDetectorListFlag(parser, &flags.detector_list);
  parser.AddOption("match-pair", "IMAGE2",
                   "also time the patch matcher between IMAGE and IMAGE2 (same size) for every "
                   "cost",
                   &flags.match_pair);
  parser.AddOption("match-features", "N", "features per frame for --match-pair (strongest N)",
                   &flags.match_features);
  parser.AddFlag("match-only", "with --match-pair: time only the patch matcher, not the detectors",
                 &flags.match_only);
}

void Flags::Check() {
  COMIC_CHECK(match_features >= 1, kInvalidArgument, "--match-features must be >= 1");
  COMIC_CHECK(match_pair.empty() || comic::io::PathExists(match_pair), kNotFound,
              match_pair << ": no such file (--match-pair)");
  comic::io::CheckResizeHeight(resize_height);
  COMIC_CHECK(runs >= 1 && runs <= 1000, kInvalidArgument,
              "--runs must be >= 1 and <= 1000, got " << runs);
  comic::apps::CheckThreadCount("--threads", threads);
  COMIC_CHECK(comic::io::PathExists(input), kNotFound,
              input << ": no such file (pass a real frame as IMAGE, e.g. "
                       "../shared/data/middlebury2003_cones/im2.png)");
  {
    std::stringstream stream(counts_list);
    std::string item;
    while (std::getline(stream, item, ',')) {
      char* end = nullptr;
      const long value = std::strtol(item.c_str(), &end, 10);
      COMIC_CHECK(!item.empty() && *end == '\0' && value >= 1 && value <= 1000000, kInvalidArgument,
                  "--keep: expected positive integers, got '" << item << "'");
      counts.push_back(static_cast<int>(value));
    }
    COMIC_CHECK(counts.empty() || perturbations, kInvalidArgument, "--keep needs --perturbations");
  }
  COMIC_CHECK(!match_only || !match_pair.empty(), kInvalidArgument,
              "--match-only needs --match-pair");
  comic::io::CheckOutputsAvoidInputs({{"--json", json_path}},
                                     {{"IMAGE", input}, {"--match-pair", match_pair}});
  // --detectors: the detectors of the --perturbations tables (comic's losses need comic).
  perturbation_detectors =
      detector_list.empty()
          ? std::vector<std::string>{"comic", "comic-paper", "harris", "hessian", "fast"}
          : comic::frontend::ParseDetectorList(detector_list);
  COMIC_CHECK(detector_list.empty() || perturbations, kInvalidArgument,
              "--detectors needs --perturbations");
  if (!json_path.empty()) comic::io::CheckWritableFile(json_path);
}

// One detector's timing, as a row of the table.
struct Entry {
  std::string name;
  int threads;
  Timing timing;
};

// The one-thread CoMIC runs' stage times, kept apart for the per-stage medians.
struct StageTimes {
  std::vector<comic::frontend::ComicDirectDetectionStats> direct;
  std::vector<comic::frontend::ComicDetectionStats> paper;
};

// Times every detector on the image; the rows are in the order the ratios below index them.
std::vector<Entry> TimeDetectors(const cv::Mat& gray, int runs, int many, StageTimes& times) {
  std::vector<comic::frontend::ComicDirectDetectionStats>& stages = times.direct;
  std::vector<comic::frontend::ComicDetectionStats>& paper_stages = times.paper;
  // "comic": the direct search (the default detector); "comic-paper": Algorithm 1.
  comic::frontend::ComicDirectDetectorOptions one_thread;
  one_thread.num_threads = 1;
  comic::frontend::ComicDirectDetectorOptions n_threads;
  n_threads.num_threads = many;
  const comic::frontend::ComicDirectDetector comic_1(one_thread);
  const comic::frontend::ComicDirectDetector comic_n(n_threads);
  comic::frontend::ComicDetectorOptions paper_one_thread;
  paper_one_thread.num_threads = 1;
  const comic::frontend::ComicDetector paper_1(paper_one_thread);
  const cv::Ptr<cv::MSER> mser = cv::MSER::create(/*delta=*/5);
  const cv::Ptr<cv::FastFeatureDetector> fast =
      cv::FastFeatureDetector::create(20, true, cv::FastFeatureDetector::TYPE_9_16);
  const cv::Ptr<cv::GFTTDetector> harris =
      cv::GFTTDetector::create(/*maxCorners=*/100000, /*qualityLevel=*/0.001,
                               /*minDistance=*/1, /*blockSize=*/3, /*useHarrisDetector=*/true);

  std::vector<Entry> entries;
  entries.push_back({"CoMIC", 1, Time(runs, [&] {
                       comic::frontend::ComicDirectDetectionStats stats;
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
  entries.push_back({"CoMIC-paper (Algorithm 1)", 1, Time(runs, [&] {
                       comic::frontend::ComicDetectionStats stats;
                       const size_t count = paper_1.Detect(gray, &stats).size();
                       paper_stages.push_back(stats);
                       return count;
                     })});
  return entries;
}

// Prints the timing table and the CoMIC / MSER ratios; returns the table for --json.
comic::io::ReportTable PrintTimes(const std::vector<Entry>& entries, int many) {
  comic::io::ReportTable table(
      {"detector", "threads", "median ms", "min ms", "median CPU ms", "features"});
  table.SetPrecision("median ms", 1);
  table.SetPrecision("min ms", 1);
  table.SetPrecision("median CPU ms", 1);
  for (const Entry& e : entries) {
    table.AddRow({e.name, int64_t{e.threads}, e.timing.median_ms, e.timing.min_ms,
                  e.timing.median_cpu_ms, static_cast<int64_t>(e.timing.features)});
  }
  std::cout << table.ToMarkdown() << "\n";
  const double mser_ms = entries[2].timing.median_ms;
  std::cout << "CoMIC / MSER (median, 1 thread): " << entries[0].timing.median_ms / mser_ms
            << "\nCoMIC / MSER (median, " << many
            << " threads): " << entries[1].timing.median_ms / mser_ms << "\nCoMIC speed-up with "
            << many << " threads: " << entries[0].timing.median_ms / entries[1].timing.median_ms
            << "\n";
  std::cout << "CoMIC / MSER (median CPU time, 1 thread): "
            << entries[0].timing.median_cpu_ms / entries[2].timing.median_cpu_ms << "\n";
  std::cout << "CoMIC-paper / MSER (median, 1 thread): " << entries[5].timing.median_ms / mser_ms
            << "\n";
  return table;
}

// Prints each CoMIC's one-thread time by stage, against MSER's median.
void PrintStageTimes(StageTimes& times, double mser_ms) {
  std::vector<comic::frontend::ComicDirectDetectionStats>& stages = times.direct;
  std::vector<comic::frontend::ComicDetectionStats>& paper_stages = times.paper;
  // Where each one-thread time goes: medians of each stage over the timed runs (the warm-up
  // run, first, left out).
  stages.erase(stages.begin());
  paper_stages.erase(paper_stages.begin());
  auto median_of = [](const auto& all, auto field) {
    std::vector<double> values;
    for (const auto& stats : all) values.push_back(stats.*field);
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
  };
  using DirectStats = comic::frontend::ComicDirectDetectionStats;
  const DirectStats& direct_counts = stages.front();
  std::cout << std::fixed << std::setprecision(1) << "CoMIC stages, 1 thread (medians): trees "
            << median_of(stages, &DirectStats::trees_ms) << " ms ("
            << median_of(stages, &DirectStats::trees_ms) / mser_ms << " x MSER), curves "
            << median_of(stages, &DirectStats::curves_ms) << " ms (" << direct_counts.num_curves
            << " curves, " << direct_counts.num_maxima << " kappa maxima), stability "
            << median_of(stages, &DirectStats::stability_ms) << " ms (" << direct_counts.num_runs
            << " runs), side masks and output " << median_of(stages, &DirectStats::output_ms)
            << " ms\n";
  using PaperStats = comic::frontend::ComicDetectionStats;
  const PaperStats& paper_counts = paper_stages.front();
  const double init_ms = median_of(paper_stages, &PaperStats::initialisation_ms);
  std::cout << "CoMIC-paper stages, 1 thread (medians): initialisation " << init_ms << " ms ("
            << init_ms / mser_ms << " x MSER), convergence "
            << median_of(paper_stages, &PaperStats::convergence_ms) << " ms ("
            << paper_counts.num_seeds << " seeds, " << paper_counts.num_iterations
            << " iterations, " << paper_counts.num_settled << " settled), side masks and output "
            << median_of(paper_stages, &PaperStats::output_ms) << " ms\n";
}

int Run(int argc, char** argv) {
  Flags flags;
  comic::apps::ArgParser parser(
      "comic_bench", "[IMAGE] [options]",
      "Times CoMIC (the default direct search, 1 thread and N threads), OpenCV MSER (delta 5),\n"
      "FAST-9, GFTT-Harris and CoMIC-paper (Algorithm 1, 1 thread) on IMAGE resized to\n"
      "--resize-height, each run --runs times after one warm-up run, and prints the median\n"
      "milliseconds per frame and the ratios CoMIC (1 thread) / MSER and CoMIC-paper / MSER,\n"
      "then each CoMIC's one-thread time by stage. --threads sets the worker count of the\n"
      "second CoMIC run (and of --perturbations); OpenCV's own thread pool is left as\n"
      "configured (cv::getNumThreads() is reported).");
  AddFlags(parser, flags);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  flags.Check();

  const cv::Mat gray = comic::io::LoadImage(flags.input, flags.resize_height).gray;
  cv::Mat gray2;
  if (!flags.match_pair.empty()) {
    gray2 = comic::io::LoadImage(flags.match_pair, flags.resize_height).gray;
    COMIC_CHECK(gray2.size() == gray.size(), kInvalidArgument,
                flags.match_pair << " is " << gray2.cols << "x" << gray2.rows << ", " << flags.input
                                 << " is " << gray.cols << "x" << gray.rows
                                 << " (--match-pair needs equal sizes)");
  }
  if (flags.match_only) {
    std::cout << "image: " << flags.input << " (" << gray.cols << "x" << gray.rows << ")\n";
    PrintMatcherTimes(gray, gray2, flags.match_features, flags.runs);
    return 0;
  }
  const int many = comic::frontend::ResolveNumThreads(flags.threads, 1 << 20);
  std::cout << "image: " << flags.input << " (" << gray.cols << "x" << gray.rows << "), "
            << flags.runs << " runs per detector, OpenCV threads: " << cv::getNumThreads()
            << "\n\n";

  StageTimes times;
  const std::vector<Entry> entries = TimeDetectors(gray, flags.runs, many, times);
  const comic::io::ReportTable table = PrintTimes(entries, many);
  PrintStageTimes(times, entries[2].timing.median_ms);
  if (!flags.json_path.empty()) {
    comic::io::WriteFileAtomically(flags.json_path, comic::io::JsonText(table.ToJson(), 1));
  }
  if (flags.perturbations) {
    if (flags.counts.empty()) flags.counts.push_back(0);
    for (int count : flags.counts) {
      PrintPerturbations(gray, many, count, flags.perturbation_detectors);
    }
  }
  if (!gray2.empty()) PrintMatcherTimes(gray, gray2, flags.match_features, flags.runs);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return comic::apps::RunMain("comic_bench", [&] { return Run(argc, argv); });
}
