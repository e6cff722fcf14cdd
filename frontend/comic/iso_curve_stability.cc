#include "frontend/comic/iso_curve_stability.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace comic::frontend {

int UpLevel(double threshold, double delta) {
  return static_cast<int>(std::ceil(threshold + delta)) - 1;
}

int DownLevel(double threshold, double delta) {
  return static_cast<int>(std::ceil(threshold - delta)) - 1;
}

// ---------------------------------------------------------------------------------------------
// Initialisation stage.

namespace {

// The same rules on ComponentTree (per block) and ImageComponentTree (the whole image).
template <class Tree>
double StabilityOf(const Tree& tree, int node, int level, double delta) {
  const double threshold = level + 0.5;
  const int up = tree.Area(tree.AncestorAtLevel(node, UpLevel(threshold, delta)));
  const int down = tree.MainDescendantArea(node, DownLevel(threshold, delta));
  return tree.Perimeter(node) / static_cast<double>(std::max(1, up - down));
}

template <class Tree>
std::vector<StableComponent> MaximallyStableComponents(const Tree& tree, double delta,
                                                       int min_perimeter, double min_stability,
                                                       int level_radius) {
  std::vector<StableComponent> result;
  const int root = tree.Root();
  for (int node : tree.Nodes()) {
    if (node == root || tree.Perimeter(node) < min_perimeter) continue;
    const int first = tree.Level(node);
    const int last = tree.Level(tree.Parent(node)) - 1;
    // Best ρ over the span, and the run of levels attaining it.
    double best = -1.0;
    int run_begin = first;
    int run_end = first;
    bool in_run = false;
    for (int level = first; level <= last; ++level) {
      const double rho = StabilityOf(tree, node, level, delta);
      if (rho > best) {
        best = rho;
        run_begin = run_end = level;
        in_run = true;
      } else if (rho == best && in_run) {
        run_end = level;
      } else {
        in_run = false;
      }
    }
    if (best < min_stability) continue;
    // Local maximum along the lineage: compare with the levels beyond the span that are within
    // level_radius of the best run.
    bool is_max = true;
    for (int level = first - 1; is_max && level >= run_begin - level_radius; --level) {
      const int below = tree.MainDescendantAtLevel(node, level);
      if (below < 0) break;
      is_max = best > StabilityOf(tree, below, level, delta);
    }
    for (int level = last + 1; is_max && level <= run_end + level_radius && level <= 255; ++level) {
      const int above = tree.AncestorAtLevel(node, level);
      if (above == root) break;
      is_max = best >= StabilityOf(tree, above, level, delta);
    }
    if (!is_max) continue;
    result.push_back({node, (run_begin + run_end) / 2, best});
  }
  return result;
}

}  // namespace

double ComponentStability(const ComponentTree& tree, int node, int level, double delta) {
  return StabilityOf(tree, node, level, delta);
}

double ComponentStability(const ImageComponentTree& tree, int node, int level, double delta) {
  return StabilityOf(tree, node, level, delta);
}

std::vector<StableComponent> FindMaximallyStableComponents(const ComponentTree& tree, double delta,
                                                           int min_perimeter, double min_stability,
                                                           int level_radius) {
  return MaximallyStableComponents(tree, delta, min_perimeter, min_stability, level_radius);
}

std::vector<StableComponent> FindMaximallyStableComponents(const ImageComponentTree& tree,
                                                           double delta, int min_perimeter,
                                                           double min_stability, int level_radius) {
  return MaximallyStableComponents(tree, delta, min_perimeter, min_stability, level_radius);
}

// ---------------------------------------------------------------------------------------------
// Convergence stage.

namespace {

// Interpolation of an 8-bit image (border replicated) for the normal profiles: cubic convolution
// (Catmull-Rom, Keys a = -0.5) near the curve, bilinear beyond. Bilinear interpolation across a
// sharp edge is linear between the two pixels straddling it (a flat gradient, hence a flat ρ over
// many levels); the cubic has a continuous gradient with a maximum near the edge, so the most
// stable level is well defined. Far from the curve only the toes of the edge are sampled, which
// decide the weak levels only, and the cheaper bilinear interpolation is enough there.
class ProfileSampler {
 public:
  explicit ProfileSampler(const cv::Mat& gray) : gray_(gray) {}

  float Cubic(double x, double y) const {
    const int x0 = FloorToInt(x);
    const int y0 = FloorToInt(y);
    float wx[4], wy[4];
    CubicWeights(static_cast<float>(x - x0), wx);
    CubicWeights(static_cast<float>(y - y0), wy);
    if (x0 >= 1 && y0 >= 1 && x0 + 2 < gray_.cols && y0 + 2 < gray_.rows) {
      const uint8_t* row = gray_.ptr<uint8_t>(y0 - 1) + (x0 - 1);
      return Convolve4x4(row, gray_.step[0], wx, wy);
    }
    float sum = 0.0f;
    for (int j = 0; j < 4; ++j) {
      const uint8_t* row = gray_.ptr<uint8_t>(std::clamp(y0 - 1 + j, 0, gray_.rows - 1));
      float line = 0.0f;
      for (int i = 0; i < 4; ++i) line += wx[i] * row[std::clamp(x0 - 1 + i, 0, gray_.cols - 1)];
      sum += wy[j] * line;
    }
    return sum;
  }

  float Bilinear(double x, double y) const {
    if (x >= 0.0 && y >= 0.0 && x < gray_.cols - 1.0 && y < gray_.rows - 1.0) {
      // Inside: the clamps below change nothing and (x0, y0) + 1 is in the image.
      const int x0 = static_cast<int>(x);
      const int y0 = static_cast<int>(y);
      const float tx = static_cast<float>(x - x0);
      const float ty = static_cast<float>(y - y0);
      const uint8_t* r0 = gray_.ptr<uint8_t>(y0) + x0;
      const uint8_t* r1 = r0 + gray_.step[0];
      const float top = r0[0] + tx * (r0[1] - r0[0]);
      const float bottom = r1[0] + tx * (r1[1] - r1[0]);
      return top + ty * (bottom - top);
    }
    x = std::clamp(x, 0.0, gray_.cols - 1.0);
    y = std::clamp(y, 0.0, gray_.rows - 1.0);
    const int x0 = std::min(static_cast<int>(x), std::max(0, gray_.cols - 2));
    const int y0 = std::min(static_cast<int>(y), std::max(0, gray_.rows - 2));
    const int x1 = std::min(x0 + 1, gray_.cols - 1);
    const int y1 = std::min(y0 + 1, gray_.rows - 1);
    const float tx = static_cast<float>(x - x0);
    const float ty = static_cast<float>(y - y0);
    const uint8_t* r0 = gray_.ptr<uint8_t>(y0);
    const uint8_t* r1 = gray_.ptr<uint8_t>(y1);
    const float top = r0[x0] + tx * (r0[x1] - r0[x0]);
    const float bottom = r1[x0] + tx * (r1[x1] - r1[x0]);
    return top + ty * (bottom - top);
  }

 private:
  // floor for the coordinates of a profile (well inside the int range): a truncation corrected
  // for negatives, cheaper than std::floor without SSE4.1.
  static int FloorToInt(double v) {
    const int i = static_cast<int>(v);
    return i - (v < i ? 1 : 0);
  }

  // Σ_j wy[j] (Σ_i wx[i] row_j[i]) over a 4 x 4 window, each sum accumulated in the order
  // written (i, then j, from 0): with SSE2 the four rows run in the four lanes, which performs
  // the same float operations in the same order, so both paths give the same bits.
  static float Convolve4x4(const uint8_t* row, size_t step, const float* wx, const float* wy) {
#if defined(__SSE2__)
    auto load4 = [](const uint8_t* p) {
      int32_t v;
      std::memcpy(&v, p, sizeof(v));
      return _mm_cvtsi32_si128(v);
    };
    // Bytes of the four rows interleaved column by column: r0[i] r1[i] r2[i] r3[i] for i = 0..3.
    const __m128i r01 = _mm_unpacklo_epi8(load4(row), load4(row + step));
    const __m128i r23 = _mm_unpacklo_epi8(load4(row + 2 * step), load4(row + 3 * step));
    const __m128i columns = _mm_unpacklo_epi16(r01, r23);
    const __m128i zero = _mm_setzero_si128();
    const __m128i low = _mm_unpacklo_epi8(columns, zero);   // columns 0, 1 as 16-bit
    const __m128i high = _mm_unpackhi_epi8(columns, zero);  // columns 2, 3
    const __m128 c0 = _mm_cvtepi32_ps(_mm_unpacklo_epi16(low, zero));
    const __m128 c1 = _mm_cvtepi32_ps(_mm_unpackhi_epi16(low, zero));
    const __m128 c2 = _mm_cvtepi32_ps(_mm_unpacklo_epi16(high, zero));
    const __m128 c3 = _mm_cvtepi32_ps(_mm_unpackhi_epi16(high, zero));
    __m128 line =
        _mm_add_ps(_mm_mul_ps(_mm_set1_ps(wx[0]), c0), _mm_mul_ps(_mm_set1_ps(wx[1]), c1));
    line = _mm_add_ps(line, _mm_mul_ps(_mm_set1_ps(wx[2]), c2));
    line = _mm_add_ps(line, _mm_mul_ps(_mm_set1_ps(wx[3]), c3));
    alignas(16) float terms[4];
    _mm_store_ps(terms, _mm_mul_ps(_mm_loadu_ps(wy), line));
    return ((terms[0] + terms[1]) + terms[2]) + terms[3];
#else
    float sum = 0.0f;
    for (int j = 0; j < 4; ++j, row += step) {
      sum += wy[j] * (wx[0] * row[0] + wx[1] * row[1] + wx[2] * row[2] + wx[3] * row[3]);
    }
    return sum;
#endif
  }

  static void CubicWeights(float t, float* w) {
    const float t2 = t * t, t3 = t2 * t;
    w[0] = -0.5f * t3 + t2 - 0.5f * t;
    w[1] = 1.5f * t3 - 2.5f * t2 + 1.0f;
    w[2] = -1.5f * t3 + 2.0f * t2 + 0.5f * t;
    w[3] = 0.5f * t3 - 0.5f * t2;
  }
  const cv::Mat& gray_;
};

constexpr float kNotSampled = -1.0f;

// Crossings of the thresholds first_threshold + j (j = 0..count-1, ascending) along one normal
// profile f[k] at u_k = (k - m) * step, searched outwards from the centre sample m: for a
// threshold above f[m] the first k > m with f[k] >= T, for one at or below it the first k < m with
// f[k] < T, interpolated linearly. Not found: +-m * step and `clipped` set. Samples are taken
// on demand (`sample(k)` fills f[k]), so a steep profile is read only near its centre.
template <class Sample>
void ProfileCrossings(float* f, int size, int m, double step, double first_threshold, int count,
                      const Sample& sample, double* crossing, uint8_t* clipped) {
  auto at = [&](int k) {
    if (f[k] == kNotSampled) f[k] = sample(k);
    return static_cast<double>(f[k]);
  };
  const double centre = at(m);
  const int last = size - 1;
  // Thresholds first_threshold + j <= centre are those with j < split (the difference of a float
  // and a half-integer of grey-level range is exact in double, so the floor decides exactly).
  const int split = static_cast<int>(
      std::clamp(std::floor(centre - first_threshold) + 1.0, 0.0, static_cast<double>(count)));
  // Thresholds above the centre value, ascending: walk outwards.
  int k = m + 1;
  for (int j = split; j < count; ++j) {
    const double t = first_threshold + j;
    while (k <= last && at(k) < t) ++k;
    if (k > last) {
      crossing[j] = (last - m) * step;
      clipped[j] = 1;
    } else {
      crossing[j] = ((k - 1 - m) + (t - f[k - 1]) / (f[k] - f[k - 1])) * step;
      clipped[j] = 0;
    }
  }
  // Thresholds at or below the centre value, descending: walk inwards.
  k = m - 1;
  for (int j = split - 1; j >= 0; --j) {
    const double t = first_threshold + j;
    while (k >= 0 && at(k) >= t) --k;
    if (k < 0) {
      crossing[j] = -m * step;
      clipped[j] = 1;
    } else {
      crossing[j] = ((k - m) + (t - f[k]) / (f[k + 1] - f[k])) * step;
      clipped[j] = 0;
    }
  }
}

// The selection rule of SelectMaximallyStableLevel on ρ_w given level by level: rho(l) for
// l in [0, count). Reads only the levels it needs, in an order that does not change the result.
template <class Rho>
bool SelectLevel(int first_level, int count, double middle_level, double previous_level,
                 double run_tolerance, double ripple_tolerance, Rho&& rho, StableLevel* selected) {
  auto is_max = [&](int l) {
    return l >= 1 && l + 1 < count && rho(l) > rho(l - 1) && rho(l) >= rho(l + 1);
  };
  // The maximum nearest in level to the previous MSICS (ties: larger ρ, then lower level),
  // searched outwards from previous_level.
  auto distance = [&](int l) { return std::abs(first_level + l - previous_level); };
  const double x0 = previous_level - first_level;
  const int start = static_cast<int>(std::floor(std::clamp(x0, -1.0, count + 1.0)));
  int below = std::min(start, count - 2);  // candidates below, walking down
  int above = std::max(start + 1, 1);      // candidates above, walking up
  int current = -1;
  while (current < 0 && (below >= 1 || above <= count - 2)) {
    const bool has_below = below >= 1;
    const bool has_above = above <= count - 2;
    const double d_below = has_below ? distance(below) : std::numeric_limits<double>::infinity();
    const double d_above = has_above ? distance(above) : std::numeric_limits<double>::infinity();
    const bool try_below = has_below && d_below <= d_above;
    const bool try_above = has_above && d_above <= d_below;
    const bool max_below = try_below && is_max(below);
    const bool max_above = try_above && is_max(above);
    if (max_below && max_above) {
      current = rho(above) > rho(below) ? above : below;
    } else if (max_below) {
      current = below;
    } else if (max_above) {
      current = above;
    }
    if (try_below) --below;
    if (try_above) ++above;
  }
  if (current < 0) return false;
  // Ripples are not separate curves: climb to a higher neighbouring maximum while the dip between
  // is shallower than ripple_tolerance (relative to the lower of the two), as MSER ignores
  // insignificant extrema. Between two distinct curves ρ drops by most of its value. Towards each
  // side, the walk to the neighbouring maximum stops as soon as the dip is too deep to climb.
  for (;;) {
    const double floor = (1.0 - ripple_tolerance) * rho(current);
    int next = -1;
    for (int direction : {-1, 1}) {
      double dip = std::numeric_limits<double>::infinity();
      int other = -1;
      for (int j = current + direction; j >= 1 && j + 1 < count; j += direction) {
        if (is_max(j)) {
          other = j;
          break;
        }
        dip = std::min(dip, rho(j));
        if (dip < floor) break;
      }
      if (other < 0 || rho(other) <= rho(current) || dip < floor) continue;
      if (next < 0 || rho(other) > rho(next)) next = other;
    }
    if (next < 0) break;
    current = next;
  }
  const int best = current;
  // The run of levels around the peak whose ρ is within the tolerance of it. On a sharp edge ρ is
  // nearly flat over most of the edge's range (the band keeps its width while it moves across the
  // edge), so the exact maximum would be decided by ripples and by the corner's geometry.
  const double floor = (1.0 - run_tolerance) * rho(best);
  int run_begin = best;
  int run_end = best;
  while (run_begin > 0 && rho(run_begin - 1) >= floor) --run_begin;
  while (run_end + 1 < count && rho(run_end + 1) >= floor) ++run_end;
  // Every level of the run is as stable as the peak within the tolerance: take the one in the
  // middle of the intensities on the two sides of the curve (for a blurred step edge, the level
  // line through the edge itself), which depends only on the image.
  double centre = std::clamp(middle_level - first_level, static_cast<double>(run_begin),
                             static_cast<double>(run_end));
  double peak = rho(best);
  if (run_begin == run_end) {
    // A sharp maximum: refine it below one level with a parabola through its neighbours.
    const double a = rho(best - 1);
    const double b = rho(best);
    const double c = rho(best + 1);
    const double curvature = a - 2.0 * b + c;
    if (curvature < 0) {
      const double offset = std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
      centre = best + offset;
      peak = b - 0.25 * (a - c) * offset;
    }
  }
  selected->threshold = first_level + centre + 0.5;
  selected->level = static_cast<int>(std::ceil(selected->threshold)) - 1;
  selected->stability = peak;
  return true;
}

}  // namespace

float InterpolateProfileCubic(const cv::Mat& gray, double x, double y) {
  return ProfileSampler(gray).Cubic(x, y);
}

float InterpolateProfileBilinear(const cv::Mat& gray, double x, double y) {
  return ProfileSampler(gray).Bilinear(x, y);
}

inline float WeightedStabilityEvaluator::Sample(int r, int k) {
  const float value = samples_[static_cast<size_t>(r) * (2 * m_ + 1) + k];
  return value == kNotSampled ? ReadSample(r, k) : value;
}

double WeightedStabilityEvaluator::Weight(int offset, double sigma) {
  // The Gaussian of one offset, memoised per σ (the same expression, so the same value).
  if (!(sigma == weight_sigma_)) {
    weight_sigma_ = sigma;
    weight_table_.clear();
  }
  const size_t index = static_cast<size_t>(offset < 0 ? -2 * offset - 1 : 2 * offset);
  if (index >= weight_table_.size()) weight_table_.resize(index + 1, -1.0);
  double& weight = weight_table_[index];
  if (weight < 0) {
    const double d = offset;
    weight = std::exp(-d * d / (2.0 * sigma * sigma));
  }
  return weight;
}

inline float WeightedStabilityEvaluator::ReadSample(int r, int k) {
  // Interpolation of the 8-bit image: cubic near the curve, bilinear beyond (ProfileSampler).
  const ProfileSampler interpolate(*gray_);
  const double u = (k - m_) * options_.sample_step;
  const double x = points_[r].x + u * normals_[r].x, y = points_[r].y + u * normals_[r].y;
  const float value =
      std::abs(k - m_) <= cubic_reach_ ? interpolate.Cubic(x, y) : interpolate.Bilinear(x, y);
  samples_[static_cast<size_t>(r) * (2 * m_ + 1) + k] = value;
  return value;
}

bool WeightedStabilityEvaluator::Prepare(const cv::Mat& gray,
                                         const std::vector<cv::Point2f>& reference,
                                         int centre_index,
                                         const WeightedStabilityOptions& options) {
  return PrepareImpl(gray, reference, centre_index, options, true);
}

bool WeightedStabilityEvaluator::PrepareWithoutMiddleLevel(
    const cv::Mat& gray, const std::vector<cv::Point2f>& reference, int centre_index,
    const WeightedStabilityOptions& options) {
  return PrepareImpl(gray, reference, centre_index, options, false);
}

bool WeightedStabilityEvaluator::PrepareImpl(const cv::Mat& gray,
                                             const std::vector<cv::Point2f>& reference,
                                             int centre_index,
                                             const WeightedStabilityOptions& options,
                                             bool with_middle_level) {
  gray_ = &gray;
  options_ = options;
  num_evaluated_ = 0;
  const int n = static_cast<int>(reference.size());
  if (centre_index < 1 || centre_index > n - 2) return false;
  // Normals every normal_step samples within half_length of the centre, the centre included.
  const int normal_step = std::max(1, options.normal_step);
  const int reach_before = std::min(centre_index, options.half_length) / normal_step;
  const int reach_after = std::min(n - 1 - centre_index, options.half_length) / normal_step;
  num_normals_ = reach_before + reach_after + 1;
  centre_row_ = reach_before;
  m_ = std::max(1, static_cast<int>(std::lround(options.max_distance / options.sample_step)));
  const double step = options.sample_step;
  cubic_reach_ = static_cast<int>(std::floor(options.cubic_distance / step + 1e-9));

  // Unit normals towards the bright side (the right of the direction of travel), and weights.
  points_.resize(num_normals_);
  normals_.resize(num_normals_);
  weights_.resize(num_normals_);
  weight_sum_ = 0;
  for (int r = 0; r < num_normals_; ++r) {
    const int i = centre_index + (r - centre_row_) * normal_step;
    const cv::Point2d tangent =
        cv::Point2d(reference[std::min(n - 1, i + 1)]) - cv::Point2d(reference[std::max(0, i - 1)]);
    const double norm = std::sqrt(tangent.x * tangent.x + tangent.y * tangent.y);
    points_[r] = reference[i];
    normals_[r] = norm > 0 ? cv::Point2d(-tangent.y / norm, tangent.x / norm) : cv::Point2d(0, 0);
    weights_[r] = Weight(i - centre_index, options.sigma);
    weight_sum_ += weights_[r];
  }

  // Intensity profiles along the normals (row r: samples k = 0..2m at u = (k - m) * step), read
  // on demand.
  const int samples = 2 * m_ + 1;
  samples_.assign(static_cast<size_t>(num_normals_) * samples, kNotSampled);

  // The intensities on the two sides of the curve: per normal, the darkest value on the dark
  // half and the brightest on the bright half within side_distance (extremes reach the flat sides
  // of a blurred edge whatever the reference curve's level), and across normals the weighted
  // median of their mid-points, robust to texture and to the few normals that cross to the far
  // side of a sharp tip. The central normal's values also give the candidate levels.
  const int side_reach = std::min(m_, static_cast<int>(std::lround(options.side_distance / step)));
  const int search_reach =
      std::min(m_, static_cast<int>(std::floor(options.search_radius / step + 1e-9)));
  const int read_reach = std::max(side_reach, search_reach);
  mids_.clear();
  for (int r = 0; r < num_normals_ && with_middle_level; ++r) {
    float dark = std::numeric_limits<float>::infinity();
    float bright = -dark;
    for (int k = m_ - read_reach; k <= m_ + read_reach; ++k) {
      const float v = Sample(r, k);
      if (k >= m_ - side_reach && k <= m_) dark = std::min(dark, v);
      if (k >= m_ && k <= m_ + side_reach) bright = std::max(bright, v);
    }
    mids_.emplace_back(0.5 * (dark + bright), weights_[r]);
  }
  middle_level_ = 0.0;
  if (with_middle_level) {
    std::sort(mids_.begin(), mids_.end());
    double cumulative = 0;
    double median = mids_.back().first;
    for (const auto& [mid, weight] : mids_) {
      cumulative += weight;
      if (cumulative >= 0.5 * weight_sum_) {
        median = mid;
        break;
      }
    }
    middle_level_ = median - 0.5;
  }

  // Levels whose curve crosses the central normal within the search radius: J with
  // low < J + 0.5 <= high.
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (int k = m_ - search_reach; k <= m_ + search_reach; ++k) {
    low = std::min(low, static_cast<double>(Sample(centre_row_, k)));
    high = std::max(high, static_cast<double>(Sample(centre_row_, k)));
  }
  const int level_lo = static_cast<int>(std::ceil(low - 0.5 + 1e-9));
  const int level_hi = static_cast<int>(std::ceil(high - 0.5)) - 1;
  if (level_hi < level_lo) return false;
  first_level_ = level_lo - 1;
  num_levels_ = level_hi - level_lo + 3;
  // Crossings of the thresholds J + 0.5 + e, e in [-δ, δ] (δ rounded up; a fractional δ is
  // interpolated between them).
  delta_steps_ = static_cast<int>(std::ceil(options.delta));
  first_threshold_ = first_level_ - delta_steps_ + 0.5;
  num_thresholds_ = num_levels_ + 2 * delta_steps_;
  // Sized up only (every entry used is computed before it is read).
  const size_t crossings = static_cast<size_t>(num_normals_) * num_thresholds_;
  if (crossings_.size() < crossings) crossings_.resize(crossings);
  if (clipped_.size() < crossings) clipped_.resize(crossings);
  computed_begin_ = computed_end_ = 0;
  levels_.assign(num_levels_, LevelValues());
  elements_.resize(num_normals_);
  return true;
}

void WeightedStabilityEvaluator::ComputeCrossings(int j) {
  // A level asks for thresholds j - δ and j + δ (Evaluate), so windows of δ + 2 around each
  // cover its band and the neighbouring levels the choice looks at next; wider windows were
  // measured to compute mostly crossings that are never read.
  const int slack = delta_steps_ + 2;
  int begin = std::max(0, j - slack);
  int end = std::min(num_thresholds_, j + slack + 1);
  if (computed_end_ > computed_begin_) {
    begin = std::min(begin, computed_begin_);
    end = std::max(end, computed_end_);
  }
  const int samples = 2 * m_ + 1;
  // The new thresholds below and above the computed window. Each threshold's crossing depends on
  // the threshold alone (ProfileCrossings), so computing them in pieces gives the same values.
  for (const auto& [from, to] :
       {std::pair{begin, computed_end_ > computed_begin_ ? computed_begin_ : end},
        std::pair{computed_end_ > computed_begin_ ? computed_end_ : end, end}}) {
    if (to <= from) continue;
    for (int r = 0; r < num_normals_; ++r) {
      ProfileCrossings(
          &samples_[static_cast<size_t>(r) * samples], samples, m_, options_.sample_step,
          first_threshold_ + from, to - from, [&](int k) { return ReadSample(r, k); },
          &crossings_[static_cast<size_t>(r) * num_thresholds_ + from],
          &clipped_[static_cast<size_t>(r) * num_thresholds_ + from]);
    }
  }
  computed_begin_ = begin;
  computed_end_ = end;
}

double WeightedStabilityEvaluator::CentreOffset(int l) {
  bool clipped = false;
  return Crossing(centre_row_, l + delta_steps_, &clipped);
}

template <class CurveCrossing, class BandWidth>
void WeightedStabilityEvaluator::IntegrateBand(CurveCrossing curve_crossing, BandWidth band_width,
                                               LevelValues* values) {
  // Length element of the level's curve at each normal: half of each adjoining chord between
  // the points where the curve crosses consecutive normals (0 where it does not cross).
  std::fill(elements_.begin(), elements_.end(), 0.0);
  cv::Point2d previous;
  bool previous_valid = false;
  for (int r = 0; r < num_normals_; ++r) {
    bool valid = false;
    const double u = curve_crossing(r, &valid);
    const cv::Point2d q = points_[r] + u * normals_[r];
    if (valid && previous_valid) {
      const double dx = q.x - previous.x;
      const double dy = q.y - previous.y;
      const double chord = std::sqrt(dx * dx + dy * dy);
      elements_[r - 1] += 0.5 * chord;
      elements_[r] += 0.5 * chord;
    }
    previous = q;
    previous_valid = valid;
  }
  // The strip of normal r has the band's width there times the curve's length element: the
  // area between Up and Down in that strip.
  double length = 0;
  double band = 0;
  for (int r = 0; r < num_normals_; ++r) {
    length += weights_[r] * elements_[r];
    if (elements_[r] == 0.0) continue;  // adds exactly nothing; skips reading its band
    band += weights_[r] * elements_[r] * band_width(r);
  }
  band = std::max(band, 1e-6 * weight_sum_);
  values->band_area = band;
  values->length = length;
  values->stability = length / band;
}

const WeightedStabilityEvaluator::LevelValues& WeightedStabilityEvaluator::Evaluate(int l) {
  LevelValues& values = levels_[l];
  if (values.stability >= 0) return values;
  ++num_evaluated_;
  const int j = l + delta_steps_;  // threshold index of the level itself
  const double delta = options_.delta;
  const bool whole_delta = delta == delta_steps_;
  // The level reads the thresholds j - δ .. j + δ (a fractional δ interpolates between whole
  // ones inside that range): make sure their crossings are computed, then read them directly.
  for (const int needed : {j - delta_steps_, j + delta_steps_}) {
    if (needed < computed_begin_ || needed >= computed_end_) ComputeCrossings(needed);
  }
  const int stride = num_thresholds_;
  auto u_at = [&](int r, double jj) {  // crossing of threshold index jj (may be fractional)
    const double* row = &crossings_[static_cast<size_t>(r) * stride];
    if (whole_delta) return row[static_cast<int>(jj)];
    const int j0 = std::clamp(static_cast<int>(std::floor(jj)), 0, num_thresholds_ - 1);
    const int j1 = std::min(j0 + 1, num_thresholds_ - 1);
    const double t = std::clamp(jj - j0, 0.0, 1.0);
    const double u0 = row[j0];
    const double u1 = row[j1];
    return u0 + t * (u1 - u0);
  };
  IntegrateBand(
      [&](int r, bool* valid) {
        const size_t index = static_cast<size_t>(r) * stride + j;
        *valid = clipped_[index] == 0;
        return crossings_[index];
      },
      [&](int r) { return u_at(r, j + delta) - u_at(r, j - delta); }, &values);
  return values;
}

double WeightedStabilityEvaluator::SingleLevelStability(int l) {
  LevelValues& values = levels_[l];
  if (values.stability >= 0) return values.stability;
  if (options_.delta != delta_steps_) return Evaluate(l).stability;  // fractional δ: windows
  ++num_evaluated_;
  // The three thresholds' crossings on every normal, each found on its own (a threshold's
  // crossing depends on the threshold alone, ProfileCrossings), so the values are those Evaluate
  // reads from its windows. Row 0: the level's curve; 1: Down (j - δ); 2: Up (j + δ).
  const int j = l + delta_steps_;
  const int samples = 2 * m_ + 1;
  const size_t n = static_cast<size_t>(num_normals_);
  single_crossings_.resize(3 * n);
  single_clipped_.resize(3 * n);
  const int thresholds[3] = {j, j - delta_steps_, j + delta_steps_};
  for (int t = 0; t < 3; ++t) {
    for (int r = 0; r < num_normals_; ++r) {
      ProfileCrossings(
          &samples_[static_cast<size_t>(r) * samples], samples, m_, options_.sample_step,
          first_threshold_ + thresholds[t], 1, [&](int k) { return ReadSample(r, k); },
          &single_crossings_[t * n + r], &single_clipped_[t * n + r]);
    }
  }
  IntegrateBand(
      [&](int r, bool* valid) {
        *valid = single_clipped_[r] == 0;
        return single_crossings_[r];
      },
      [&](int r) { return single_crossings_[2 * n + r] - single_crossings_[n + r]; }, &values);
  return values.stability;
}

void WeightedStabilityEvaluator::Fill(StabilityProfile* profile) {
  profile->first_level = first_level_;
  profile->stability.assign(num_levels_, 0.0);
  profile->length.assign(num_levels_, 0.0);
  profile->band_area.assign(num_levels_, 0.0);
  profile->centre_offset.assign(num_levels_, 0.0);
  profile->centre = centre();
  profile->normal = normal();
  profile->middle_level = middle_level_;
  for (int l = 0; l < num_levels_; ++l) {
    const LevelValues& values = Evaluate(l);
    profile->stability[l] = values.stability;
    profile->length[l] = values.length;
    profile->band_area[l] = values.band_area;
    profile->centre_offset[l] = CentreOffset(l);
  }
}

bool ComputeWeightedStabilityProfile(const cv::Mat& gray, const std::vector<cv::Point2f>& reference,
                                     int centre_index, const WeightedStabilityOptions& options,
                                     StabilityProfile* profile) {
  WeightedStabilityEvaluator evaluator;
  if (!evaluator.Prepare(gray, reference, centre_index, options)) return false;
  evaluator.Fill(profile);
  return true;
}

bool SelectMaximallyStableLevel(const StabilityProfile& profile, double previous_level,
                                double run_tolerance, double ripple_tolerance,
                                StableLevel* selected) {
  const std::vector<double>& rho = profile.stability;
  return SelectLevel(
      profile.first_level, profile.NumLevels(), profile.middle_level, previous_level, run_tolerance,
      ripple_tolerance, [&](int l) { return rho[l]; }, selected);
}

bool SelectMaximallyStableLevel(WeightedStabilityEvaluator* evaluator, double previous_level,
                                double run_tolerance, double ripple_tolerance,
                                StableLevel* selected) {
  return SelectLevel(
      evaluator->first_level(), evaluator->NumLevels(), evaluator->middle_level(), previous_level,
      run_tolerance, ripple_tolerance, [&](int l) { return evaluator->Stability(l); }, selected);
}

}  // namespace comic::frontend
