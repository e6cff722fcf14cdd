#include "frontend/comic/initial_corners.h"

#include <algorithm>
#include <cmath>

#include "frontend/comic/curve_cornerness.h"
#include "frontend/comic/iso_curve_stability.h"
#include "io/core/error.h"

namespace comic::frontend {

void InitialCornerOptions::Check() const {
  COMIC_CHECK(delta > 0, kInvalidArgument, "initial corners: delta must be > 0");
  COMIC_CHECK(half_length >= 2, kInvalidArgument, "initial corners: half_length must be >= 2");
  COMIC_CHECK(sigma > 0, kInvalidArgument, "initial corners: sigma must be > 0");
  COMIC_CHECK(min_cornerness >= 0, kInvalidArgument,
              "initial corners: min_cornerness must be >= 0");
  COMIC_CHECK(min_stability >= 0, kInvalidArgument, "initial corners: min_stability must be >= 0");
}

std::vector<int> BlockOrigins(int size, int block, int stride) {
  std::vector<int> origins;
  if (size < block || block <= 0 || stride <= 0) return origins;
  for (int origin = 0; origin + block <= size; origin += stride) origins.push_back(origin);
  if (origins.back() + block < size) origins.push_back(size - block);
  return origins;
}

std::pair<int, int> OwnedRange(const std::vector<int>& origins, int block, int index, int size) {
  const int count = static_cast<int>(origins.size());
  // Twice the centre of block i is 2 * origins[i] + block; midpoints between centres as bounds.
  const int begin = index == 0 ? 0 : (origins[index - 1] + origins[index] + block + 1) / 2;
  const int end = index + 1 == count ? size : (origins[index] + origins[index + 1] + block + 1) / 2;
  return {begin, end};
}

void InitialCornerDetector::DetectInBlock(const cv::Mat& image, const cv::Rect& block,
                                          const cv::Rect& owned, bool upper_sets,
                                          const InitialCornerOptions& options,
                                          std::vector<InitialCorner>* corners) {
  options.Check();
  tree_.Build(image(block), upper_sets);
  const int k = options.half_length;
  // A segment of 2k + 1 samples needs a boundary at least that long. Along a lineage, maxima
  // closer than the band half-width are the same curve seen at nearly the same level: keep the
  // best within that radius (one seed curve is enough; the convergence stage re-selects the level
  // at scale s).
  const int level_radius = std::max(1, static_cast<int>(std::ceil(options.delta)));
  const std::vector<StableComponent> stable = FindMaximallyStableComponents(
      tree_, options.delta, 2 * k + 1, options.min_stability, level_radius);
  if (stable.empty()) return;

  const int padded_size = tree_.Stride() * (tree_.height() + 2);
  if (static_cast<int>(edge_stamp_.size()) < 2 * padded_size) edge_stamp_.resize(2 * padded_size);
  std::fill(edge_stamp_.begin(), edge_stamp_.begin() + 2 * padded_size, 0);
  if (static_cast<int>(stable_index_.size()) < padded_size) stable_index_.resize(padded_size, -1);
  for (int i = 0; i < static_cast<int>(stable.size()); ++i) stable_index_[stable[i].node] = i;
  // The walk below visits only stable nodes: from the root down (reverse processing order), each
  // node's nearest stable ancestor-or-self.
  if (static_cast<int>(stable_up_.size()) < padded_size) stable_up_.resize(padded_size);
  {
    const std::vector<int>& nodes = tree_.Nodes();
    for (auto it = nodes.rbegin(); it != nodes.rend(); ++it) {
      const int parent = tree_.Parent(*it);
      stable_up_[*it] = stable_index_[*it] >= 0 ? *it : (parent < 0 ? -1 : stable_up_[parent]);
    }
  }

  // Seeds: the crossings of each component's level in the owned part whose inside pixel belongs
  // to the component. One pass over the owned 4-neighbour pairs: a pair with values a < b is
  // crossed by the curves of the levels a..b-1, and at level L its inside pixel belongs to the
  // ancestor of the inside pixel's node that spans L; so the components it seeds are the stable
  // ancestors whose chosen level is below b. Listed per component in raster order (the order a
  // scan of the owned part per component would visit them).
  seeds_.clear();
  for (int y = owned.y; y < owned.y + owned.height; ++y) {
    for (int x = owned.x; x < owned.x + owned.width; ++x) {
      const int p = tree_.PixelIndex(x - block.x, y - block.y);
      for (int direction = 0; direction < 2; ++direction) {
        const int q = p + (direction == 0 ? 1 : tree_.Stride());
        if (!tree_.InBlock(q) || tree_.Value(p) == tree_.Value(q)) continue;
        const int in = tree_.Value(p) < tree_.Value(q) ? p : q;
        const int out_value = tree_.Value(p) < tree_.Value(q) ? tree_.Value(q) : tree_.Value(p);
        // Levels grow towards the root, so skipping the unstable nodes on the way up visits the
        // same stable ones.
        for (int node = stable_up_[tree_.NodeOfPixel(in)];
             node >= 0 && tree_.Level(node) < out_value;) {
          const int index = stable_index_[node];
          if (stable[index].level < out_value) seeds_.push_back({index, 2 * p + direction});
          const int parent = tree_.Parent(node);
          node = parent < 0 ? -1 : stable_up_[parent];
        }
      }
    }
  }
  for (const StableComponent& component : stable) stable_index_[component.node] = -1;
  // Stable sort by component (counting sort), keeping the raster order within each.
  seed_start_.assign(stable.size() + 1, 0);
  for (const auto& [index, edge] : seeds_) ++seed_start_[index + 1];
  for (size_t i = 0; i < stable.size(); ++i) seed_start_[i + 1] += seed_start_[i];
  sorted_seeds_.resize(seeds_.size());
  {
    std::vector<int>& fill = seed_fill_;
    fill.assign(seed_start_.begin(), seed_start_.end() - 1);
    for (const auto& [index, edge] : seeds_) sorted_seeds_[fill[index]++] = edge;
  }

  int stamp = 0;
  const int max_points = 8 * (block.width + block.height);
  for (int c = 0; c < static_cast<int>(stable.size()); ++c) {
    const StableComponent& component = stable[c];
    ++stamp;  // visited marks per (pixel, right/down) edge, per traced component
    // In the tree's values the component is {value <= level}. In the image's grey values its
    // curve is at 254.5 - level for upper sets (the component is {v >= 255 - level}).
    const int level = component.level;
    const IsoCurveTracer tracer(image, block, upper_sets ? 254.5 - level : level + 0.5);
    const CornerContext context{&owned, upper_sets ? 254 - level : level, component.stability,
                                &options};
    // Each curve is traced once, from the first of its crossings in the list.
    for (int i = seed_start_[c]; i < seed_start_[c + 1]; ++i) {
      const int p = sorted_seeds_[i] / 2;
      const int q = p + (sorted_seeds_[i] % 2 == 0 ? 1 : tree_.Stride());
      if (edge_stamp_[sorted_seeds_[i]] == stamp) continue;
      const bool p_in = tree_.Value(p) <= level;
      const int in = p_in ? p : q;
      const int out = p_in ? q : p;
      const cv::Point in_pixel(tree_.PixelX(in) + block.x, tree_.PixelY(in) + block.y);
      const cv::Point out_pixel(tree_.PixelX(out) + block.x, tree_.PixelY(out) + block.y);
      // The tracer's inside is the dark side: the component for lower sets, its complement for
      // upper sets.
      tracer.Trace(upper_sets ? CurveEdge{out_pixel, in_pixel} : CurveEdge{in_pixel, out_pixel},
                   max_points, &curve_);
      for (const CurveEdge& edge : curve_.edges) {
        const cv::Point a = edge.inside - block.tl();
        const cv::Point b = edge.outside - block.tl();
        edge_stamp_[2 * tree_.PixelIndex(std::min(a.x, b.x), std::min(a.y, b.y)) +
                    (a.y == b.y ? 0 : 1)] = stamp;
      }
      AddCornersOfCurve(context, corners);
    }
  }
}

void InitialCornerDetector::AddCornersOfCurve(const CornerContext& context,
                                              std::vector<InitialCorner>* corners) {
  const InitialCornerOptions& options = *context.options;
  const cv::Rect& owned = *context.owned;
  const int k = options.half_length;
  if (static_cast<int>(curve_.points.size()) < 2 * k + 1) return;
  // A closed curve must be long enough for a segment to be a proper part of it (at most half):
  // on a small loop κ is near its maximum everywhere and the corner is arbitrary.
  PolylineArcLengths(curve_.points, curve_.closed, &arc_lengths_);
  const double length = arc_lengths_.back();
  if (curve_.closed && length < 4 * k + 1) return;
  int origin_index = 0;
  samples_ = ResamplePolyline(curve_.points, arc_lengths_, curve_.closed, 1.0, 0.0, 0,
                              static_cast<int>(length) + 1, &origin_index);
  const int n = static_cast<int>(samples_.size());
  if (n < 2 * k + 1) return;
  auto in_owned = [&](const cv::Point2f& p) {
    return owned.contains(cv::Point(static_cast<int>(std::floor(p.x + 0.5f)),
                                    static_cast<int>(std::floor(p.y + 0.5f))));
  };
  // κ only around the owned part (all of a closed curve): the samples there plus the support of
  // the filter and of the non-maximum suppression.
  const int nms_radius = std::max(1, static_cast<int>(std::lround(options.sigma)));
  const int filter_support = 3 * BoxRadiusForGaussian(options.sigma);
  int first = 0;
  int last = n - 1;
  if (!curve_.closed) {
    first = n;
    last = -1;
    for (int j = 0; j < n; ++j) {
      if (!in_owned(samples_[j])) continue;
      first = std::min(first, j);
      last = std::max(last, j);
    }
    if (last < 0) return;
    first = std::max(0, first - filter_support - nms_radius - 1);
    last = std::min(n - 1, last + filter_support + nms_radius + 1);
  }
  part_.assign(samples_.begin() + first, samples_.begin() + last + 1);
  std::vector<double>& part_kappa = part_kappa_;
  CurveCornerness(part_, curve_.closed, options.sigma, 0, &cornerness_, &part_kappa);
  kappa_.assign(n, -1.0);
  for (int j = first; j <= last; ++j) {
    // κ counts only where the segment is complete on the whole curve and the filter saw its full
    // support within the part.
    const bool complete = curve_.closed || (j >= k && j <= n - 1 - k);
    const bool supported = curve_.closed || ((j - first >= filter_support || first == 0) &&
                                             (last - j >= filter_support || last == n - 1));
    if (complete && supported) kappa_[j] = part_kappa[j - first];
  }
  CurveCornerOptions corner_options;
  corner_options.arm_end = k;
  for (int index : CornernessMaxima(kappa_, curve_.closed, nms_radius, options.min_cornerness)) {
    const CurveCorner corner =
        RefineCurveCorner(samples_, curve_.closed, kappa_, index, corner_options);
    if (!in_owned(corner.apex)) continue;
    InitialCorner initial;
    initial.position = corner.apex;
    initial.level = context.grey_level;
    initial.polarity = corner.polarity;
    initial.stability = static_cast<float>(context.stability);
    initial.cornerness = static_cast<float>(corner.cornerness);
    // Closed curves shorter than the reach would repeat samples.
    const int reach = curve_.closed ? std::min(2 * k, (n - 1) / 2) : 2 * k;
    for (int j = index - reach; j <= index + reach; ++j) {
      if (!curve_.closed && (j < 0 || j >= n)) continue;
      if (j == index) initial.corner_index = static_cast<int>(initial.curve.size());
      initial.curve.push_back(samples_[((j % n) + n) % n]);
    }
    corners->push_back(std::move(initial));
  }
}

}  // namespace comic::frontend
