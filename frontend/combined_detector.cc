#include "frontend/combined_detector.h"

#include <sstream>

#include "io/core/error.h"

namespace comic::frontend {

std::vector<std::string> SplitCombinedDetectorName(const std::string& name) {
  std::vector<std::string> parts;
  size_t begin = 0;
  while (true) {
    const size_t plus = name.find('+', begin);
    parts.push_back(
        name.substr(begin, plus == std::string::npos ? std::string::npos : plus - begin));
    if (plus == std::string::npos) break;
    begin = plus + 1;
  }
  return parts;
}

CombinedDetector::CombinedDetector(std::vector<std::unique_ptr<Detector>> components)
    : components_(std::move(components)) {
  COMIC_CHECK(components_.size() >= 2, kInvalidArgument,
              "combined detector: needs two or more detectors, got " << components_.size());
  for (const auto& component : components_) {
    COMIC_CHECK(component != nullptr, kInvalidArgument, "combined detector: null component");
  }
}

std::string CombinedDetector::Name() const {
  std::string name;
  for (const auto& component : components_) name += (name.empty() ? "" : "+") + component->Name();
  return name;
}

FeatureSet CombinedDetector::Detect(const cv::Mat& gray) const {
  FeatureSet features;
  for (const auto& component : components_) {
    FeatureSet part = component->Detect(gray);
    features.insert(features.end(), std::make_move_iterator(part.begin()),
                    std::make_move_iterator(part.end()));
  }
  return features;
}

}  // namespace comic::frontend
