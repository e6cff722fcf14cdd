#include "frontend/iso_curve_stability.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace comic::frontend {

int UpLevel(double threshold, double delta) {
  return static_cast<int>(std::ceil(threshold + delta)) - 1;
}

int DownLevel(double threshold, double delta) {
  return static_cast<int>(std::ceil(threshold - delta)) - 1;
}

// ---------------------------------------------------------------------------------------------
// Initialisation stage.

double ComponentStability(const ComponentTree& tree, int node, int level, double delta) {
  const double threshold = level + 0.5;
  const int up = tree.Area(tree.AncestorAtLevel(node, UpLevel(threshold, delta)));
  const int down = tree.MainDescendantArea(node, DownLevel(threshold, delta));
  return tree.Perimeter(node) / static_cast<double>(std::max(1, up - down));
}

std::vector<StableComponent> FindMaximallyStableComponents(const ComponentTree& tree, double delta,
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
      const double rho = ComponentStability(tree, node, level, delta);
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
      is_max = best > ComponentStability(tree, below, level, delta);
    }
    for (int level = last + 1; is_max && level <= run_end + level_radius && level <= 255; ++level) {
      const int above = tree.AncestorAtLevel(node, level);
      if (above == root) break;
      is_max = best >= ComponentStability(tree, above, level, delta);
    }
    if (!is_max) continue;
    result.push_back({node, (run_begin + run_end) / 2, best});
  }
  return result;
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
    const int x0 = static_cast<int>(std::floor(x));
    const int y0 = static_cast<int>(std::floor(y));
    float wx[4], wy[4];
    CubicWeights(static_cast<float>(x - x0), wx);
    CubicWeights(static_cast<float>(y - y0), wy);
    float sum = 0.0f;
    if (x0 >= 1 && y0 >= 1 && x0 + 2 < gray_.cols && y0 + 2 < gray_.rows) {
      const uint8_t* row = gray_.ptr<uint8_t>(y0 - 1) + (x0 - 1);
      for (int j = 0; j < 4; ++j, row += gray_.step[0]) {
        sum += wy[j] * (wx[0] * row[0] + wx[1] * row[1] + wx[2] * row[2] + wx[3] * row[3]);
      }
      return sum;
    }
    for (int j = 0; j < 4; ++j) {
      const uint8_t* row = gray_.ptr<uint8_t>(std::clamp(y0 - 1 + j, 0, gray_.rows - 1));
      float line = 0.0f;
      for (int i = 0; i < 4; ++i) line += wx[i] * row[std::clamp(x0 - 1 + i, 0, gray_.cols - 1)];
      sum += wy[j] * line;
    }
    return sum;
  }

  float Bilinear(double x, double y) const {
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
  // Thresholds above the centre value, ascending: walk outwards.
  int k = m + 1;
  for (int j = 0; j < count; ++j) {
    const double t = first_threshold + j;
    if (t <= centre) continue;
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
  for (int j = count - 1; j >= 0; --j) {
    const double t = first_threshold + j;
    if (t > centre) continue;
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

}  // namespace

bool ComputeWeightedStabilityProfile(const cv::Mat& gray, const std::vector<cv::Point2f>& reference,
                                     int centre_index, const WeightedStabilityOptions& options,
                                     StabilityProfile* profile) {
  const int n = static_cast<int>(reference.size());
  if (centre_index < 1 || centre_index > n - 2) return false;
  // Normals every normal_step samples within half_length of the centre, the centre included.
  const int normal_step = std::max(1, options.normal_step);
  const int reach_before = std::min(centre_index, options.half_length) / normal_step;
  const int reach_after = std::min(n - 1 - centre_index, options.half_length) / normal_step;
  const int num_normals = reach_before + reach_after + 1;
  const int centre_row = reach_before;
  const int m =
      std::max(1, static_cast<int>(std::lround(options.max_distance / options.sample_step)));
  const double step = options.sample_step;
  const int cubic_reach = static_cast<int>(std::floor(options.cubic_distance / step + 1e-9));
  const ProfileSampler interpolate(gray);

  // Unit normals towards the bright side (the right of the direction of travel), and weights.
  std::vector<cv::Point2d>& points = profile->points;
  std::vector<cv::Point2d>& normals = profile->normals;
  std::vector<double>& weights = profile->weights;
  points.resize(num_normals);
  normals.resize(num_normals);
  weights.resize(num_normals);
  double weight_sum = 0;
  for (int r = 0; r < num_normals; ++r) {
    const int i = centre_index + (r - centre_row) * normal_step;
    const cv::Point2d tangent =
        cv::Point2d(reference[std::min(n - 1, i + 1)]) - cv::Point2d(reference[std::max(0, i - 1)]);
    const double norm = std::sqrt(tangent.x * tangent.x + tangent.y * tangent.y);
    points[r] = reference[i];
    normals[r] = norm > 0 ? cv::Point2d(-tangent.y / norm, tangent.x / norm) : cv::Point2d(0, 0);
    const double d = i - centre_index;
    weights[r] = std::exp(-d * d / (2.0 * options.sigma * options.sigma));
    weight_sum += weights[r];
  }

  // Intensity profiles along the normals (row r: samples k = 0..2m at u = (k - m) * step), read
  // on demand.
  const int samples = 2 * m + 1;
  std::vector<float>& profiles = profile->samples;
  profiles.assign(static_cast<size_t>(num_normals) * samples, kNotSampled);
  auto sampler = [&](int r) {
    const cv::Point2d p = points[r];
    const cv::Point2d normal = normals[r];
    return [&interpolate, p, normal, m, step, cubic_reach](int k) {
      const double u = (k - m) * step;
      const double x = p.x + u * normal.x, y = p.y + u * normal.y;
      return std::abs(k - m) <= cubic_reach ? interpolate.Cubic(x, y) : interpolate.Bilinear(x, y);
    };
  };
  auto row_of = [&](int r) { return &profiles[static_cast<size_t>(r) * samples]; };

  // The intensities on the two sides of the curve: per normal, the darkest value on the dark
  // half and the brightest on the bright half within side_distance (extremes reach the flat sides
  // of a blurred edge whatever the reference curve's level), and across normals the weighted
  // median of their mid-points, robust to texture and to the few normals that cross to the far
  // side of a sharp tip. The central normal's values also give the candidate levels.
  const int side_reach = std::min(m, static_cast<int>(std::lround(options.side_distance / step)));
  const int search_reach =
      std::min(m, static_cast<int>(std::floor(options.search_radius / step + 1e-9)));
  const int read_reach = std::max(side_reach, search_reach);
  std::vector<std::pair<double, double>>& mids = profile->mids;
  mids.clear();
  for (int r = 0; r < num_normals; ++r) {
    float* row = row_of(r);
    const auto sample = sampler(r);
    for (int k = m - read_reach; k <= m + read_reach; ++k) row[k] = sample(k);
    float dark = std::numeric_limits<float>::infinity();
    float bright = -dark;
    for (int k = m - side_reach; k <= m; ++k) dark = std::min(dark, row[k]);
    for (int k = m; k <= m + side_reach; ++k) bright = std::max(bright, row[k]);
    mids.emplace_back(0.5 * (dark + bright), weights[r]);
  }
  std::sort(mids.begin(), mids.end());
  double cumulative = 0;
  double median = mids.back().first;
  for (const auto& [mid, weight] : mids) {
    cumulative += weight;
    if (cumulative >= 0.5 * weight_sum) {
      median = mid;
      break;
    }
  }
  profile->middle_level = median - 0.5;

  // Levels whose curve crosses the central normal within the search radius: J with
  // low < J + 0.5 <= high.
  const float* centre_profile = row_of(centre_row);
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (int k = m - search_reach; k <= m + search_reach; ++k) {
    low = std::min(low, static_cast<double>(centre_profile[k]));
    high = std::max(high, static_cast<double>(centre_profile[k]));
  }
  const int level_lo = static_cast<int>(std::ceil(low - 0.5 + 1e-9));
  const int level_hi = static_cast<int>(std::ceil(high - 0.5)) - 1;
  if (level_hi < level_lo) return false;
  const int first_level = level_lo - 1;
  const int num_levels = level_hi - level_lo + 3;
  // Crossings of the thresholds J + 0.5 + e, e in [-δ, δ] (δ rounded up; a fractional δ is
  // interpolated below).
  const int delta_steps = static_cast<int>(std::ceil(options.delta));
  const int first_threshold_level = first_level - delta_steps;
  const int num_thresholds = num_levels + 2 * delta_steps;
  std::vector<double>& crossing = profile->crossings;
  std::vector<uint8_t>& clipped = profile->clipped;
  crossing.resize(static_cast<size_t>(num_normals) * num_thresholds);
  clipped.resize(crossing.size());
  for (int r = 0; r < num_normals; ++r) {
    ProfileCrossings(row_of(r), samples, m, step, first_threshold_level + 0.5, num_thresholds,
                     sampler(r), &crossing[static_cast<size_t>(r) * num_thresholds],
                     &clipped[static_cast<size_t>(r) * num_thresholds]);
  }
  const bool whole_delta = options.delta == delta_steps;
  auto u_at = [&](int r, double j) {  // crossing of threshold index j (may be fractional)
    const double* row = &crossing[static_cast<size_t>(r) * num_thresholds];
    if (whole_delta) return row[static_cast<int>(j)];
    const int j0 = std::clamp(static_cast<int>(std::floor(j)), 0, num_thresholds - 1);
    const int j1 = std::min(j0 + 1, num_thresholds - 1);
    const double t = std::clamp(j - j0, 0.0, 1.0);
    return row[j0] + t * (row[j1] - row[j0]);
  };

  profile->first_level = first_level;
  profile->stability.assign(num_levels, 0.0);
  profile->length.assign(num_levels, 0.0);
  profile->band_area.assign(num_levels, 0.0);
  profile->centre_offset.assign(num_levels, 0.0);
  profile->centre = points[centre_row];
  profile->normal = normals[centre_row];
  std::vector<double>& element = profile->elements;
  element.resize(num_normals);
  for (int l = 0; l < num_levels; ++l) {
    const int j = l + delta_steps;  // threshold index of the level itself
    // Length element of the level's curve at each normal: half of each adjoining chord between
    // the points where the curve crosses consecutive normals (0 where it does not cross).
    std::fill(element.begin(), element.end(), 0.0);
    cv::Point2d previous;
    bool previous_valid = false;
    for (int r = 0; r < num_normals; ++r) {
      const size_t index = static_cast<size_t>(r) * num_thresholds + j;
      const bool valid = !clipped[index];
      const cv::Point2d q = points[r] + crossing[index] * normals[r];
      if (valid && previous_valid) {
        const double dx = q.x - previous.x;
        const double dy = q.y - previous.y;
        const double chord = std::sqrt(dx * dx + dy * dy);
        element[r - 1] += 0.5 * chord;
        element[r] += 0.5 * chord;
      }
      previous = q;
      previous_valid = valid;
    }
    // The strip of normal r has the band's width there times the curve's length element: the
    // area between Up and Down in that strip.
    double length = 0;
    double band = 0;
    for (int r = 0; r < num_normals; ++r) {
      length += weights[r] * element[r];
      band += weights[r] * element[r] * (u_at(r, j + options.delta) - u_at(r, j - options.delta));
    }
    band = std::max(band, 1e-6 * weight_sum);
    profile->band_area[l] = band;
    profile->length[l] = length;
    profile->stability[l] = length / band;
    profile->centre_offset[l] = crossing[static_cast<size_t>(centre_row) * num_thresholds + j];
  }
  return true;
}

bool SelectMaximallyStableLevel(const StabilityProfile& profile, double previous_level,
                                double run_tolerance, double ripple_tolerance,
                                StableLevel* selected) {
  const std::vector<double>& rho = profile.stability;
  const int count = profile.NumLevels();
  std::vector<int> maxima;
  for (int l = 1; l + 1 < count; ++l) {
    if (rho[l] > rho[l - 1] && rho[l] >= rho[l + 1]) maxima.push_back(l);
  }
  if (maxima.empty()) return false;
  // The maximum nearest in level to the previous MSICS (ties: larger ρ, then lower level).
  int current = 0;
  for (int m = 1; m < static_cast<int>(maxima.size()); ++m) {
    const double d = std::abs(profile.first_level + maxima[m] - previous_level);
    const double d_best = std::abs(profile.first_level + maxima[current] - previous_level);
    if (d < d_best || (d == d_best && rho[maxima[m]] > rho[maxima[current]])) current = m;
  }
  // Ripples are not separate curves: climb to a higher neighbouring maximum while the dip between
  // is shallower than ripple_tolerance (relative to the lower of the two), as MSER ignores
  // insignificant extrema. Between two distinct curves ρ drops by most of its value.
  auto dip_between = [&](int a, int b) {  // minimum of ρ strictly between levels a < b
    double low = std::numeric_limits<double>::infinity();
    for (int l = a + 1; l < b; ++l) low = std::min(low, rho[l]);
    return low;
  };
  for (;;) {
    const int l = maxima[current];
    const double floor = (1.0 - ripple_tolerance) * rho[l];
    int next = -1;
    for (int m : {current - 1, current + 1}) {
      if (m < 0 || m >= static_cast<int>(maxima.size())) continue;
      const int other = maxima[m];
      if (rho[other] <= rho[l]) continue;
      if (dip_between(std::min(l, other), std::max(l, other)) < floor) continue;
      if (next < 0 || rho[other] > rho[maxima[next]]) next = m;
    }
    if (next < 0) break;
    current = next;
  }
  const int best = maxima[current];
  // The run of levels around the peak whose ρ is within the tolerance of it. On a sharp edge ρ is
  // nearly flat over most of the edge's range (the band keeps its width while it moves across the
  // edge), so the exact maximum would be decided by ripples and by the corner's geometry.
  const double floor = (1.0 - run_tolerance) * rho[best];
  int run_begin = best;
  int run_end = best;
  while (run_begin > 0 && rho[run_begin - 1] >= floor) --run_begin;
  while (run_end + 1 < count && rho[run_end + 1] >= floor) ++run_end;
  // Every level of the run is as stable as the peak within the tolerance: take the one in the
  // middle of the intensities on the two sides of the curve (for a blurred step edge, the level
  // line through the edge itself), which depends only on the image.
  double centre = std::clamp(profile.middle_level - profile.first_level,
                             static_cast<double>(run_begin), static_cast<double>(run_end));
  double peak = rho[best];
  if (run_begin == run_end) {
    // A sharp maximum: refine it below one level with a parabola through its neighbours.
    const double a = rho[best - 1];
    const double b = rho[best];
    const double c = rho[best + 1];
    const double curvature = a - 2.0 * b + c;
    if (curvature < 0) {
      const double offset = std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
      centre = best + offset;
      peak = b - 0.25 * (a - c) * offset;
    }
  }
  selected->threshold = profile.first_level + centre + 0.5;
  selected->level = static_cast<int>(std::ceil(selected->threshold)) - 1;
  selected->stability = peak;
  return true;
}

}  // namespace comic::frontend
