// The detection run behind comic_detect and Python's comic.detect: CoMIC's options named once,
// as the flags and keywords of the detector option table (detector_option_table.h) set them,
// mapped onto the search that runs; the detection; and the strongest features kept.
//
//   comic::sfm::DetectRunOptions options;  // the direct search, every core
//   options.detector = "comic-paper";
//   options.full_resolution_init = true;
//   options.Check();
//   comic::sfm::DetectRunResult result = comic::sfm::RunDetect(options, gray);
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "frontend/detector_factory.h"
#include "frontend/feature.h"

namespace comic::sfm {

struct DetectRunOptions {
  // One of frontend::DetectorNames() or several joined by '+'; comic_detect runs "comic" (the
  // direct search) or "comic-paper" (Algorithm 1).
  std::string detector = "comic";

  // Both CoMIC searches. Each default is the search's own (the table's test checks that the two
  // searches agree on the ones they share).
  double scale = frontend::ComicDirectDetectorOptions().scale;
  int delta = frontend::ComicDirectDetectorOptions().delta;
  int half_length = frontend::ComicDirectDetectorOptions().half_length;
  double merge_radius = frontend::ComicDirectDetectorOptions().merge_radius;
  double min_stability = frontend::ComicDirectDetectorOptions().min_stability;
  double min_cornerness = frontend::ComicDirectDetectorOptions().min_cornerness;

  // comic-paper (Algorithm 1) only. The switches say what differs from the default search, so
  // that each is off by default: full_resolution_init = !coarse_initialisation,
  // no_neighbour_seeds = !seed_neighbouring_corners, every_path = !skip_duplicate_paths.
  int block_size = frontend::ComicDetectorOptions().block_size;
  int max_iterations = frontend::ComicDetectorOptions().max_iterations;
  double convergence_tolerance = frontend::ComicDetectorOptions().convergence_tolerance;
  double stop_tolerance = frontend::ComicDetectorOptions().stop_tolerance;
  bool full_resolution_init = !frontend::ComicDetectorOptions().coarse_initialisation;
  bool no_neighbour_seeds = !frontend::ComicDetectorOptions().seed_neighbouring_corners;
  bool every_path = !frontend::ComicDetectorOptions().skip_duplicate_paths;

  // comic (the direct search) only.
  double presmoothing_sigma = frontend::ComicDirectDetectorOptions().presmoothing_sigma;
  int level_radius = frontend::ComicDirectDetectorOptions().level_radius;
  int bridge_levels = frontend::ComicDirectDetectorOptions().bridge_levels;
  double link_radius = frontend::ComicDirectDetectorOptions().link_radius;
  double consensus_fraction = frontend::ComicDirectDetectorOptions().consensus_fraction;

  // Worker threads of either search (0: one per core); the features do not depend on it.
  int threads = 0;
  // Keep the strongest N features (0: all).
  int max_features = 0;
  // What the table does not cover: the baselines' options and the scale space (comic.detect's
  // harris, hessian, mser and fast keywords, scale_levels). Its name and CoMIC fields are
  // ignored: the fields above make those.
  frontend::DetectorOptions other;

  // Throws comic::Error(kInvalidArgument) naming the bad option. Both CoMIC searches' options are
  // checked whichever runs, so that a bad value is an error rather than ignored.
  void Check() const;
  // The detector's options: `other` with the name and both CoMIC searches made from the fields.
  frontend::DetectorOptions ToDetectorOptions() const;
};

// True for the two CoMIC searches, the detectors the table's options are for.
bool IsComicSearch(const std::string& detector);

struct DetectRunResult {
  frontend::FeatureSet features;  // strongest first, at most max_features
  std::string detector_name;      // the detector's own name (frontend::Detector::Name)
  double milliseconds = 0.0;      // the detection's wall-clock time (reported, never compared)
};

// Detects with `options` (checked first) on the 8-bit grey `gray` and keeps the strongest
// max_features. The features do not depend on the thread count.
DetectRunResult RunDetect(const DetectRunOptions& options, const cv::Mat& gray);

}  // namespace comic::sfm
