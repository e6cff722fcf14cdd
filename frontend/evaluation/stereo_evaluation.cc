#include "frontend/evaluation/stereo_evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

int RegionIndex(StereoRegion region) { return static_cast<int>(region); }

// The region a valid pixel class belongs to (the overall region holds both).
int RegionOfClass(StereoPixelClass c) {
  return c == StereoPixelClass::kBoundary ? RegionIndex(StereoRegion::kBoundary)
                                          : RegionIndex(StereoRegion::kNonBoundary);
}

bool IsValid(StereoPixelClass c) {
  return c == StereoPixelClass::kBoundary || c == StereoPixelClass::kNonBoundary;
}

void Report(const StereoProgress& progress, const std::string& message) {
  if (progress) progress(message);
}

FeatureSet FittingFeatures(const FeatureSet& features, const cv::Size& size) {
  FeatureSet kept;
  kept.reserve(features.size());
  for (const Feature& f : features) {
    if (PatchFits(f, size)) kept.push_back(f);
  }
  return kept;
}

// Right features sorted by row, for "is any feature within r of p" queries.
class RowIndex {
 public:
  explicit RowIndex(const FeatureSet& features) {
    points_.reserve(features.size());
    for (const Feature& f : features) points_.push_back(f.Position());
    std::sort(points_.begin(), points_.end(), [](const cv::Point2f& a, const cv::Point2f& b) {
      return a.y != b.y ? a.y < b.y : a.x < b.x;
    });
  }

  bool AnyWithin(const cv::Point2f& p, double radius) const {
    auto it = std::lower_bound(points_.begin(), points_.end(), p.y - radius,
                               [](const cv::Point2f& a, double y) { return a.y < y; });
    for (; it != points_.end() && it->y <= p.y + radius; ++it) {
      const double dx = it->x - p.x;
      const double dy = it->y - p.y;
      if (dx * dx + dy * dy <= radius * radius) return true;
    }
    return false;
  }

 private:
  std::vector<cv::Point2f> points_;
};

}  // namespace

const char* StereoRegionName(StereoRegion region) {
  switch (region) {
    case StereoRegion::kBoundary:
      return "boundary";
    case StereoRegion::kNonBoundary:
      return "non-boundary";
    case StereoRegion::kOverall:
      return "overall";
  }
  return "?";
}

std::string StereoMethod::Label() const { return detector + "/" + MatchCostName(cost); }

std::vector<StereoMethod> DefaultStereoMethods() {
  return {{"comic", MatchCost::kSplitMinOfFourPairings},
          {"comic", MatchCost::kSplitLikeSides},
          {"comic", MatchCost::kFullPatch},
          {"comic-paper", MatchCost::kSplitMinOfFourPairings},
          {"harris", MatchCost::kFullPatch},
          {"hessian", MatchCost::kFullPatch},
          {"mser", MatchCost::kFullPatch},
          {"fast", MatchCost::kFullPatch}};
}

std::vector<StereoMethod> ParseStereoMethods(const std::string& list) {
  std::vector<StereoMethod> methods;
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ',')) {
    COMIC_CHECK(!item.empty(), kInvalidArgument, "methods: empty entry in '" << list << "'");
    StereoMethod method;
    const size_t slash = item.find('/');
    method.detector = item.substr(0, slash);
    COMIC_CHECK(IsDetectorName(method.detector), kInvalidArgument,
                "methods: unknown detector '"
                    << method.detector
                    << "' (valid: comic, comic-paper, harris, hessian, mser, fast)");
    method.cost =
        slash == std::string::npos ? MatchCost::kFullPatch : ParseMatchCost(item.substr(slash + 1));
    COMIC_CHECK(std::find(methods.begin(), methods.end(), method) == methods.end(),
                kInvalidArgument, "methods: " << method.Label() << " is listed twice");
    methods.push_back(method);
  }
  COMIC_CHECK(!methods.empty(), kInvalidArgument, "methods: the list is empty");
  return methods;
}

void StereoEvaluationOptions::Check() const {
  COMIC_CHECK(working_height >= 0, kInvalidArgument,
              "stereo evaluation: working_height must be >= 0, got " << working_height);
  COMIC_CHECK(!methods.empty(), kInvalidArgument, "stereo evaluation: no methods to evaluate");
  for (size_t i = 0; i < methods.size(); ++i) {
    COMIC_CHECK(IsDetectorName(methods[i].detector), kInvalidArgument,
                "stereo evaluation: unknown detector '" << methods[i].detector << "'");
    for (size_t j = 0; j < i; ++j) {
      COMIC_CHECK(!(methods[i] == methods[j]), kInvalidArgument,
                  "stereo evaluation: method " << methods[i].Label() << " is listed twice");
    }
  }
  for (const std::string& name : DetectorNames()) {
    DetectorOptions named = detectors;
    named.name = name;
    named.Check();
  }
  COMIC_CHECK(!target_counts.empty(), kInvalidArgument,
              "stereo evaluation: target_counts is empty");
  for (int n : target_counts) {
    COMIC_CHECK(
        n >= 0, kInvalidArgument,
        "stereo evaluation: target counts must be >= 0 (0 = the reference's count), got " << n);
  }
  COMIC_CHECK(IsDetectorName(count_reference), kInvalidArgument,
              "stereo evaluation: unknown count_reference detector '" << count_reference << "'");
  COMIC_CHECK(row_tolerance >= 0, kInvalidArgument,
              "stereo evaluation: row_tolerance must be >= 0 px, got " << row_tolerance);
  COMIC_CHECK(min_disparity >= 0, kInvalidArgument,
              "stereo evaluation: min_disparity must be >= 0 px, got " << min_disparity);
  COMIC_CHECK(max_disparity >= 0, kInvalidArgument,
              "stereo evaluation: max_disparity must be >= 0 px (0 = from the ground truth), got "
                  << max_disparity);
  COMIC_CHECK(max_disparity == 0 || max_disparity >= min_disparity, kInvalidArgument,
              "stereo evaluation: max_disparity ("
                  << max_disparity << ") must be >= min_disparity (" << min_disparity << ")");
  COMIC_CHECK(disparity_margin >= 0, kInvalidArgument,
              "stereo evaluation: disparity_margin must be >= 0 px, got " << disparity_margin);
  COMIC_CHECK(min_side_overlap >= 1 && min_side_overlap <= kPatchSize * kPatchSize,
              kInvalidArgument,
              "stereo evaluation: min_side_overlap must be in [1, 529], got " << min_side_overlap);
  {
    PatchMatcherOptions matcher;
    matcher.min_side_fraction = min_side_fraction;
    matcher.side_noise_sigma = side_noise_sigma;
    matcher.Check();  // the calibrated cost's options, with the matcher's own messages
  }
  COMIC_CHECK(max_cost > 0 && !std::isnan(max_cost), kInvalidArgument,
              "stereo evaluation: max_cost (T) must be > 0, got " << max_cost);
  for (double t : sensitivity_costs) {
    COMIC_CHECK(t > 0 && !std::isnan(t), kInvalidArgument,
                "stereo evaluation: sensitivity thresholds must be > 0, got " << t);
  }
  COMIC_CHECK(correct_tolerance > 0, kInvalidArgument,
              "stereo evaluation: correct_tolerance must be > 0 px, got " << correct_tolerance);
  COMIC_CHECK(!repeatability_tolerances.empty(), kInvalidArgument,
              "stereo evaluation: repeatability_tolerances is empty");
  for (double t : repeatability_tolerances) {
    COMIC_CHECK(t > 0, kInvalidArgument,
                "stereo evaluation: repeatability tolerances must be > 0 px, got " << t);
  }
  COMIC_CHECK(target_precision >= 0 && target_precision <= 1, kInvalidArgument,
              "stereo evaluation: target_precision must be in [0, 1] (0 = from "
                  << precision_reference.Label() << "), got " << target_precision);
  COMIC_CHECK(target_precision > 0 ||
                  std::find(methods.begin(), methods.end(), precision_reference) != methods.end(),
              kInvalidArgument,
              "stereo evaluation: the precision reference " << precision_reference.Label()
                                                            << " is not among the methods");
}

StereoGroundTruth::StereoGroundTruth(const io::MiddleburyPair& pair) {
  const cv::Size size = pair.left_gray.size();
  COMIC_CHECK(!pair.left_gray.empty() && pair.left_gray.type() == CV_8UC1, kInvalidArgument,
              "stereo evaluation: the left image must be a non-empty 8-bit grey image");
  COMIC_CHECK(pair.right_gray.type() == CV_8UC1 && pair.right_gray.size() == size, kInvalidArgument,
              "stereo evaluation: the right image is "
                  << pair.right_gray.cols << "x" << pair.right_gray.rows << " but the left is "
                  << size.width << "x" << size.height);
  COMIC_CHECK(pair.disparity.type() == CV_32FC1 && pair.disparity.size() == size, kInvalidArgument,
              "stereo evaluation: the disparity map must be CV_32F of the left image's size");
  const std::pair<const cv::Mat*, const char*> masks[] = {{&pair.nonocc, "nonocc"},
                                                          {&pair.disc, "disc"}};
  for (const auto& [mask, name] : masks) {
    COMIC_CHECK(
        mask->empty() || (mask->type() == CV_8UC1 && mask->size() == size), kInvalidArgument,
        "stereo evaluation: the " << name << " mask must be 8-bit of the left image's size");
  }
  disparity_ = pair.disparity;
  has_disc_ = !pair.disc.empty();
  has_nonocc_ = !pair.nonocc.empty();
  classes_.create(size, CV_8SC1);
  valid_ = cv::Mat::zeros(size, CV_8UC1);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const float d = disparity_.at<float>(y, x);
      StereoPixelClass c;
      if (!(d > 0) || !std::isfinite(d)) {
        c = StereoPixelClass::kUnknownDisparity;
      } else if (has_nonocc_ && pair.nonocc.at<uint8_t>(y, x) == 0) {
        c = StereoPixelClass::kOccluded;
      } else if (has_disc_ && pair.disc.at<uint8_t>(y, x) == 255) {
        c = StereoPixelClass::kBoundary;
      } else {
        c = StereoPixelClass::kNonBoundary;
      }
      classes_.at<int8_t>(y, x) = static_cast<int8_t>(c);
      if (IsValid(c)) valid_.at<uint8_t>(y, x) = 255;
      // Occluded pixels' disparities count too: the range is the pair's, as the issue sets it.
      if (c != StereoPixelClass::kUnknownDisparity) {
        max_disparity_ = std::max(max_disparity_, static_cast<double>(d));
      }
    }
  }
}

StereoPixelClass StereoGroundTruth::Classify(float x, float y) const {
  const int ix = static_cast<int>(std::lround(x));
  const int iy = static_cast<int>(std::lround(y));
  if (ix < 0 || iy < 0 || ix >= classes_.cols || iy >= classes_.rows) {
    return StereoPixelClass::kUnknownDisparity;
  }
  return static_cast<StereoPixelClass>(classes_.at<int8_t>(iy, ix));
}

cv::Point2f StereoGroundTruth::TrueRightPosition(float x, float y) const {
  const int ix = std::clamp(static_cast<int>(std::lround(x)), 0, disparity_.cols - 1);
  const int iy = std::clamp(static_cast<int>(std::lround(y)), 0, disparity_.rows - 1);
  return {x - disparity_.at<float>(iy, ix), y};
}

std::array<int, 4> StereoGroundTruth::PixelCounts() const {
  std::array<int, 4> counts{};
  for (int y = 0; y < classes_.rows; ++y) {
    for (int x = 0; x < classes_.cols; ++x) ++counts[classes_.at<int8_t>(y, x)];
  }
  return counts;
}

std::optional<double> RegionCounts::MScore() const {
  if (detected == 0) return std::nullopt;
  return static_cast<double>(correct) / detected;
}

std::optional<double> RegionCounts::Precision() const {
  if (accepted == 0) return std::nullopt;
  return static_cast<double>(correct) / accepted;
}

const StereoDetection& StereoRun::DetectionFor(const std::string& detector) const {
  for (const StereoDetection& d : detections) {
    if (d.detector == detector) return d;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "stereo evaluation: detector '" + detector + "' was not run");
}

StereoDetection MakeStereoDetection(const StereoGroundTruth& truth, const std::string& detector,
                                    const FeatureSet& left, const FeatureSet& right,
                                    const std::vector<double>& repeatability_tolerances) {
  StereoDetection detection;
  detection.detector = detector;
  detection.left = FittingFeatures(left, truth.size());
  detection.right = FittingFeatures(right, truth.size());
  detection.repeatable.assign(repeatability_tolerances.size(), {});
  const RowIndex right_index(detection.right);
  detection.left_class.reserve(detection.left.size());
  for (const Feature& f : detection.left) {
    const StereoPixelClass c = truth.Classify(f.x, f.y);
    detection.left_class.push_back(c);
    if (c == StereoPixelClass::kUnknownDisparity) {
      ++detection.unknown_disparity;
      continue;
    }
    if (c == StereoPixelClass::kOccluded) {
      ++detection.occluded;
      continue;
    }
    const int region = RegionOfClass(c);
    ++detection.detected[region];
    ++detection.detected[RegionIndex(StereoRegion::kOverall)];
    const cv::Point2f target = truth.TrueRightPosition(f.x, f.y);
    for (size_t k = 0; k < repeatability_tolerances.size(); ++k) {
      if (right_index.AnyWithin(target, repeatability_tolerances[k])) {
        ++detection.repeatable[k][region];
        ++detection.repeatable[k][RegionIndex(StereoRegion::kOverall)];
      }
    }
  }
  detection.cut.count = detection.detected[RegionIndex(StereoRegion::kOverall)];
  detection.cut.target = detection.cut.count;
  detection.cut.available = detection.cut.count;
  detection.cut.reached = true;
  detection.left_candidates = static_cast<int>(detection.left.size());
  detection.right_candidates = static_cast<int>(detection.right.size());
  return detection;
}

StereoMatching MatchStereoDetection(const io::MiddleburyPair& pair, const StereoGroundTruth& truth,
                                    const StereoDetection& detection, MatchCost cost,
                                    const StereoEvaluationOptions& options,
                                    double gate_max_disparity) {
  PatchMatcherOptions matcher;
  matcher.gate = CandidateGate::kRectifiedStereo;
  matcher.row_tolerance = options.row_tolerance;
  matcher.min_disparity = options.min_disparity;
  matcher.max_disparity = std::max(gate_max_disparity, options.min_disparity);
  matcher.cost = cost;
  matcher.min_side_overlap = options.min_side_overlap;
  matcher.min_side_fraction = options.min_side_fraction;
  matcher.side_noise_sigma = options.side_noise_sigma;
  matcher.side_noise_from_pair = options.side_noise_from_pair;
  matcher.max_cost = kInfinity;
  StereoMatching matching;
  matching.method = {detection.detector, cost};
  matching.mutual = SelectMutualBest(ComputeCandidateCosts(
      pair.left_gray, detection.left, pair.right_gray, detection.right, matcher));
  matching.verdict.reserve(matching.mutual.size());
  for (const PatchMatch& m : matching.mutual) {
    const Feature& l = detection.left[m.index1];
    if (!IsValid(detection.left_class[m.index1])) {
      matching.verdict.push_back(-1);
      continue;
    }
    const cv::Point2f target = truth.TrueRightPosition(l.x, l.y);
    const Feature& r = detection.right[m.index2];
    const double dx = r.x - target.x;
    const double dy = r.y - target.y;
    const bool correct = dx * dx + dy * dy <= options.correct_tolerance * options.correct_tolerance;
    matching.verdict.push_back(correct ? 1 : 0);
  }
  return matching;
}

RegionScores ScoreAt(const StereoDetection& detection, const StereoMatching& matching,
                     double max_cost) {
  COMIC_CHECK(matching.mutual.size() == matching.verdict.size(), kInvalidArgument,
              "stereo evaluation: " << matching.verdict.size() << " verdicts for "
                                    << matching.mutual.size() << " matches");
  RegionScores scores;
  for (int r = 0; r < kNumStereoRegions; ++r) scores[r].detected = detection.detected[r];
  for (size_t k = 0; k < matching.mutual.size(); ++k) {
    if (matching.verdict[k] < 0 || matching.mutual[k].cost > max_cost) continue;
    const int region = RegionOfClass(detection.left_class.at(matching.mutual[k].index1));
    for (int r : {region, RegionIndex(StereoRegion::kOverall)}) {
      ++scores[r].accepted;
      scores[r].correct += matching.verdict[k];
    }
  }
  return scores;
}

MatchedPrecision ScoreAtPrecision(const StereoDetection& detection, const StereoMatching& matching,
                                  double target_precision) {
  std::vector<PatchMatch> judged;
  std::vector<bool> correct;
  for (size_t k = 0; k < matching.mutual.size(); ++k) {
    if (matching.verdict.at(k) < 0) continue;
    judged.push_back(matching.mutual[k]);
    correct.push_back(matching.verdict[k] == 1);
  }
  MatchedPrecision result;
  result.point = ThresholdForPrecision(judged, correct, target_precision);
  if (result.point) {
    result.scores = ScoreAt(detection, matching, result.point->max_cost);
  } else {
    for (int r = 0; r < kNumStereoRegions; ++r) result.scores[r].detected = detection.detected[r];
  }
  return result;
}

StereoPairEvaluation EvaluateStereoPair(const io::MiddleburyPair& pair,
                                        const StereoEvaluationOptions& options,
                                        const StereoProgress& progress) {
  options.Check();
  COMIC_CHECK(options.working_height == 0 || pair.left_gray.rows == options.working_height,
              kInvalidArgument,
              "stereo evaluation: the pair is "
                  << pair.left_gray.rows << " px high but the protocol's working height is "
                  << options.working_height << " (load it at that height)");
  const StereoGroundTruth truth(pair);
  const cv::Size size = truth.size();

  StereoPairEvaluation result;
  result.name = pair.name;
  result.size = size;
  result.resize_factor = pair.resize_factor;
  result.disparity_scale = pair.disparity_scale;
  result.max_gt_disparity = truth.MaxDisparity();
  result.gate_min_disparity = options.min_disparity;
  result.gate_max_disparity = options.max_disparity > 0
                                  ? options.max_disparity
                                  : truth.MaxDisparity() + options.disparity_margin;
  result.pixel_counts = truth.PixelCounts();

  // Detectors in the order of first use by the methods, the count reference included.
  std::vector<std::string> detectors;
  for (const StereoMethod& m : options.methods) {
    if (std::find(detectors.begin(), detectors.end(), m.detector) == detectors.end()) {
      detectors.push_back(m.detector);
    }
  }
  const bool need_reference = std::find(options.target_counts.begin(), options.target_counts.end(),
                                        0) != options.target_counts.end();
  if (need_reference &&
      std::find(detectors.begin(), detectors.end(), options.count_reference) == detectors.end()) {
    detectors.push_back(options.count_reference);
  }

  // Every candidate of every detector on both images, patch fitting; detected once.
  std::map<std::string, std::pair<FeatureSet, FeatureSet>> candidates;
  for (const std::string& name : detectors) {
    DetectorOptions detector_options = options.detectors;
    detector_options.name = name;
    const std::unique_ptr<Detector> detector = MakeDetector(detector_options);
    Report(progress, result.name + ": detecting " + name + " on the left image");
    FeatureSet left = FittingFeatures(detector->Detect(pair.left_gray), size);
    Report(progress, result.name + ": detecting " + name + " on the right image");
    FeatureSet right = FittingFeatures(detector->Detect(pair.right_gray), size);
    candidates[name] = {std::move(left), std::move(right)};
  }
  if (need_reference) {
    result.reference_count =
        CountCountedFeatures(candidates.at(options.count_reference).first, size, truth.ValidMask());
  }

  for (int requested : options.target_counts) {
    StereoRun run;
    run.requested_count = requested;
    run.target_count = requested > 0 ? requested : result.reference_count;
    for (const std::string& name : detectors) {
      const auto& [left_all, right_all] = candidates.at(name);
      ThresholdCut cut;
      cut.target = run.target_count;
      cut.available = CountCountedFeatures(left_all, size, truth.ValidMask());
      if (run.target_count > 0) {
        cut = EqualiseThreshold(left_all, run.target_count, size, truth.ValidMask());
      } else {
        // N = 0 (the reference found nothing): every detector keeps nothing.
        cut.min_response = std::numeric_limits<float>::infinity();
      }
      StereoDetection detection = MakeStereoDetection(
          truth, name, ApplyThreshold(left_all, cut.min_response),
          ApplyThreshold(right_all, cut.min_response), options.repeatability_tolerances);
      detection.cut = cut;
      detection.left_candidates = static_cast<int>(left_all.size());
      detection.right_candidates = static_cast<int>(right_all.size());
      run.detections.push_back(std::move(detection));
    }
    for (const StereoMethod& method : options.methods) {
      Report(progress, result.name + ": N = " + std::to_string(run.target_count) + ", matching " +
                           method.Label());
      run.matchings.push_back(MatchStereoDetection(pair, truth, run.DetectionFor(method.detector),
                                                   method.cost, options,
                                                   result.gate_max_disparity));
    }
    if (options.target_precision > 0) {
      run.target_precision = options.target_precision;
    } else {
      for (const StereoMatching& m : run.matchings) {
        if (!(m.method == options.precision_reference)) continue;
        const RegionScores scores =
            ScoreAt(run.DetectionFor(m.method.detector), m, options.max_cost);
        run.target_precision = scores[RegionIndex(StereoRegion::kOverall)].Precision();
      }
    }
    result.runs.push_back(std::move(run));
  }
  return result;
}

}  // namespace comic::frontend
