// FAST-9 corner detector (Rosten & Drummond 2006), a baseline of the paper (§5.1): a pixel is a
// corner when 9 contiguous pixels of the 16-pixel Bresenham circle of radius 3 are all brighter
// or all darker than the centre by more than a threshold. Candidates come from cv::FAST
// (TYPE_9_16) at the lowest threshold; the response is the FAST score, the largest threshold at
// which the pixel is still a corner — an integer, so ties at a cut-off are common (see
// threshold_equalisation.h for how they are resolved); a 3x3 non-maximum suppression on the
// score follows.
//
// Score and suppression are computed here, not by OpenCV: cv::FAST reports scores only inside
// its own suppression, which keeps a corner only if its score is strictly above all 8
// neighbours, so two adjacent corners of equal score both vanish (every corner of an
// axis-aligned synthetic square does). Ours keeps the first of equal neighbours in raster order.
#pragma once

#include <string>

#include "frontend/detector.h"

namespace comic::frontend {

struct FastDetectorOptions {
  // Lowest intensity-difference threshold, in grey levels: every corner at this threshold is a
  // candidate, and threshold equalisation raises the cut-off on the score from there.
  int min_threshold = 5;
  // Keep only corners whose score is the maximum of their 3x3 neighbourhood.
  bool nonmax_suppression = true;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

class FastDetector : public Detector {
 public:
  explicit FastDetector(const FastDetectorOptions& options = {});

  std::string Name() const override { return "fast"; }
  // Corners at integer positions, response = FAST score, scale = 3 (the circle's radius).
  FeatureSet Detect(const cv::Mat& gray) const override;

  const FastDetectorOptions& options() const { return options_; }

 private:
  FastDetectorOptions options_;
};

}  // namespace comic::frontend
