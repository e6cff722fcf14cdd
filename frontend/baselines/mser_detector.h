// MSER (Matas et al. 2002) as a point detector, a baseline of the paper (§5.1: "we compare with
// MSER since their method is closely related to ours"): one feature per maximally stable
// extremal region, at the region's centroid, for both polarities (dark regions: components of
// {I ≤ level}; bright regions: components of {I ≥ level}).
//
// Own component-tree implementation (union-find over pixels sorted by grey level) rather than
// cv::MSER, because a threshold must be a cut-off on a per-feature response and cv::MSER does not
// report a region's stability. Stability follows OpenCV's one-sided definition: the variation
// v = (|Q(level + δ)| − |Q(level)|) / |Q(level)|, where Q(level + δ) is the component containing
// the region δ grey levels further; a region is maximally stable when v is a local minimum along
// its branch of the component tree (below its parent's, at most its largest child's). The
// response is 1 / (1 + v) (larger = more stable), so every stable region is a candidate and
// threshold equalisation picks the cut-off.
#pragma once

#include <string>

#include "frontend/detector.h"

namespace comic::frontend {

struct MserDetectorOptions {
  // δ, in grey levels (MSER's and OpenCV's customary 5; the paper's Fig. 3 uses δ = 5 as well).
  int delta = 5;
  // Smallest and largest region area, in pixels (OpenCV's defaults).
  int min_area = 60;
  int max_area = 14400;
  // Regions whose variation exceeds this are not candidates (dimensionless; 1 = the area doubles
  // over δ levels — nothing so unstable is "stable" in any sense).
  double max_variation = 1.0;
  // Centroids closer than this (pixels) are one feature — nested regions often share a centroid;
  // the more stable one is kept (like CoMIC's merge radius).
  double merge_radius = 2.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

class MserDetector : public Detector {
 public:
  explicit MserDetector(const MserDetectorOptions& options = {});

  std::string Name() const override { return "mser"; }
  // One feature per maximally stable region: position = centroid, response = 1 / (1 + v),
  // scale = sqrt(area / π), polarity = kDark / kBright.
  FeatureSet Detect(const cv::Mat& gray) const override;

  const MserDetectorOptions& options() const { return options_; }

 private:
  MserDetectorOptions options_;
};

}  // namespace comic::frontend
