// Any detector in scale space: the base detector runs on the image as given (level 0) and on an
// image pyramid of it, each level 1/level_factor the size of the one before, and every feature
// comes back in level-0 pixels with its scale multiplied by level_factor^level. A blurred frame
// has no sharp corners left at level 0 but has them at a level where the blur is ~1 pixel (issues
// 41 and 47, item 2; Lowe 2004 §3, Lindeberg 1998 for scale selection). The features keep what
// the descriptor needs: the scale (so a SIFT descriptor, frontend/description/, is measured at
// the level's σ and its orientation on that level too), the response, and CoMIC's curve and side
// mask mapped to level 0.
//
//   ScaleSpaceDetectorOptions options;
//   options.num_levels = 3;
//   ScaleSpaceDetector detector(MakeDetector("harris"), options);
//   FeatureSet features = detector.Detect(gray);  // every level's candidates, strongest first
//
// Or through the factory: DetectorOptions::scale_space (detector_factory.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "frontend/detector.h"

namespace comic::frontend {

struct ScaleSpaceDetectorOptions {
  // Levels detected on, the image as given included (1: the base detector alone, unchanged).
  int num_levels = 1;
  // Each level is this many times smaller than the one before (2: half the width and height),
  // made by area averaging (cv::resize INTER_AREA), see scale_space_detector.cc for why.
  double level_factor = 2.0;
  // A feature closer than this (level-0 pixels) to a feature of another level that responds more
  // strongly is dropped: the same corner seen at two levels is kept once, at the level where it
  // responds most (scale selection). 0 keeps every level's features.
  double duplicate_radius_px = 3.0;
  // No level is made whose smaller side would be below this (pixels): the base detectors find
  // little in fewer pixels than their 23x23 matching patch.
  int min_level_size = 32;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The pyramid of `gray` (CV_8UC1): level 0 is `gray` itself (not copied), level l is level l − 1
// resized by 1 / level_factor with area averaging, as long as its smaller side stays at least
// min_level_size; at most num_levels levels, at least one.
std::vector<cv::Mat> BuildScaleLevels(const cv::Mat& gray,
                                      const ScaleSpaceDetectorOptions& options);

// The level-0 coordinate of coordinate `c` of a level that is `factor` times smaller. Pixel
// centres are at integers at every level (feature.h's convention, OpenCV's): level pixel i covers
// level-0 pixels [(i · factor) − 0.5, ((i + 1) · factor) − 0.5), its centre is (i + 0.5) · factor
// − 0.5.
inline double ToLevelZero(double c, double factor) { return (c + 0.5) * factor - 0.5; }

// `feature`, detected on a level `factor` (= level_factor^l) times smaller than level 0, in
// level-0 terms: position and curve points by ToLevelZero, scale times `factor`, side mask
// resampled onto the level-0 patch (each level-0 pixel takes the label of the level pixel it
// lies in). Response, cornerness, iso level and polarity are kept: they are measured in the
// level's own pixels, which is what makes responses of different levels comparable (a corner of
// a given contrast responds alike at every level at which it is sharp).
Feature MapToLevelZero(Feature feature, double factor);

// The features of all levels as one set, strongest first (SortByResponse): each level's features
// (already in level-0 pixels) in order of response over all levels, a feature dropped when one
// already kept from another level lies closer than `duplicate_radius_px`. Features of one level
// are never dropped for each other (the base detector's own non-maximum suppression decides
// those). Equal responses: the finer level first.
FeatureSet MergeScaleLevels(const std::vector<FeatureSet>& levels, double duplicate_radius_px);

class ScaleSpaceDetector : public Detector {
 public:
  // Throws comic::Error(kInvalidArgument) for a null base or bad options.
  ScaleSpaceDetector(std::unique_ptr<Detector> base, const ScaleSpaceDetectorOptions& options);

  // The base detector's name, unchanged: the name chooses the descriptor's σ per scale
  // (DescriptorOptionsFor), names track files and reports, and the track cache's key holds the
  // scale-space options besides it (sfm/run/track_cache.cc).
  std::string Name() const override { return base_->Name(); }
  // MergeScaleLevels(DetectLevels(gray), duplicate_radius_px). Sequential over levels (the base
  // detector may use threads inside a level), so as deterministic as the base detector.
  FeatureSet Detect(const cv::Mat& gray) const override;

  // Each level's features (the base detector's, strongest first), mapped to level 0 by
  // MapToLevelZero, before duplicates across levels are dropped; one set per level built.
  std::vector<FeatureSet> DetectLevels(const cv::Mat& gray) const;

  const Detector& base() const { return *base_; }
  const ScaleSpaceDetectorOptions& options() const { return options_; }

 private:
  std::unique_ptr<Detector> base_;
  ScaleSpaceDetectorOptions options_;
};

}  // namespace comic::frontend
