#include "frontend/comic/curve_cornerness.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace comic::frontend {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Floor division for possibly negative numerators.
long FloorDiv(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Channels x, y, x², xy, y² of the moments (the weight channel "1" is an integer count, kept
// apart in CurveCornerness).
constexpr long kChannels = 5;

// Grows `buffer` to at least `size` elements, never shrinking it (a shrink and regrow would zero
// the regrown part every time a longer curve follows a shorter one), and returns its data.
template <typename T>
T* Reserved(std::vector<T>* buffer, size_t size) {
  if (buffer->size() < size) buffer->resize(size);
  return buffer->data();
}

// One box-filter pass of radius r over the interleaved channels of n samples:
// out[i] = sum of in[i - r .. i + r], truncated at the ends of an open sequence, wrapped around a
// closed one, through prefix sums. `p` is scratch space of (n + 1) * C values.
void BoxPass(const double* x, long n, bool closed, int r, double* p, double* y) {
  constexpr long C = kChannels;
  for (long c = 0; c < C; ++c) p[c] = 0.0;
  for (long i = 0; i < n; ++i) {
    for (long c = 0; c < C; ++c) p[(i + 1) * C + c] = p[i * C + c] + x[i * C + c];
  }
  // Samples whose window lies inside [0, n): the same difference for both kinds of curve (for a
  // closed one both wrap counts are 0, and 0 * total + p is p exactly, up to the sign of a zero,
  // which no later step reads).
  const long inner_begin = std::min<long>(r, n);
  const long inner_end = std::max(inner_begin, n - r - 1);
  for (long i = inner_begin; i < inner_end; ++i) {
    const double* p_hi = p + (i + r + 1) * C;
    const double* p_lo = p + (i - r) * C;
    for (long c = 0; c < C; ++c) y[i * C + c] = p_hi[c] - p_lo[c];
  }
  auto edge = [&](long i) {
    if (closed) {
      // Sums of in[j mod n] for j in [0, i + r + 1) and [0, i - r).
      const double* total = p + n * C;
      const long hi = i + r + 1, lo = i - r;
      const long hi_wraps = FloorDiv(hi, n), lo_wraps = FloorDiv(lo, n);
      const double* p_hi = p + (hi - hi_wraps * n) * C;
      const double* p_lo = p + (lo - lo_wraps * n) * C;
      for (long c = 0; c < C; ++c) {
        y[i * C + c] = (hi_wraps * total[c] + p_hi[c]) - (lo_wraps * total[c] + p_lo[c]);
      }
    } else {
      const double* p_hi = p + std::min(n, i + r + 1) * C;
      const double* p_lo = p + std::max(0L, i - r) * C;
      for (long c = 0; c < C; ++c) y[i * C + c] = p_hi[c] - p_lo[c];
    }
  };
  for (long i = 0; i < inner_begin; ++i) edge(i);
  for (long i = inner_end; i < n; ++i) edge(i);
}

// The same pass on the weight channel (the filtered "1"): integer counts, exact in double, so
// the doubles the six-channel filter gave are these integers.
void CountPass(const long* x, long n, bool closed, int r, long* p, long* y) {
  p[0] = 0;
  for (long i = 0; i < n; ++i) p[i + 1] = p[i] + x[i];
  for (long i = 0; i < n; ++i) {
    if (closed) {
      const long hi = i + r + 1, lo = i - r;
      const long hi_wraps = FloorDiv(hi, n), lo_wraps = FloorDiv(lo, n);
      y[i] = (hi_wraps * p[n] + p[hi - hi_wraps * n]) - (lo_wraps * p[n] + p[lo - lo_wraps * n]);
    } else {
      y[i] = p[std::min(n, i + r + 1)] - p[std::max(0L, i - r)];
    }
  }
}

cv::Point2d SampleAt(const std::vector<cv::Point2f>& points, bool closed, double index) {
  const int n = static_cast<int>(points.size());
  if (!closed) index = std::clamp(index, 0.0, static_cast<double>(n - 1));
  const double base = std::floor(index);
  const double t = index - base;
  int i0 = static_cast<int>(base);
  int i1 = i0 + 1;
  if (closed) {
    i0 = ((i0 % n) + n) % n;
    i1 = ((i1 % n) + n) % n;
  } else {
    i1 = std::min(i1, n - 1);
  }
  return cv::Point2d(points[i0]) * (1.0 - t) + cv::Point2d(points[i1]) * t;
}

struct Line {
  cv::Point2d centroid;
  cv::Point2d direction;
  double rms = 0.0;  // RMS distance of the samples from the line
};

// Total-least-squares line through the samples with index in [from, to] (wrapped if closed).
bool FitLine(const std::vector<cv::Point2f>& points, bool closed, double from, double to,
             Line* line) {
  const int n = static_cast<int>(points.size());
  // The samples: indices [first, last], clipped to the curve if it is open (two passes over
  // them, no copy).
  int first = static_cast<int>(std::ceil(from));
  int last = static_cast<int>(std::floor(to));
  if (!closed) {
    first = std::max(first, 0);
    last = std::min(last, n - 1);
  }
  const int count = std::max(0, last - first + 1);
  if (count < 3) return false;
  auto sample = [&](int j) { return cv::Point2d(points[((j % n) + n) % n]); };
  cv::Point2d mean(0, 0);
  for (int j = first; j <= last; ++j) mean += sample(j);
  mean *= 1.0 / count;
  double sxx = 0, sxy = 0, syy = 0;
  for (int j = first; j <= last; ++j) {
    const cv::Point2d d = sample(j) - mean;
    sxx += d.x * d.x;
    sxy += d.x * d.y;
    syy += d.y * d.y;
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  line->centroid = mean;
  line->direction = {std::cos(angle), std::sin(angle)};
  // The smaller eigenvalue of the scatter matrix is the sum of squared distances from the line.
  const double half_trace = 0.5 * (sxx + syy);
  const double across =
      half_trace - std::sqrt(std::max(0.0, half_trace * half_trace - (sxx * syy - sxy * sxy)));
  line->rms = std::sqrt(std::max(0.0, across) / count);
  return true;
}

double Cross(const cv::Point2d& a, const cv::Point2d& b) { return a.x * b.y - a.y * b.x; }

}  // namespace

int BoxRadiusForGaussian(double sigma) {
  const double r = 0.5 * (std::sqrt(1.0 + 4.0 * sigma * sigma) - 1.0);
  return std::max(1, static_cast<int>(std::lround(r)));
}

std::vector<double> CurveCornerness(const std::vector<cv::Point2f>& points, bool closed,
                                    double sigma, int min_support) {
  CornernessWorkspace workspace;
  std::vector<double> kappa;
  CurveCornerness(points, closed, sigma, min_support, &workspace, &kappa);
  return kappa;
}

void CurveCornerness(const std::vector<cv::Point2f>& points, bool closed, double sigma,
                     int min_support, CornernessWorkspace* workspace, std::vector<double>* kappa) {
  const int n = static_cast<int>(points.size());
  kappa->assign(n, -1.0);
  if (n < 3) return;
  const int r = BoxRadiusForGaussian(sigma);
  // Channels x, y, x², xy, y² (relative to the first point, for numerical range), interleaved.
  const size_t size = static_cast<size_t>(n) * kChannels;
  double* channels = Reserved(&workspace->channels, size);
  double* filtered = Reserved(&workspace->filtered, size);
  double* prefix = Reserved(&workspace->prefix, size + kChannels);
  const cv::Point2d origin = points[0];
  for (int i = 0; i < n; ++i) {
    const double x = points[i].x - origin.x;
    const double y = points[i].y - origin.y;
    double* c = channels + static_cast<size_t>(i) * kChannels;
    c[0] = x;
    c[1] = y;
    c[2] = x * x;
    c[3] = x * y;
    c[4] = y * y;
  }
  for (int pass = 0; pass < 3; ++pass) {
    BoxPass(channels, n, closed, r, prefix, filtered);
    std::swap(channels, filtered);
  }
  // The filtered weight normalises truncated windows: (2r + 1)³ wherever the window is whole (a
  // closed curve always), fewer near the ends of an open one.
  const long whole = static_cast<long>(2 * r + 1) * (2 * r + 1) * (2 * r + 1);
  long* counts = nullptr;
  if (!closed) {
    long* ones = Reserved(&workspace->counts, 3 * static_cast<size_t>(n) + 1);
    long* scratch = ones + n;
    counts = scratch + n + 1;
    std::fill(ones, ones + n, 1L);
    for (int pass = 0; pass < 3; ++pass) {
      CountPass(ones, n, closed, r, scratch, counts);
      std::copy(counts, counts + n, ones);
    }
  }
  double* k = kappa->data();
  for (int i = 0; i < n; ++i) {
    if (!closed && (i < min_support || i > n - 1 - min_support)) continue;
    const double* c = channels + static_cast<size_t>(i) * kChannels;
    const double w = static_cast<double>(closed ? whole : counts[i]);
    const double mx = c[0] / w;
    const double my = c[1] / w;
    const double sxx = c[2] / w - mx * mx;
    const double sxy = c[3] / w - mx * my;
    const double syy = c[4] / w - my * my;
    const double trace = sxx + syy;
    const double det = sxx * syy - sxy * sxy;
    k[i] = trace > 1e-12 ? std::clamp(det / (trace * trace), 0.0, 0.25) : 0.0;
  }
}

namespace {

// Outputs per block of CurveCornernessCumulative: the sums restart at every block, from a local
// origin, so that their magnitudes (~ block³ · extent²) keep κ within 1e-9 of the box passes.
constexpr int kCumulativeBlock = 256;

// Moments of one sample relative to `origin`: weight, x, y, x², xy, y² (weight 0: off the curve).
struct Moments {
  double v[6];
};

}  // namespace

void CurveCornernessCumulative(const std::vector<cv::Point2f>& points, bool closed, double sigma,
                               int min_support, CornernessWorkspace* workspace,
                               std::vector<double>* kappa) {
  const int n = static_cast<int>(points.size());
  kappa->assign(n, -1.0);
  if (n < 3) return;
  const int r = BoxRadiusForGaussian(sigma);
  // κ is asked for on [begin, end): every sample of a closed curve, those with min_support
  // samples on both sides on an open one.
  const int begin = closed ? 0 : min_support;
  const int end = closed ? n : n - min_support;
  // Per block of outputs [b0, b0 + B): the samples s0 = b0 - 3r .. b0 + B + 3r + 2 (wrapped on a
  // closed curve, weight 0 beyond an open one's ends), S¹..S³ their exclusive running sums, and
  //   box³[i] = S³[i + 3r + 3] - 3 S³[i + r + 2] + 3 S³[i - r + 1] - S³[i - 3r]   (local i).
  const int span = kCumulativeBlock + 6 * r + 3;
  double* s3 = Reserved(&workspace->prefix, static_cast<size_t>(span + 1) * 6);
  double* k = kappa->data();
  for (int b0 = begin; b0 < end; b0 += kCumulativeBlock) {
    const int b1 = std::min(end, b0 + kCumulativeBlock);
    const int s0 = b0 - 3 * r;
    const int m = (b1 - b0) + 6 * r + 3;
    const double ox = points[b0 % n].x, oy = points[b0 % n].y;
    // The samples of the block, wrapped on a closed curve: j -> points[j mod n], without a
    // division per sample.
    int wrapped = s0 % n;
    if (wrapped < 0) wrapped += n;
    auto moments = [&](int j, Moments* out) {
      const int index = wrapped;
      if (++wrapped == n) wrapped = 0;
      if (!closed && (j < 0 || j >= n)) {
        *out = Moments{};
        return;
      }
      const cv::Point2f& p = points[index];
      const double x = p.x - ox, y = p.y - oy;
      out->v[0] = 1.0;
      out->v[1] = x;
      out->v[2] = y;
      out->v[3] = x * x;
      out->v[4] = x * y;
      out->v[5] = y * y;
    };
    Moments u;
#if defined(__SSE2__)
    __m128d a1[3], a2[3], a3[3];
    for (int c = 0; c < 3; ++c) a1[c] = a2[c] = a3[c] = _mm_setzero_pd();
    for (int c = 0; c < 3; ++c) _mm_storeu_pd(s3 + 2 * c, a3[c]);
    for (int j = 0; j < m; ++j) {
      moments(s0 + j, &u);
      double* out = s3 + static_cast<size_t>(j + 1) * 6;
      for (int c = 0; c < 3; ++c) {
        // S³[j + 1] = S³[j] + S²[j], S²[j + 1] = S²[j] + S¹[j], S¹[j + 1] = S¹[j] + u[j].
        a3[c] = _mm_add_pd(a3[c], a2[c]);
        a2[c] = _mm_add_pd(a2[c], a1[c]);
        a1[c] = _mm_add_pd(a1[c], _mm_loadu_pd(u.v + 2 * c));
        _mm_storeu_pd(out + 2 * c, a3[c]);
      }
    }
#else
    double a1[6] = {}, a2[6] = {}, a3[6] = {};
    for (int c = 0; c < 6; ++c) s3[c] = 0.0;
    for (int j = 0; j < m; ++j) {
      moments(s0 + j, &u);
      double* out = s3 + static_cast<size_t>(j + 1) * 6;
      for (int c = 0; c < 6; ++c) {
        a3[c] += a2[c];
        a2[c] += a1[c];
        a1[c] += u.v[c];
        out[c] = a3[c];
      }
    }
#endif
    for (int i = b0; i < b1; ++i) {
      const int local = i - s0;
      const double* p0 = s3 + static_cast<size_t>(local + 3 * r + 3) * 6;
      const double* p1 = s3 + static_cast<size_t>(local + r + 2) * 6;
      const double* p2 = s3 + static_cast<size_t>(local - r + 1) * 6;
      const double* p3 = s3 + static_cast<size_t>(local - 3 * r) * 6;
      double box[6];
#if defined(__SSE2__)
      const __m128d three = _mm_set1_pd(3.0);
      for (int c = 0; c < 6; c += 2) {
        const __m128d outer = _mm_sub_pd(_mm_loadu_pd(p0 + c), _mm_loadu_pd(p3 + c));
        const __m128d inner = _mm_sub_pd(_mm_loadu_pd(p2 + c), _mm_loadu_pd(p1 + c));
        _mm_storeu_pd(box + c, _mm_add_pd(outer, _mm_mul_pd(three, inner)));
      }
#else
      for (int c = 0; c < 6; ++c) box[c] = (p0[c] - p3[c]) + 3.0 * (p2[c] - p1[c]);
#endif
      const double inverse_weight = 1.0 / box[0];
      const double mx = box[1] * inverse_weight;
      const double my = box[2] * inverse_weight;
      const double sxx = box[3] * inverse_weight - mx * mx;
      const double sxy = box[4] * inverse_weight - mx * my;
      const double syy = box[5] * inverse_weight - my * my;
      const double trace = sxx + syy;
      const double det = sxx * syy - sxy * sxy;
      k[i] = trace > 1e-12 ? std::clamp(det / (trace * trace), 0.0, 0.25) : 0.0;
    }
  }
}

std::vector<int> CornernessMaxima(const std::vector<double>& kappa, bool closed, int radius,
                                  double min_cornerness) {
  const int n = static_cast<int>(kappa.size());
  std::vector<int> maxima;
  // Whether neighbour j (offset != 0) lets sample i, with κ = k, be a maximum: it is ignored when
  // outside an open curve, on i itself after wrapping, or without κ; earlier samples must be
  // strictly lower and later ones not higher, so that a plateau yields its first sample.
  auto allows = [&](int i, int offset, double k) {
    int j = i + offset;
    if (closed) {
      if (j < 0 || j >= n) j = ((j % n) + n) % n;  // a radius beyond n wraps more than once
      if (j == i) return true;
    } else if (j < 0 || j >= n) {
      return true;
    }
    if (kappa[j] < 0) return true;
    return offset < 0 ? kappa[j] < k : kappa[j] <= k;
  };
  const double* values = kappa.data();
  for (int i = 0; i < n; ++i) {
    const double k = values[i];
    if (k < 0 || k < min_cornerness) continue;
    // Nearest neighbours first: most samples are rejected by an adjacent one.
    bool is_max = true;
    if (i >= radius && i + radius < n) {
      // Every neighbour inside the curve, none wrapped onto i: allows() reduces to the
      // comparisons (a neighbour without κ, -1, is below k >= 0 either way).
      for (int d = 1; d <= radius && is_max; ++d) is_max = values[i - d] < k && values[i + d] <= k;
    } else {
      for (int d = 1; d <= radius && is_max; ++d) is_max = allows(i, -d, k) && allows(i, d, k);
    }
    if (is_max) maxima.push_back(i);
  }
  return maxima;
}

CurveCorner RefineCurveCorner(const std::vector<cv::Point2f>& points, bool closed,
                              const std::vector<double>& kappa, int index,
                              const CurveCornerOptions& options) {
  const int n = static_cast<int>(points.size());
  auto kappa_at = [&](int j) -> double {
    if (closed) return kappa[((j % n) + n) % n];
    return (j < 0 || j >= n) ? -1.0 : kappa[j];
  };
  CurveCorner corner;
  const double k0 = kappa_at(index);
  const double km = kappa_at(index - 1);
  const double kp = kappa_at(index + 1);
  double offset = 0.0;
  corner.cornerness = k0;
  const double curvature = km - 2.0 * k0 + kp;
  if (km >= 0 && kp >= 0 && curvature < 0) {
    offset = std::clamp(0.5 * (km - kp) / curvature, -0.5, 0.5);
    corner.cornerness = std::min(0.25, k0 - 0.25 * (km - kp) * offset);  // κ <= 1/4
  }
  corner.index = index + offset;
  const cv::Point2d apex = SampleAt(points, closed, corner.index);
  corner.apex = apex;
  corner.vertex = apex;

  // Turning direction and vertex from lines fitted to the two arms.
  Line before, after;
  const bool arms_fit = (!closed || n > 2 * options.arm_end + 2) &&
                        FitLine(points, closed, corner.index - options.arm_end,
                                corner.index - options.arm_begin, &before) &&
                        FitLine(points, closed, corner.index + options.arm_begin,
                                corner.index + options.arm_end, &after);
  cv::Point2d out_before, out_after;  // unit vectors from the apex along each arm
  if (arms_fit) {
    out_before = before.direction;
    if (out_before.dot(before.centroid - apex) < 0) out_before = -out_before;
    out_after = after.direction;
    if (out_after.dot(after.centroid - apex) < 0) out_after = -out_after;
  } else {
    // Too short for lines: use the chords to the farthest samples available on each side.
    const double reach = std::min(options.arm_end, closed ? 0.5 * (n - 1) : options.arm_end);
    out_before = SampleAt(points, closed, corner.index - reach) - apex;
    out_after = SampleAt(points, closed, corner.index + reach) - apex;
    const double nb = std::hypot(out_before.x, out_before.y);
    const double na = std::hypot(out_after.x, out_after.y);
    if (nb <= 0 || na <= 0) return corner;
    out_before *= 1.0 / nb;
    out_after *= 1.0 / na;
  }
  const double interior = std::acos(std::clamp(out_before.dot(out_after), -1.0, 1.0));
  const double turn = kPi - interior;
  // Incoming direction -out_before, outgoing out_after; with y pointing down a negative cross
  // product is a turn to the left, the dark side.
  const bool towards_dark = Cross(-out_before, out_after) < 0;
  corner.turn_angle = towards_dark ? turn : -turn;
  corner.polarity = towards_dark ? Polarity::kDark : Polarity::kBright;
  if (!arms_fit) return corner;

  corner.arm_rms = std::max(before.rms, after.rms);
  const double turn_degrees = turn * 180.0 / kPi;
  const double clear_turn =
      std::clamp((turn_degrees - options.blend_begin_degrees) /
                     std::max(1e-9, options.blend_end_degrees - options.blend_begin_degrees),
                 0.0, 1.0);
  const double straight_arms = std::clamp(
      (options.straight_arms_rms_end - corner.arm_rms) /
          std::max(1e-9, options.straight_arms_rms_end - options.straight_arms_rms_begin),
      0.0, 1.0);
  const double blend = clear_turn * straight_arms;
  const double det = Cross(before.direction, after.direction);
  if (blend <= 0 || std::abs(det) < 1e-6) return corner;
  // before.centroid + a * before.direction = after.centroid + b * after.direction.
  const cv::Point2d gap = after.centroid - before.centroid;
  const double a = Cross(gap, after.direction) / det;
  const cv::Point2d intersection = before.centroid + a * before.direction;
  cv::Point2d shift = intersection - apex;
  const double length = std::hypot(shift.x, shift.y);
  if (length > options.max_vertex_shift) shift *= options.max_vertex_shift / length;
  corner.vertex = apex + blend * shift;
  return corner;
}

}  // namespace comic::frontend
