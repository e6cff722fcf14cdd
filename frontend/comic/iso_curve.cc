#include "frontend/comic/iso_curve.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/core/error.h"

namespace comic::frontend {

IsoCurveTracer::IsoCurveTracer(const cv::Mat& image, const cv::Rect& domain, double threshold)
    : domain_(domain & cv::Rect(0, 0, image.cols, image.rows)),
      threshold_(threshold),
      data_(image.data),
      step_(static_cast<ptrdiff_t>(image.step[0])),
      inside_bound_(std::isnan(threshold)
                        ? -1
                        : static_cast<int>(std::clamp(std::ceil(threshold), -1.0, 257.0))) {
  COMIC_CHECK(image.type() == CV_8UC1, kInvalidArgument, "IsoCurveTracer: expected CV_8UC1");
}

bool IsoCurveTracer::IsCrossing(const CurveEdge& edge) const {
  const cv::Point d = edge.outside - edge.inside;
  return std::abs(d.x) + std::abs(d.y) == 1 && InDomain(edge.inside) && InDomain(edge.outside) &&
         IsInside(edge.inside) && !IsInside(edge.outside);
}

cv::Point2f IsoCurveTracer::Crossing(const CurveEdge& edge) const {
  const double v_in = Value(edge.inside);
  const double v_out = Value(edge.outside);
  const double t = (threshold_ - v_in) / (v_out - v_in);
  return {static_cast<float>(edge.inside.x + t * (edge.outside.x - edge.inside.x)),
          static_cast<float>(edge.inside.y + t * (edge.outside.y - edge.inside.y))};
}

namespace {

// The four directions of a pixel pair (outside - inside): +x, +y, -x, -y. Turning a direction by
// -90° (image coordinates, y down) is (d + 3) & 3, by +90° (d + 1) & 3, reversing it (d + 2) & 3.
constexpr int kDx[4] = {1, 0, -1, 0};
constexpr int kDy[4] = {0, 1, 0, -1};

int DirectionOf(const CurveEdge& edge) {
  const cv::Point d = edge.outside - edge.inside;
  return d.x == 1 ? 0 : d.y == 1 ? 1 : d.x == -1 ? 2 : 3;
}

}  // namespace

void IsoCurveTracer::Trace(const CurveEdge& seed, int max_points_each_way, IsoCurve* curve) const {
  TraceImpl<true>(seed, max_points_each_way, curve);
}

void IsoCurveTracer::TracePoints(const CurveEdge& seed, int max_points_each_way,
                                 IsoCurve* curve) const {
  TraceImpl<false>(seed, max_points_each_way, curve);
}

template <bool kWithEdges>
void IsoCurveTracer::TraceImpl(const CurveEdge& seed, int max_points_each_way,
                               IsoCurve* curve) const {
  COMIC_CHECK(IsCrossing(seed), kInvalidArgument, "IsoCurveTracer: seed is not a crossing");
  // A crossing is walked as its inside pixel (coordinates and address) and its direction; this
  // runs once per point of every traced curve, so it reads pixels by address.
  const ptrdiff_t offset[4] = {1, step_, -1, -step_};
  struct Walk {
    int x, y, direction;
    const uint8_t* inside;
  };
  const Walk start{seed.inside.x, seed.inside.y, DirectionOf(seed),
                   data_ + seed.inside.y * step_ + seed.inside.x};
  const double four_thresholds = 4.0 * threshold_;
  // One step along the curve: forward keeps the inside on the left. Marching squares on the cell
  // ahead of the pair: a, b the pixels ahead of the inside and outside pixel.
  auto step = [&](Walk* w, bool forward) {
    const int turn = forward ? (w->direction + 3) & 3 : (w->direction + 1) & 3;
    // The pair's pixels are in the domain and `turn` is perpendicular to their direction: a and b
    // share the one coordinate that moved, so a single compare decides whether both are in.
    const bool ahead_in_domain = (turn & 1) == 0
                                     ? static_cast<unsigned>(w->x + kDx[turn] - domain_.x) <
                                           static_cast<unsigned>(domain_.width)
                                     : static_cast<unsigned>(w->y + kDy[turn] - domain_.y) <
                                           static_cast<unsigned>(domain_.height);
    if (!ahead_in_domain) return false;
    const uint8_t* a = w->inside + offset[turn];
    const uint8_t* b = a + offset[w->direction];
    const bool a_inside = *a < inside_bound_;
    const bool b_inside = *b < inside_bound_;
    const int back = (turn + 2) & 3;
    if (!a_inside) {
      // Saddle (inside pixels on a diagonal): the cell centre, the mean of its four pixels as in
      // the bilinear interpolant, decides whether the two inside pixels are joined.
      const bool joined =
          b_inside && *w->inside + w->inside[offset[w->direction]] + *a + *b < four_thresholds;
      if (joined) {
        w->x += kDx[turn] + kDx[w->direction];
        w->y += kDy[turn] + kDy[w->direction];
        w->inside = b;
        w->direction = back;
      } else {
        w->direction = turn;
      }
    } else if (!b_inside) {
      w->x += kDx[turn];
      w->y += kDy[turn];
      w->inside = a;
    } else {
      w->x += kDx[turn] + kDx[w->direction];
      w->y += kDy[turn] + kDy[w->direction];
      w->inside = b;
      w->direction = back;
    }
    return true;
  };
  auto same = [](const Walk& p, const Walk& q) {
    return p.x == q.x && p.y == q.y && p.direction == q.direction;
  };
  // The crossing of a pair, linearly interpolated between the pixel centres.
  auto crossing = [&](const Walk& w) {
    const double v_in = *w.inside;
    const double v_out = w.inside[offset[w.direction]];
    const double t = (threshold_ - v_in) / (v_out - v_in);
    return cv::Point2f(static_cast<float>(w.x + t * kDx[w.direction]),
                       static_cast<float>(w.y + t * kDy[w.direction]));
  };
  auto edge_of = [](const Walk& w) {
    return CurveEdge{{w.x, w.y}, {w.x + kDx[w.direction], w.y + kDy[w.direction]}};
  };
  std::vector<cv::Point2f>& points = curve->points;
  std::vector<CurveEdge>& edges = curve->edges;
  points.clear();
  edges.clear();
  curve->closed = false;
  auto emit = [&](const Walk& w) {
    points.push_back(crossing(w));
    if (kWithEdges) edges.push_back(edge_of(w));
  };
  // Backward part first (collected reversed), then the seed, then the forward part.
  Walk walk = start;
  for (int n = 0; n < max_points_each_way && step(&walk, false); ++n) {
    if (same(walk, start)) {
      curve->closed = true;
      break;
    }
    emit(walk);
  }
  if (curve->closed) {
    // A closed curve, in the natural order: the seed, then going forward. A step is reversible
    // (both directions pair the crossings of a cell alike, saddles included, by the same four
    // values), so the backward walk already visited every crossing of the loop: reversed, it is
    // the forward walk, and the loop need not be traced a second time.
    emit(start);
    std::reverse(points.begin(), points.end());
    if (kWithEdges) std::reverse(edges.begin(), edges.end());
    curve->seed_index = 0;
    return;
  }
  std::reverse(points.begin(), points.end());
  if (kWithEdges) std::reverse(edges.begin(), edges.end());
  curve->seed_index = static_cast<int>(points.size());
  emit(start);
  walk = start;
  for (int n = 0; n < max_points_each_way && step(&walk, true); ++n) {
    if (same(walk, start)) break;  // cannot happen for an open curve; guards the loop
    emit(walk);
  }
}

bool IsoCurveTracer::FindNearestCrossing(const cv::Point2f& point, int radius,
                                         CurveEdge* edge) const {
  const int cx = static_cast<int>(std::lround(point.x));
  const int cy = static_cast<int>(std::lround(point.y));
  double best = std::numeric_limits<double>::infinity();
  for (int y = cy - radius; y <= cy + radius; ++y) {
    for (int x = cx - radius; x <= cx + radius; ++x) {
      const cv::Point p(x, y);
      if (!InDomain(p)) continue;
      const bool p_inside = IsInside(p);
      for (const cv::Point& q : {cv::Point(x + 1, y), cv::Point(x, y + 1)}) {
        if (q.x > cx + radius || q.y > cy + radius || !InDomain(q)) continue;
        if (IsInside(q) == p_inside) continue;
        const CurveEdge candidate = p_inside ? CurveEdge{p, q} : CurveEdge{q, p};
        const cv::Point2f c = Crossing(candidate);
        const double d2 = (c.x - point.x) * (c.x - point.x) + (c.y - point.y) * (c.y - point.y);
        if (d2 < best) {
          best = d2;
          *edge = candidate;
        }
      }
    }
  }
  return std::isfinite(best);
}

namespace {

double Distance(const cv::Point2f& a, const cv::Point2f& b) {
  const double dx = static_cast<double>(a.x) - b.x;
  const double dy = static_cast<double>(a.y) - b.y;
  return std::sqrt(dx * dx + dy * dy);
}

}  // namespace

void PolylineArcLengths(const std::vector<cv::Point2f>& points, bool closed,
                        std::vector<double>* cumulative) {
  const size_t n = points.size();
  cumulative->resize(n + 1);
  double* c = cumulative->data();
  c[0] = 0.0;
  for (size_t i = 1; i < n; ++i) c[i] = c[i - 1] + Distance(points[i - 1], points[i]);
  c[n] = n == 0 ? 0.0 : c[n - 1] + (closed ? Distance(points[n - 1], points[0]) : 0.0);
}

double PolylineLength(const std::vector<cv::Point2f>& points, bool closed) {
  std::vector<double> cumulative;
  PolylineArcLengths(points, closed, &cumulative);
  return cumulative.back();
}

double ArcLengthAt(const std::vector<cv::Point2f>& points, int index) {
  double s = 0;
  for (int i = 1; i <= index && i < static_cast<int>(points.size()); ++i) {
    s += Distance(points[i - 1], points[i]);
  }
  return s;
}

std::vector<cv::Point2f> ResamplePolyline(const std::vector<cv::Point2f>& points, bool closed,
                                          double spacing, double origin, int max_before,
                                          int max_after, int* origin_index) {
  std::vector<double> cumulative;
  PolylineArcLengths(points, closed, &cumulative);
  return ResamplePolyline(points, cumulative, closed, spacing, origin, max_before, max_after,
                          origin_index);
}

std::vector<cv::Point2f> ResamplePolyline(const std::vector<cv::Point2f>& points,
                                          const std::vector<double>& cumulative, bool closed,
                                          double spacing, double origin, int max_before,
                                          int max_after, int* origin_index) {
  std::vector<cv::Point2f> samples;
  if (origin_index) *origin_index = 0;
  if (points.size() < 2 || spacing <= 0) return samples;
  const double length = cumulative.back();
  if (length <= 0) return samples;
  if (closed) {
    const int n = std::max(3, static_cast<int>(std::lround(length / spacing)));
    const double step = length / n;
    samples.resize(n);
    cv::Point2f* out = samples.data();
    // The segment of each sample as Interpolate finds it (the last vertex at or before s), by a
    // walk instead of a binary search while s increases (it wraps at most once, for an origin
    // other than 0): the same segment, hence the same point.
    const size_t num_points = points.size();
    const size_t segments = num_points;
    size_t segment = 0;
    double previous_s = -1.0;
    for (int k = 0; k < n; ++k) {
      // fmod(s, length) is s itself for s in [0, length): skip it there (most samples).
      double s = origin + k * step;
      if (!(s >= 0 && s < length)) {
        s = std::fmod(s, length);
        if (s < 0) s += length;
      }
      if (s < previous_s) segment = 0;
      previous_s = s;
      while (segment < segments && cumulative[segment + 1] <= s) ++segment;
      const size_t i = std::min(segment, segments - 1);
      const double segment_length = cumulative[i + 1] - cumulative[i];
      const double t =
          segment_length > 0 ? std::clamp((s - cumulative[i]) / segment_length, 0.0, 1.0) : 0.0;
      const cv::Point2f& a = points[i];
      const cv::Point2f& b = points[i + 1 == num_points ? 0 : i + 1];
      out[k] = cv::Point2f(static_cast<float>(a.x + t * (b.x - a.x)),
                           static_cast<float>(a.y + t * (b.y - a.y)));
    }
    return samples;
  }
  constexpr double kSlack = 1e-6;
  const int k_first =
      std::max(-max_before, static_cast<int>(std::ceil((-kSlack - origin) / spacing)));
  const int k_last =
      std::min(max_after, static_cast<int>(std::floor((length + kSlack - origin) / spacing)));
  if (k_last < k_first) return samples;
  samples.resize(k_last - k_first + 1);
  cv::Point2f* out = samples.data();
  // Arc lengths increase with k: walk the segments once.
  size_t segment = 0;
  const size_t last_segment = points.size() - 2;
  for (int k = k_first; k <= k_last; ++k) {
    const double s = std::clamp(origin + k * spacing, 0.0, length);
    while (segment < last_segment && cumulative[segment + 1] < s) ++segment;
    const double segment_length = cumulative[segment + 1] - cumulative[segment];
    const double t =
        segment_length > 0 ? std::clamp((s - cumulative[segment]) / segment_length, 0.0, 1.0) : 0.0;
    const cv::Point2f& a = points[segment];
    const cv::Point2f& b = points[segment + 1];
    out[k - k_first] = cv::Point2f(static_cast<float>(a.x + t * (b.x - a.x)),
                                   static_cast<float>(a.y + t * (b.y - a.y)));
  }
  if (origin_index) *origin_index = std::max(0, -k_first);
  return samples;
}

double ProjectOntoPolyline(const std::vector<cv::Point2f>& points, bool closed,
                           const cv::Point2f& query) {
  if (points.size() < 2) return 0.0;
  const size_t n = points.size();
  const size_t segments = closed ? n : n - 1;
  double best_d2 = std::numeric_limits<double>::infinity();
  double best_s = 0;
  double s0 = 0;
  for (size_t i = 0; i < segments; ++i) {
    const cv::Point2d a = points[i];
    const cv::Point2d b = points[(i + 1) % n];
    const cv::Point2d ab = b - a;
    const double len2 = ab.dot(ab);
    const double t = len2 > 0 ? std::clamp((cv::Point2d(query) - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const cv::Point2d c = a + t * ab;
    const cv::Point2d diff = cv::Point2d(query) - c;
    const double d2 = diff.dot(diff);
    const double len = std::sqrt(len2);
    if (d2 < best_d2) {
      best_d2 = d2;
      best_s = s0 + t * len;
    }
    s0 += len;
  }
  return best_s;
}

}  // namespace comic::frontend
