#include "frontend/matching/patch_matcher.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "frontend/grid_cell_key.h"
#include "io/error.h"

namespace comic::frontend {

namespace {

constexpr int kPatchPixels = kPatchSize * kPatchSize;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// A feature's patch: grey values and side labels (kNone everywhere without a side mask).
struct Patch {
  bool valid = false;
  bool has_sides = false;
  std::array<uint8_t, kPatchPixels> values{};
  std::array<PatchSide, kPatchPixels> sides{};
};

Patch ExtractPatch(const cv::Mat& gray, const Feature& feature) {
  Patch patch;
  if (!PatchFits(feature, gray.size())) return patch;
  patch.valid = true;
  const int cx = static_cast<int>(std::lround(feature.x));
  const int cy = static_cast<int>(std::lround(feature.y));
  for (int v = 0; v < kPatchSize; ++v) {
    const uint8_t* row = gray.ptr<uint8_t>(cy - kPatchRadius + v) + (cx - kPatchRadius);
    std::copy(row, row + kPatchSize, patch.values.begin() + v * kPatchSize);
  }
  if (feature.HasSideMask()) {
    patch.has_sides = true;
    std::copy(feature.side_mask.begin(), feature.side_mask.end(), patch.sides.begin());
  }
  return patch;
}

float FullCost(const Patch& a, const Patch& b) {
  int64_t sum = 0;
  for (int k = 0; k < kPatchPixels; ++k) {
    const int d = static_cast<int>(a.values[k]) - static_cast<int>(b.values[k]);
    sum += d * d;
  }
  return static_cast<float>(static_cast<double>(sum) / kPatchPixels);
}

// Mean squared difference over pixels on side s1 in `a` and side s2 in `b` for every pairing
// (Algorithm 2, steps 8-10), minimum over the allowed pairings with enough overlap.
float SplitCost(const Patch& a, const Patch& b, bool like_sides_only, int min_overlap) {
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

float Cost(const Patch& a, const Patch& b, const PatchMatcherOptions& options) {
  if (!a.valid || !b.valid) return kInfinity;
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
  }
  return "?";
}

MatchCost ParseMatchCost(const std::string& name) {
  for (MatchCost cost :
       {MatchCost::kFullPatch, MatchCost::kSplitMinOfFourPairings, MatchCost::kSplitLikeSides}) {
    if (name == MatchCostName(cost)) return cost;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "unknown match cost '" + name + "' (valid: full, split, like-sides)");
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
}

std::vector<PatchMatch> ComputeCandidateCosts(const cv::Mat& gray1, const FeatureSet& features1,
                                              const cv::Mat& gray2, const FeatureSet& features2,
                                              const PatchMatcherOptions& options,
                                              const SearchRegions& search) {
  options.Check();
  CheckImage(gray1, "image 1");
  CheckImage(gray2, "image 2");
  COMIC_CHECK(search.centres.empty() || search.centres.size() == features1.size(), kInvalidArgument,
              "patch matcher: " << search.centres.size() << " search centres for "
                                << features1.size() << " features");
  COMIC_CHECK(search.radii.empty() || search.radii.size() == features1.size(), kInvalidArgument,
              "patch matcher: " << search.radii.size() << " search radii for " << features1.size()
                                << " features");
  std::vector<Patch> patches2(features2.size());
  for (size_t j = 0; j < features2.size(); ++j) patches2[j] = ExtractPatch(gray2, features2[j]);
  const double cell = options.gate == CandidateGate::kRadius
                          ? std::max(8.0, options.radius)
                          : std::max(8.0, options.max_disparity - options.min_disparity);
  const FeatureGrid grid(features2, cell);

  std::vector<PatchMatch> candidates;
  for (int i = 0; i < static_cast<int>(features1.size()); ++i) {
    const Patch patch1 = ExtractPatch(gray1, features1[i]);
    if (!patch1.valid) continue;
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
      const float cost = Cost(patch1, patches2[j], options);
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

float PatchCost(const cv::Mat& gray1, const Feature& feature1, const cv::Mat& gray2,
                const Feature& feature2, const PatchMatcherOptions& options) {
  options.Check();
  CheckImage(gray1, "image 1");
  CheckImage(gray2, "image 2");
  return Cost(ExtractPatch(gray1, feature1), ExtractPatch(gray2, feature2), options);
}

}  // namespace comic::frontend
