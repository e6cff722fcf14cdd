#include "sfm/run/detect_run.h"

#include <chrono>
#include <memory>

#include "io/core/error.h"
#include "io/core/thread_count.h"

namespace comic::sfm {
namespace {

// The fields both searches share, then the direct search's own.
frontend::ComicDirectDetectorOptions DirectOptions(const DetectRunOptions& o) {
  frontend::ComicDirectDetectorOptions direct;
  direct.scale = o.scale;
  direct.delta = o.delta;
  direct.half_length = o.half_length;
  direct.merge_radius = o.merge_radius;
  direct.min_stability = o.min_stability;
  direct.min_cornerness = o.min_cornerness;
  direct.num_threads = o.threads;
  direct.presmoothing_sigma = o.presmoothing_sigma;
  direct.level_radius = o.level_radius;
  direct.bridge_levels = o.bridge_levels;
  direct.link_radius = o.link_radius;
  direct.consensus_fraction = o.consensus_fraction;
  return direct;
}

// The fields both searches share, then Algorithm 1's own.
frontend::ComicDetectorOptions PaperOptions(const DetectRunOptions& o) {
  frontend::ComicDetectorOptions paper;
  paper.scale = o.scale;
  paper.delta = o.delta;
  paper.half_length = o.half_length;
  paper.merge_radius = o.merge_radius;
  paper.min_stability = o.min_stability;
  paper.min_cornerness = o.min_cornerness;
  paper.num_threads = o.threads;
  paper.block_size = o.block_size;
  paper.max_iterations = o.max_iterations;
  paper.convergence_tolerance = o.convergence_tolerance;
  paper.stop_tolerance = o.stop_tolerance;
  paper.coarse_initialisation = !o.full_resolution_init;
  paper.seed_neighbouring_corners = !o.no_neighbour_seeds;
  paper.skip_duplicate_paths = !o.every_path;
  return paper;
}

}  // namespace

bool IsComicSearch(const std::string& detector) {
  return detector == "comic" || detector == "comic-paper";
}

frontend::DetectorOptions DetectRunOptions::ToDetectorOptions() const {
  frontend::DetectorOptions options = other;
  options.name = detector;
  options.comic = DirectOptions(*this);
  options.comic_paper = PaperOptions(*this);
  return options;
}

void DetectRunOptions::Check() const {
  COMIC_CHECK(max_features >= 0, kInvalidArgument, "--max-features must be >= 0");
  io::CheckThreadCount("--threads", threads);
  const frontend::DetectorOptions options = ToDetectorOptions();
  options.Check();  // the name (listing the valid ones) and the named detector's options
  options.comic.Check();
  options.comic_paper.Check();
}

DetectRunResult RunDetect(const DetectRunOptions& options, const cv::Mat& gray) {
  options.Check();
  const std::unique_ptr<frontend::Detector> detector =
      frontend::MakeDetector(options.ToDetectorOptions());
  DetectRunResult result;
  result.detector_name = detector->Name();
  const auto start = std::chrono::steady_clock::now();
  result.features = detector->Detect(gray);
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (options.max_features > 0 &&
      result.features.size() > static_cast<size_t>(options.max_features)) {
    result.features.resize(options.max_features);
  }
  return result;
}

}  // namespace comic::sfm
