#include "frontend/matching/patch_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "frontend/grid_cell_key.h"
#include "io/core/error.h"

namespace comic::frontend {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

float FullCost(const FeaturePatch& a, const FeaturePatch& b) {
  int64_t sum = 0;
  for (int k = 0; k < kPatchPixels; ++k) {
    const int d = static_cast<int>(a.values[k]) - static_cast<int>(b.values[k]);
    sum += d * d;
  }
  return static_cast<float>(static_cast<double>(sum) / kPatchPixels);
}

// Mean squared difference over pixels on side s1 in `a` and side s2 in `b` for every pairing
// (Algorithm 2, steps 8-10), minimum over the allowed pairings with enough overlap.
float SplitCost(const FeaturePatch& a, const FeaturePatch& b, bool like_sides_only,
                int min_overlap) {
  // Index 0: kPlus, 1: kMinus.
  int64_t sum[2][2] = {{0, 0}, {0, 0}};
  int count[2][2] = {{0, 0}, {0, 0}};
  for (int k = 0; k < kPatchPixels; ++k) {
    const PatchSide sa = a.sides[k];
    const PatchSide sb = b.sides[k];
    if (sa == PatchSide::kNone || sb == PatchSide::kNone) continue;
    const int ia = sa == PatchSide::kPlus ? 0 : 1;
    const int ib = sb == PatchSide::kPlus ? 0 : 1;
    const int d = static_cast<int>(a.values[k]) - static_cast<int>(b.values[k]);
    sum[ia][ib] += d * d;
    ++count[ia][ib];
  }
  float best = kInfinity;
  for (int ia = 0; ia < 2; ++ia) {
    for (int ib = 0; ib < 2; ++ib) {
      if (like_sides_only && ia != ib) continue;
      if (count[ia][ib] < min_overlap || count[ia][ib] == 0) continue;
      best = std::min(best, static_cast<float>(static_cast<double>(sum[ia][ib]) / count[ia][ib]));
    }
  }
  return best;
}

// The full-patch sum of squared differences and, over the union of side `side_a` of patch i and
// side `side_b` of patch j, the sum and the pixel count, in one branch-free pass over int16 words
// (differences within ±255, so d·d is one 16x16->32 bit multiply-add; 529 · 255² < 2³¹).
struct SideSums {
  int32_t full = 0;
  int32_t side = 0;
  int32_t count = 0;
};

SideSums SumOverSideUnion(const PatchSet& set_a, size_t i, PatchSide side_a, const PatchSet& set_b,
                          size_t j, PatchSide side_b) {
  const int16_t* va = set_a.Values(i);
  const int16_t* vb = set_b.Values(j);
  const int16_t* ma = set_a.SideWords(i, side_a);
  const int16_t* mb = set_b.SideWords(j, side_b);
  int32_t full = 0, side = 0, count = 0;
  for (int k = 0; k < kPatchPixels; ++k) {
    const int16_t d = static_cast<int16_t>(va[k] - vb[k]);
    const int16_t m = static_cast<int16_t>(ma[k] | mb[k]);  // all ones where k is on either side
    const int16_t dm = static_cast<int16_t>(d & m);
    full += static_cast<int32_t>(d) * d;
    side += static_cast<int32_t>(dm) * d;
    count -= m;
  }
  return {full, side, count};
}

// kCalibratedSides: the full-patch cost and the calibrated cost of the object sides' union (or,
// with like_sides_without_object, of both like pairings for a pair without object sides), the
// lowest of them.
float CalibratedCost(const PatchSet& set_a, size_t i, const PatchSet& set_b, size_t j,
                     const PatchMatcherOptions& options) {
  const FeaturePatch& a = set_a[i];
  const FeaturePatch& b = set_b[j];
  PatchSide pairings[2][2];
  int num_pairings = 0;
  if (a.has_sides && b.has_sides) {
    if (a.object_side != PatchSide::kNone && b.object_side != PatchSide::kNone) {
      pairings[num_pairings][0] = a.object_side;
      pairings[num_pairings++][1] = b.object_side;
    } else if (options.like_sides_without_object) {
      pairings[num_pairings][0] = PatchSide::kPlus;
      pairings[num_pairings++][1] = PatchSide::kPlus;
      pairings[num_pairings][0] = PatchSide::kMinus;
      pairings[num_pairings++][1] = PatchSide::kMinus;
    }
  }
  if (num_pairings == 0) return FullCost(a, b);
  const int min_pixels =
      std::max(options.min_side_overlap,
               static_cast<int>(std::ceil(options.min_side_fraction * kPatchPixels)));
  double best = kInfinity;
  for (int p = 0; p < num_pairings; ++p) {
    const SideSums sums = SumOverSideUnion(set_a, i, pairings[p][0], set_b, j, pairings[p][1]);
    best = std::min(best, static_cast<double>(sums.full) / kPatchPixels);
    if (sums.count < min_pixels) continue;
    best = std::min(best, CalibratedSideCost(static_cast<double>(sums.side) / sums.count,
                                             sums.count, options.side_noise_sigma));
  }
  return static_cast<float>(best);
}

float Cost(const PatchSet& set_a, size_t i, const PatchSet& set_b, size_t j,
           const PatchMatcherOptions& options) {
  const FeaturePatch& a = set_a[i];
  const FeaturePatch& b = set_b[j];
  if (!a.valid || !b.valid) return kInfinity;
  if (IsCalibratedCost(options.cost)) return CalibratedCost(set_a, i, set_b, j, options);
  if (options.cost == MatchCost::kFullPatch || !a.has_sides || !b.has_sides) {
    return FullCost(a, b);
  }
  return SplitCost(a, b, options.cost == MatchCost::kSplitLikeSides, options.min_side_overlap);
}

void CheckImage(const cv::Mat& gray, const char* which) {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "patch matcher: " << which << " must be a non-empty 8-bit single-channel image");
}

// Features of one image bucketed in square cells, for gate queries.
class FeatureGrid {
 public:
  FeatureGrid(const FeatureSet& features, double cell) : cell_(cell) {
    for (int i = 0; i < static_cast<int>(features.size()); ++i) {
      cells_[Key(Cell(features[i].x), Cell(features[i].y))].push_back(i);
    }
  }

  // Indices of features in cells overlapping [x0, x1] x [y0, y1], ascending.
  std::vector<int> Query(double x0, double x1, double y0, double y1) const {
    std::vector<int> found;
    for (int64_t cy = Cell(y0); cy <= Cell(y1); ++cy) {
      for (int64_t cx = Cell(x0); cx <= Cell(x1); ++cx) {
        const auto it = cells_.find(Key(cx, cy));
        if (it != cells_.end()) found.insert(found.end(), it->second.begin(), it->second.end());
      }
    }
    std::sort(found.begin(), found.end());
    return found;
  }

 private:
  int64_t Cell(double v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
  static uint64_t Key(int64_t cx, int64_t cy) { return GridCellKey(cx, cy); }

  double cell_;
  std::unordered_map<uint64_t, std::vector<int>> cells_;
};

}  // namespace

const char* MatchCostName(MatchCost cost) {
  switch (cost) {
    case MatchCost::kFullPatch:
      return "full";
    case MatchCost::kSplitMinOfFourPairings:
      return "split";
    case MatchCost::kSplitLikeSides:
      return "like-sides";
    case MatchCost::kCalibratedSides:
      return "calibrated";
    case MatchCost::kTrackSides:
      return "track-sides";
  }
  return "?";
}

MatchCost ParseMatchCost(const std::string& name) {
  for (MatchCost cost :
       {MatchCost::kFullPatch, MatchCost::kSplitMinOfFourPairings, MatchCost::kSplitLikeSides,
        MatchCost::kCalibratedSides, MatchCost::kTrackSides}) {
    if (name == MatchCostName(cost)) return cost;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "unknown match cost '" + name +
                  "' (valid: full, split, like-sides, calibrated, track-sides)");
}

bool IsCalibratedCost(MatchCost cost) {
  return cost == MatchCost::kCalibratedSides || cost == MatchCost::kTrackSides;
}

double PairNoiseSigma(const std::vector<PatchMatch>& full_patch_mutual, double fallback) {
  if (full_patch_mutual.empty()) return fallback;
  std::vector<float> costs;
  costs.reserve(full_patch_mutual.size());
  for (const PatchMatch& m : full_patch_mutual) costs.push_back(m.cost);
  const size_t middle = costs.size() / 2;
  std::nth_element(costs.begin(), costs.begin() + middle, costs.end());
  const double median = costs[middle];
  return median > 0 ? std::sqrt(0.5 * median) : fallback;
}

double CalibratedSideCost(double mean_squared_difference, int pixels, double noise_sigma) {
  COMIC_CHECK(pixels >= 1 && noise_sigma > 0 && mean_squared_difference >= 0, kInvalidArgument,
              "calibrated side cost: needs pixels >= 1, noise_sigma > 0 and a mean >= 0, got "
                  << pixels << ", " << noise_sigma << ", " << mean_squared_difference);
  if (pixels == kPatchPixels) return mean_squared_difference;
  const double scale = 2.0 * noise_sigma * noise_sigma;  // the mean of d² under the noise model
  const double g_n = std::sqrt(2.0 / (9.0 * pixels));
  const double g_full = std::sqrt(2.0 / (9.0 * kPatchPixels));
  const double z = (std::cbrt(mean_squared_difference / scale) - (1.0 - g_n * g_n)) / g_n;
  const double base = 1.0 - g_full * g_full + z * g_full;
  return base <= 0 ? 0.0 : scale * base * base * base;
}

void PatchMatcherOptions::Check() const {
  COMIC_CHECK(radius > 0, kInvalidArgument, "matcher: radius must be > 0 px, got " << radius);
  COMIC_CHECK(row_tolerance >= 0, kInvalidArgument,
              "matcher: row_tolerance must be >= 0 px, got " << row_tolerance);
  COMIC_CHECK(max_disparity >= min_disparity, kInvalidArgument,
              "matcher: max_disparity (" << max_disparity << ") must be >= min_disparity ("
                                         << min_disparity << ")");
  COMIC_CHECK(min_side_overlap >= 1 && min_side_overlap <= kPatchPixels, kInvalidArgument,
              "matcher: min_side_overlap must be in [1, " << kPatchPixels << "] pixels, got "
                                                          << min_side_overlap);
  COMIC_CHECK(max_cost >= 0 && !std::isnan(max_cost), kInvalidArgument,
              "matcher: max_cost must be >= 0, got " << max_cost);
  COMIC_CHECK(min_side_fraction >= 0 && min_side_fraction <= 1, kInvalidArgument,
              "matcher: min_side_fraction must be in [0, 1], got " << min_side_fraction);
  COMIC_CHECK(side_noise_sigma > 0 && std::isfinite(side_noise_sigma), kInvalidArgument,
              "matcher: side_noise_sigma must be a positive number of grey levels, got "
                  << side_noise_sigma);
}

PatchSides SidesFor(MatchCost cost) {
  switch (cost) {
    case MatchCost::kFullPatch:
      return PatchSides::kNone;
    case MatchCost::kSplitMinOfFourPairings:
    case MatchCost::kSplitLikeSides:
      return PatchSides::kDetector;
    case MatchCost::kCalibratedSides:
    case MatchCost::kTrackSides:
      return PatchSides::kLevelLines;
  }
  return PatchSides::kNone;
}

PatchSet PreparePatches(const cv::Mat& gray, const FeatureSet& features,
                        const PatchMatcherOptions& options) {
  return PatchSet(gray, features, SidesFor(options.cost));
}

std::vector<PatchMatch> ComputeCandidateCosts(const cv::Mat& gray1, const FeatureSet& features1,
                                              const cv::Mat& gray2, const FeatureSet& features2,
                                              const PatchMatcherOptions& options,
                                              const SearchRegions& search) {
  options.Check();
  CheckImage(gray1, "image 1");
  CheckImage(gray2, "image 2");
  return ComputeCandidateCosts(features1, PreparePatches(gray1, features1, options), features2,
                               PreparePatches(gray2, features2, options), options, search);
}

std::vector<PatchMatch> ComputeCandidateCosts(const FeatureSet& features1, const PatchSet& patches1,
                                              const FeatureSet& features2, const PatchSet& patches2,
                                              const PatchMatcherOptions& options,
                                              const SearchRegions& search) {
  options.Check();
  const PatchSides needed = SidesFor(options.cost);
  for (const PatchSet* patches : {&patches1, &patches2}) {
    COMIC_CHECK(needed == PatchSides::kNone || patches->sides() == needed, kInvalidArgument,
                "patch matcher: the " << MatchCostName(options.cost)
                                      << " cost needs patches prepared with its sides "
                                         "(PreparePatches with the same options)");
  }
  COMIC_CHECK(patches1.size() == features1.size() && patches2.size() == features2.size(),
              kInvalidArgument,
              "patch matcher: " << patches1.size() << " and " << patches2.size() << " patches for "
                                << features1.size() << " and " << features2.size() << " features");
  COMIC_CHECK(search.centres.empty() || search.centres.size() == features1.size(), kInvalidArgument,
              "patch matcher: " << search.centres.size() << " search centres for "
                                << features1.size() << " features");
  COMIC_CHECK(search.radii.empty() || search.radii.size() == features1.size(), kInvalidArgument,
              "patch matcher: " << search.radii.size() << " search radii for " << features1.size()
                                << " features");
  if (IsCalibratedCost(options.cost) && options.side_noise_from_pair) {
    // Two passes: the full patch's mutual-best matches give the pair's σ, then the calibrated
    // cost with it.
    PatchMatcherOptions full = options;
    full.cost = MatchCost::kFullPatch;
    full.side_noise_from_pair = false;
    PatchMatcherOptions calibrated = options;
    calibrated.side_noise_from_pair = false;
    calibrated.side_noise_sigma =
        PairNoiseSigma(SelectMutualBest(ComputeCandidateCosts(features1, patches1, features2,
                                                              patches2, full, search)),
                       options.side_noise_sigma);
    return ComputeCandidateCosts(features1, patches1, features2, patches2, calibrated, search);
  }
  const double cell = options.gate == CandidateGate::kRadius
                          ? std::max(8.0, options.radius)
                          : std::max(8.0, options.max_disparity - options.min_disparity);
  const FeatureGrid grid(features2, cell);

  std::vector<PatchMatch> candidates;
  for (int i = 0; i < static_cast<int>(features1.size()); ++i) {
    if (!patches1[i].valid) continue;
    const cv::Point2f centre = search.centres.empty() ? features1[i].Position() : search.centres[i];
    const double radius = search.radii.empty() ? options.radius : search.radii[i];
    std::vector<int> nearby;
    if (options.gate == CandidateGate::kRadius) {
      nearby =
          grid.Query(centre.x - radius, centre.x + radius, centre.y - radius, centre.y + radius);
    } else {
      nearby = grid.Query(centre.x - options.max_disparity, centre.x - options.min_disparity,
                          centre.y - options.row_tolerance, centre.y + options.row_tolerance);
    }
    for (int j : nearby) {
      const Feature& f2 = features2[j];
      if (options.gate == CandidateGate::kRadius) {
        const double dx = f2.x - centre.x;
        const double dy = f2.y - centre.y;
        if (dx * dx + dy * dy > radius * radius) continue;
      } else {
        const double disparity = centre.x - f2.x;
        if (std::abs(f2.y - centre.y) > options.row_tolerance ||
            disparity < options.min_disparity || disparity > options.max_disparity) {
          continue;
        }
      }
      const float cost = Cost(patches1, i, patches2, j, options);
      if (std::isinf(cost)) continue;
      candidates.push_back({i, j, cost});
    }
  }
  return candidates;
}

std::vector<PatchMatch> SelectMutualBest(const std::vector<PatchMatch>& candidates) {
  // Best partner of every index on each side: lowest cost, then lowest partner index.
  std::unordered_map<int, const PatchMatch*> best1, best2;
  auto better = [](const PatchMatch& a, const PatchMatch* b, bool by_index2) {
    if (b == nullptr) return true;
    if (a.cost != b->cost) return a.cost < b->cost;
    return by_index2 ? a.index2 < b->index2 : a.index1 < b->index1;
  };
  for (const PatchMatch& c : candidates) {
    const PatchMatch*& b1 = best1[c.index1];
    if (better(c, b1, true)) b1 = &c;
    const PatchMatch*& b2 = best2[c.index2];
    if (better(c, b2, false)) b2 = &c;
  }
  std::vector<PatchMatch> mutual;
  for (const auto& [index1, match] : best1) {
    if (best2.at(match->index2) == match) mutual.push_back(*match);
  }
  std::sort(mutual.begin(), mutual.end(),
            [](const PatchMatch& a, const PatchMatch& b) { return a.index1 < b.index1; });
  return mutual;
}

std::vector<PatchMatch> ApplyCostThreshold(const std::vector<PatchMatch>& matches,
                                           double max_cost) {
  std::vector<PatchMatch> accepted;
  for (const PatchMatch& m : matches) {
    if (m.cost <= max_cost) accepted.push_back(m);
  }
  return accepted;
}

std::vector<PatchMatch> MatchFeatures(const cv::Mat& gray1, const FeatureSet& features1,
                                      const cv::Mat& gray2, const FeatureSet& features2,
                                      const PatchMatcherOptions& options,
                                      const SearchRegions& search) {
  return ApplyCostThreshold(
      SelectMutualBest(ComputeCandidateCosts(gray1, features1, gray2, features2, options, search)),
      options.max_cost);
}

std::vector<PatchMatch> MatchFeatures(const FeatureSet& features1, const PatchSet& patches1,
                                      const FeatureSet& features2, const PatchSet& patches2,
                                      const PatchMatcherOptions& options,
                                      const SearchRegions& search) {
  return ApplyCostThreshold(SelectMutualBest(ComputeCandidateCosts(features1, patches1, features2,
                                                                   patches2, options, search)),
                            options.max_cost);
}

float PatchCost(const cv::Mat& gray1, const Feature& feature1, const cv::Mat& gray2,
                const Feature& feature2, const PatchMatcherOptions& options) {
  options.Check();
  CheckImage(gray1, "image 1");
  CheckImage(gray2, "image 2");
  return Cost(PreparePatches(gray1, {feature1}, options), 0,
              PreparePatches(gray2, {feature2}, options), 0, options);
}

float PatchCost(const PatchSet& patches1, size_t i, const PatchSet& patches2, size_t j,
                const PatchMatcherOptions& options) {
  options.Check();
  const PatchSides needed = SidesFor(options.cost);
  COMIC_CHECK(
      (needed == PatchSides::kNone || (patches1.sides() == needed && patches2.sides() == needed)) &&
          i < patches1.size() && j < patches2.size(),
      kInvalidArgument,
      "patch cost: patches " << i << " of " << patches1.size() << " and " << j << " of "
                             << patches2.size() << " prepared for another cost");
  return Cost(patches1, i, patches2, j, options);
}

}  // namespace comic::frontend
