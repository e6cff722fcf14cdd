#include "frontend/detector_factory.h"

#include <algorithm>
#include <sstream>

#include "frontend/combined_detector.h"
#include "io/core/error.h"

namespace comic::frontend {
namespace {

std::string ValidNames() {
  std::string names;
  for (const std::string& name : DetectorNames()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

bool IsSingleDetectorName(const std::string& name) {
  const auto& names = DetectorNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// A name of DetectorNames(), or two or more distinct ones joined by '+'.
void CheckName(const std::string& name) {
  const std::vector<std::string> parts = SplitCombinedDetectorName(name);
  for (const std::string& part : parts) {
    COMIC_CHECK(IsSingleDetectorName(part), kInvalidArgument,
                "unknown detector '" << part << "'"
                                     << (parts.size() > 1 ? " in '" + name + "'" : std::string())
                                     << " (valid: " << ValidNames()
                                     << "); several may be joined by '+', e.g. comic+hessian");
  }
  for (size_t i = 0; i < parts.size(); ++i) {
    for (size_t j = i + 1; j < parts.size(); ++j) {
      COMIC_CHECK(parts[i] != parts[j], kInvalidArgument,
                  "detector '" << parts[i] << "' appears twice in '" << name << "'");
    }
  }
}

}  // namespace

const std::vector<std::string>& DetectorNames() {
  static const std::vector<std::string> kNames = {"comic",   "comic-paper", "harris",
                                                  "hessian", "mser",        "fast"};
  return kNames;
}

void CheckDetectorName(const std::string& name) { CheckName(name); }

bool IsDetectorName(const std::string& name) {
  try {
    CheckName(name);
  } catch (const Error&) {
    return false;
  }
  return true;
}

void DetectorOptions::Check() const {
  CheckName(name);
  if (name.find('+') != std::string::npos) {
    for (const std::string& part : SplitCombinedDetectorName(name)) {
      DetectorOptions component = *this;
      component.name = part;
      component.Check();
    }
    return;
  }
  if (name == "comic") comic.Check();
  if (name == "comic-paper") comic_paper.Check();
  if (name == "harris") harris.Check();
  if (name == "hessian") hessian.Check();
  if (name == "mser") mser.Check();
  if (name == "fast") fast.Check();
  scale_space.Check();
}

std::unique_ptr<Detector> MakeDetector(const DetectorOptions& options) {
  options.Check();
  if (options.name.find('+') != std::string::npos) {
    std::vector<std::unique_ptr<Detector>> components;
    for (const std::string& part : SplitCombinedDetectorName(options.name)) {
      DetectorOptions component = options;
      component.name = part;
      components.push_back(MakeDetector(component));
    }
    return std::make_unique<CombinedDetector>(std::move(components));
  }
  std::unique_ptr<Detector> detector;
  if (options.name == "comic") {
    detector = std::make_unique<ComicDirectDetector>(options.comic);
  } else if (options.name == "comic-paper") {
    detector = std::make_unique<ComicDetector>(options.comic_paper);
  } else if (options.name == "harris") {
    detector = std::make_unique<HarrisDetector>(options.harris);
  } else if (options.name == "hessian") {
    detector = std::make_unique<HessianDetector>(options.hessian);
  } else if (options.name == "mser") {
    detector = std::make_unique<MserDetector>(options.mser);
  } else {
    detector = std::make_unique<FastDetector>(options.fast);
  }
  if (options.scale_space.num_levels == 1) return detector;
  return std::make_unique<ScaleSpaceDetector>(std::move(detector), options.scale_space);
}

std::unique_ptr<Detector> MakeDetector(const std::string& name) {
  DetectorOptions options;
  options.name = name;
  return MakeDetector(options);
}

std::vector<std::string> ParseDetectorList(const std::string& list) {
  std::vector<std::string> names;
  std::istringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    COMIC_CHECK(!name.empty(), kInvalidArgument, "empty name in detector list '" << list << "'");
    CheckName(name);
    COMIC_CHECK(std::find(names.begin(), names.end(), name) == names.end(), kInvalidArgument,
                "detector '" << name << "' listed twice");
    names.push_back(name);
  }
  COMIC_CHECK(!names.empty(), kInvalidArgument,
              "empty detector list (valid: " << ValidNames() << ")");
  return names;
}

}  // namespace comic::frontend
