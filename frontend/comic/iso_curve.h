// Sub-pixel iso-intensity curves. An iso-curve at threshold T is the level line f = T of the image
// interpolated linearly between pixel centres, traced marching-squares style: it separates the
// "inside" pixels {v < T} (the dark side) from the others and crosses every 4-neighbour pair
// (inside, outside) once, at the linearly interpolated point. For CoMIC's level I the threshold is
// T = I + 0.5 (DESIGN.md: the boundary between {v <= I} and {v > I}); a fractional T in (I, I + 1)
// separates the same pixels but places the crossings in between, which is how a level is refined
// below one grey level (paper §2, "choose the level consistently", see iso_curve_stability.h).
//
// Tracing follows pixel-edge crossings, so the curve is a polyline through crossing points rather
// than the staircase of pixel edges. In a saddle cell (two inside pixels on a diagonal) the curve
// is resolved by the cell's mean value, as the bilinear interpolant does, which treats both
// polarities alike. Curves are oriented with the dark side on the left (image coordinates, y
// down).
#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace comic::frontend {

// A 4-neighbour pixel pair crossed by a curve: `inside` has value < T, `outside` >= T.
struct CurveEdge {
  cv::Point inside;
  cv::Point outside;
  bool operator==(const CurveEdge& other) const {
    return inside == other.inside && outside == other.outside;
  }
};

struct IsoCurve {
  // Crossing points in order, dark side on the left. Sub-pixel, OpenCV pixel-centre convention.
  std::vector<cv::Point2f> points;
  // The pixel pair crossed at each point (same order as `points`).
  std::vector<CurveEdge> edges;
  // True if the curve closes on itself inside the domain; false if it ends at the domain border
  // (or at the length limit).
  bool closed = false;
  // Index in `points` of the seed the trace started from.
  int seed_index = 0;
};

// Traces level lines of one 8-bit image at one threshold, within a rectangular domain of pixels.
class IsoCurveTracer {
 public:
  // `image` is CV_8UC1; `domain` is clipped to the image. The tracer keeps a reference to the
  // image data: it must outlive the tracer.
  IsoCurveTracer(const cv::Mat& image, const cv::Rect& domain, double threshold);

  double threshold() const { return threshold_; }
  const cv::Rect& domain() const { return domain_; }
  bool InDomain(const cv::Point& p) const {
    // Unsigned compares: one test per axis (as cv::Rect::contains).
    return static_cast<unsigned>(p.x - domain_.x) < static_cast<unsigned>(domain_.width) &&
           static_cast<unsigned>(p.y - domain_.y) < static_cast<unsigned>(domain_.height);
  }
  int Value(const cv::Point& p) const { return data_[p.y * step_ + p.x]; }
  // v < threshold for an integer v is v < ceil(threshold): an integer compare per pixel.
  bool IsInside(const cv::Point& p) const { return Value(p) < inside_bound_; }
  // True if the pair is a valid crossing of this tracer: both in the domain, 4-neighbours,
  // inside/outside as named.
  bool IsCrossing(const CurveEdge& edge) const;
  // Where the curve crosses `edge` (linear interpolation between the two pixel centres).
  cv::Point2f Crossing(const CurveEdge& edge) const;

  // Traces the curve through `seed` both ways until it closes, leaves the domain, or has
  // `max_points_each_way` points on a side. `seed` must satisfy IsCrossing.
  void Trace(const CurveEdge& seed, int max_points_each_way, IsoCurve* curve) const;
  // The same points, closed flag and seed index, without `curve->edges` (left empty), for a
  // caller that needs the polyline only.
  void TracePoints(const CurveEdge& seed, int max_points_each_way, IsoCurve* curve) const;

  // The crossing of this threshold nearest to `point` among the 4-neighbour pairs whose pixels
  // lie within `radius` pixels of it (inclusive, Chebyshev). Returns false if there is none.
  bool FindNearestCrossing(const cv::Point2f& point, int radius, CurveEdge* edge) const;

 private:
  template <bool kWithEdges>
  void TraceImpl(const CurveEdge& seed, int max_points_each_way, IsoCurve* curve) const;

  cv::Rect domain_;
  double threshold_;
  const uint8_t* data_;
  ptrdiff_t step_;
  int inside_bound_;  // ceil(threshold_), clamped to [-1, 257]
};

// Arc length of a polyline (closing segment included when `closed`).
double PolylineLength(const std::vector<cv::Point2f>& points, bool closed);

// Resamples a polyline at a uniform spacing along its arc length. For an open polyline, samples
// are at arc lengths origin + k * spacing for k in [-max_before, max_after], kept where they fall
// within the polyline; *origin_index receives the index of k = 0. For a closed polyline the
// spacing is adjusted to divide the length exactly and the samples go once around starting at
// `origin` (max_before/max_after ignored; *origin_index = 0).
std::vector<cv::Point2f> ResamplePolyline(const std::vector<cv::Point2f>& points, bool closed,
                                          double spacing, double origin, int max_before,
                                          int max_after, int* origin_index);

// The arc length at each vertex of a polyline, plus its total length (closing segment included
// when `closed`) as the last element; n + 1 values. `cumulative[i]` equals ArcLengthAt(points, i)
// and `cumulative.back()` PolylineLength(points, closed), bit for bit.
void PolylineArcLengths(const std::vector<cv::Point2f>& points, bool closed,
                        std::vector<double>* cumulative);
// ResamplePolyline given the polyline's PolylineArcLengths, for callers that also need the
// lengths: the arc lengths are then computed once.
std::vector<cv::Point2f> ResamplePolyline(const std::vector<cv::Point2f>& points,
                                          const std::vector<double>& cumulative, bool closed,
                                          double spacing, double origin, int max_before,
                                          int max_after, int* origin_index);

// Arc length along the polyline of the point of the polyline nearest to `query`.
double ProjectOntoPolyline(const std::vector<cv::Point2f>& points, bool closed,
                           const cv::Point2f& query);

// Arc length of vertex `index` along the polyline.
double ArcLengthAt(const std::vector<cv::Point2f>& points, int index);

}  // namespace comic::frontend
