// One place that builds any detector by name, so apps, the tracker and the evaluation treat CoMIC
// and the baselines alike (paper §5.1 compares CoMIC with Harris, Hessian, MSER and FAST-9).
//
//   comic::frontend::DetectorOptions options;
//   options.name = "harris";
//   options.harris.integration_sigma = 2.5;
//   std::unique_ptr<comic::frontend::Detector> detector = comic::frontend::MakeDetector(options);
//   comic::frontend::FeatureSet features = detector->Detect(gray);  // every candidate
//
// Every detector returns every candidate with its response, strongest first; a detection
// threshold is a cut-off on the response (see threshold_equalisation.h). Parameters are in pixels
// of the image given to Detect; the evaluation apps resize frames to height 700 first, as the
// paper's experiments do (§5.1), so the defaults are meant for that scale.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "frontend/baselines/fast_detector.h"
#include "frontend/baselines/harris_detector.h"
#include "frontend/baselines/hessian_detector.h"
#include "frontend/baselines/mser_detector.h"
#include "frontend/comic/comic_detector.h"
#include "frontend/comic/comic_direct_detector.h"
#include "frontend/detector.h"
#include "frontend/scale_space_detector.h"

namespace comic::frontend {

struct DetectorOptions {
  // Which detector: one of DetectorNames(), or several of them joined by '+' ("comic+hessian":
  // a CombinedDetector of those detectors, each with its options below).
  std::string name = "comic";
  // The options of each detector; only the one named is used. `comic`: the direct search of the
  // §2 definition (ComicDirectDetector); `comic_paper`: Algorithm 1 (ComicDetector, "comic-paper").
  ComicDirectDetectorOptions comic;
  ComicDetectorOptions comic_paper;
  HarrisDetectorOptions harris;
  HessianDetectorOptions hessian;
  MserDetectorOptions mser;
  FastDetectorOptions fast;
  // Every detector of the name in scale space (ScaleSpaceDetector): num_levels 1, the default, is
  // the detector alone. A combined name puts each component in scale space on its own, so that
  // its features are still tracked component by component.
  ScaleSpaceDetectorOptions scale_space;

  // Throws comic::Error(kInvalidArgument) for an unknown name (listing the valid ones) or bad
  // options of the named detector.
  void Check() const;
};

// {"comic", "comic-paper", "harris", "hessian", "mser", "fast"}: the paper's table order, with
// CoMIC's two searches first.
const std::vector<std::string>& DetectorNames();

// True if `name` is one of DetectorNames() or two or more distinct ones joined by '+'.
bool IsDetectorName(const std::string& name);

// Throws comic::Error(kInvalidArgument) saying what is wrong with `name` unless IsDetectorName.
void CheckDetectorName(const std::string& name);

// Builds the named detector with its options. Throws comic::Error(kInvalidArgument) as Check().
std::unique_ptr<Detector> MakeDetector(const DetectorOptions& options);

// Builds the named detector with default options.
std::unique_ptr<Detector> MakeDetector(const std::string& name);

// Splits a comma-separated list ("comic,harris,comic+hessian") into names, checking each one
// (IsDetectorName); throws
// comic::Error(kInvalidArgument) for an unknown or repeated name or an empty list.
std::vector<std::string> ParseDetectorList(const std::string& list);

}  // namespace comic::frontend
