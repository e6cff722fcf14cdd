// The one interface behind which CoMIC and the baseline detectors (Harris, Hessian, MSER,
// FAST-9) sit. A detector returns every candidate with its response; a detection threshold is a
// response cut-off applied afterwards, so threshold equalisation (paper §5.1) is one generic
// function rather than per-detector code.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "frontend/feature.h"

namespace comic::frontend {

class Detector {
 public:
  virtual ~Detector() = default;

  // Short lower-case name used in reports and on the command line ("comic", "harris", ...).
  virtual std::string Name() const = 0;

  // Detects features in an 8-bit single-channel image and returns every candidate, sorted
  // strongest first (SortByResponse). Images too small to hold a feature, or uniform, give an
  // empty result, not an error; an image of the wrong type throws comic::Error
  // (kInvalidArgument). The result is a deterministic function of the image and the options,
  // whatever the number of threads.
  virtual FeatureSet Detect(const cv::Mat& gray) const = 0;
};

}  // namespace comic::frontend
