// Several detectors as one (the paper's Discussion: Hessian's blobs complement CoMIC's boundary
// corners): "comic+hessian" detects with each and keeps every feature as its own detector made
// it (response, scale, side mask). The responses of different detectors are not comparable, so
// Detect() returns the components' features one after the other (each component's strongest
// first), and the tracker tracks each component on its own (frontend/matching/
// combined_tracking.h): features of different detectors are never matched to each other.
//
//   std::unique_ptr<Detector> detector = MakeDetector("comic+hessian");  // detector_factory.h
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "frontend/detector.h"

namespace comic::frontend {

// "comic+hessian" -> {"comic", "hessian"}; a name without '+' -> {name}. Empty parts are kept
// (as "") so that the caller can reject them.
std::vector<std::string> SplitCombinedDetectorName(const std::string& name);

class CombinedDetector : public Detector {
 public:
  // Two or more detectors; throws comic::Error(kInvalidArgument) otherwise.
  explicit CombinedDetector(std::vector<std::unique_ptr<Detector>> components);

  // The components' names joined by '+'.
  std::string Name() const override;
  // Component 0's features (strongest first), then component 1's, ...
  FeatureSet Detect(const cv::Mat& gray) const override;

  size_t NumComponents() const { return components_.size(); }
  const Detector& Component(size_t i) const { return *components_.at(i); }

 private:
  std::vector<std::unique_ptr<Detector>> components_;
};

}  // namespace comic::frontend
