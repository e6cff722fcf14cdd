// Test scenes with known corners for the CoMIC detectors: four rendered polygons (21 vertices:
// convex, reflex, acute, at sub-pixel positions) on a flat or a textured background, and helpers
// to compare features with the vertices and with each other.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "frontend/feature.h"
#include "tests/frontend/synthetic_images.h"

namespace comic::test {

using frontend::Feature;
using frontend::FeatureSet;

// A square, an L, a T and a triangle at sub-pixel positions, shifted by (dx, dy).
inline std::vector<Polygon> Shapes(double dx = 0.0, double dy = 0.0) {
  std::vector<Polygon> shapes = {MakeSquare({30.3, 35.6}, 40, 200),
                                 MakeL({110.2, 30.7}, 60, 25, 190),
                                 MakeTriangle({40.4, 170.2}, {100.6, 160.3}, {60.1, 100.8}, 215),
                                 MakeT({115.3, 110.4}, 60, 18, 20, 60, 180)};
  for (Polygon& p : shapes) p = Translated(p, dx, dy);
  return shapes;
}

inline std::vector<cv::Point2d> Vertices(const std::vector<Polygon>& shapes) {
  std::vector<cv::Point2d> vertices;
  for (const Polygon& p : shapes) {
    vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
  }
  return vertices;
}

// The feature nearest to `point`, or null if there is none.
inline const Feature* Nearest(const FeatureSet& features, const cv::Point2d& point) {
  const Feature* best = nullptr;
  double best_distance = 1e300;
  for (const Feature& f : features) {
    const double d = std::hypot(f.x - point.x, f.y - point.y);
    if (d < best_distance) {
      best_distance = d;
      best = &f;
    }
  }
  return best;
}

inline double Distance(const Feature* f, const cv::Point2d& point) {
  return f == nullptr ? 1e300 : std::hypot(f->x - point.x, f->y - point.y);
}

inline const cv::Size kSceneSize(200, 200);

inline cv::Mat FlatScene(double dx = 0.0, double dy = 0.0) {
  return RenderPolygons(FlatBackground(kSceneSize, 50), Shapes(dx, dy), 1.0);
}

// Random texture of 90 grey levels at an 8 px scale behind the shapes. Finer texture right at a
// blurred boundary moves a level line by up to ~0.5 px along it (docs/comic_detector.md).
inline cv::Mat TexturedScene(uint64_t seed) {
  return RenderPolygons(TexturedBackground(kSceneSize, seed, 20, 110, 8), Shapes(), 1.0);
}

// Every field of every feature equal, in the same order.
inline void ExpectIdentical(const FeatureSet& a, const FeatureSet& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x, b[i].x);
    EXPECT_EQ(a[i].y, b[i].y);
    EXPECT_EQ(a[i].scale, b[i].scale);
    EXPECT_EQ(a[i].response, b[i].response);
    EXPECT_EQ(a[i].cornerness, b[i].cornerness);
    EXPECT_EQ(a[i].level, b[i].level);
    EXPECT_EQ(a[i].polarity, b[i].polarity);
    EXPECT_EQ(a[i].side_mask, b[i].side_mask);
    EXPECT_EQ(a[i].curve, b[i].curve);
  }
}

}  // namespace comic::test
