// Synthetic test images with known answers for the CoMIC tests: polygons with sub-pixel vertices,
// blurred by a known Gaussian, on flat or textured backgrounds. Header-only, test code only.
#pragma once

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace comic::test {

struct Polygon {
  std::vector<cv::Point2d> vertices;  // pixel coordinates, OpenCV centre convention
  double intensity = 200.0;
};

// The polygon translated by (dx, dy).
inline Polygon Translated(Polygon polygon, double dx, double dy) {
  for (cv::Point2d& v : polygon.vertices) v += cv::Point2d(dx, dy);
  return polygon;
}

inline Polygon MakeSquare(cv::Point2d corner, double side, double intensity) {
  return {{corner, corner + cv::Point2d(side, 0), corner + cv::Point2d(side, side),
           corner + cv::Point2d(0, side)},
          intensity};
}

// An L: a `size` square with its top-right `notch` square removed (one reflex vertex).
inline Polygon MakeL(cv::Point2d corner, double size, double notch, double intensity) {
  const double x = corner.x, y = corner.y;
  return {{{x, y},
           {x + size - notch, y},
           {x + size - notch, y + notch},
           {x + size, y + notch},
           {x + size, y + size},
           {x, y + size}},
          intensity};
}

// A T: a bar of width `width` and height `bar` on top of a centred stem of width `stem`.
inline Polygon MakeT(cv::Point2d corner, double width, double bar, double stem, double height,
                     double intensity) {
  const double x = corner.x, y = corner.y;
  const double s0 = x + (width - stem) / 2, s1 = s0 + stem;
  return {{{x, y},
           {x + width, y},
           {x + width, y + bar},
           {s1, y + bar},
           {s1, y + height},
           {s0, y + height},
           {s0, y + bar},
           {x, y + bar}},
          intensity};
}

inline Polygon MakeTriangle(cv::Point2d a, cv::Point2d b, cv::Point2d c, double intensity) {
  return {{a, b, c}, intensity};
}

// A smooth random texture in [low, high]: uniform noise on a grid `cell` px apart, interpolated
// bicubically (clamped). Deterministic for a given seed.
inline cv::Mat TexturedBackground(cv::Size size, uint64_t seed, double low, double high,
                                  int cell = 4) {
  cv::RNG rng(seed);
  cv::Mat coarse(size.height / cell + 3, size.width / cell + 3, CV_32F);
  rng.fill(coarse, cv::RNG::UNIFORM, low, high);
  cv::Mat fine;
  cv::resize(coarse, fine, cv::Size(coarse.cols * cell, coarse.rows * cell), 0, 0, cv::INTER_CUBIC);
  cv::Mat out = fine(cv::Rect(cell, cell, size.width, size.height)).clone();
  cv::min(cv::max(out, low), high, out);
  return out;
}

inline cv::Mat FlatBackground(cv::Size size, double value) {
  return cv::Mat(size, CV_32F, cv::Scalar(value));
}

// Renders the polygons (even-odd rule, in order, later ones on top) over `background` (CV_32F),
// then blurs with a Gaussian of `blur_sigma` px and returns an 8-bit image. Rendering is
// supersampled 8x in y, with exact coverage in x, then integrated over each pixel's area.
inline cv::Mat RenderPolygons(const cv::Mat& background, const std::vector<Polygon>& polygons,
                              double blur_sigma) {
  constexpr int kS = 8;
  const int w = background.cols, h = background.rows;
  cv::Mat canvas;
  cv::resize(background, canvas, cv::Size(w * kS, h * kS), 0, 0, cv::INTER_NEAREST);
  for (const Polygon& polygon : polygons) {
    const size_t n = polygon.vertices.size();
    for (int j = 0; j < h * kS; ++j) {
      const double y = (j + 0.5) / kS - 0.5;
      std::vector<double> xs;
      for (size_t e = 0; e < n; ++e) {
        const cv::Point2d a = polygon.vertices[e];
        const cv::Point2d b = polygon.vertices[(e + 1) % n];
        if ((a.y <= y) == (b.y <= y)) continue;
        xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
      }
      std::sort(xs.begin(), xs.end());
      float* row = canvas.ptr<float>(j);
      for (size_t s = 0; s + 1 < xs.size(); s += 2) {
        // Supersample i covers x in [(i)/kS - 0.5, (i + 1)/kS - 0.5): blend by covered fraction.
        const double u0 = (xs[s] + 0.5) * kS;
        const double u1 = (xs[s + 1] + 0.5) * kS;
        for (int i = std::max(0, static_cast<int>(std::floor(u0)));
             i < std::min(w * kS, static_cast<int>(std::ceil(u1))); ++i) {
          const double covered = std::min(u1, i + 1.0) - std::max(u0, static_cast<double>(i));
          if (covered <= 0) continue;
          row[i] = static_cast<float>(row[i] + covered * (polygon.intensity - row[i]));
        }
      }
    }
  }
  if (blur_sigma > 0) {
    const double sigma = blur_sigma * kS;
    const int ksize = 2 * static_cast<int>(std::ceil(4 * sigma)) + 1;
    cv::GaussianBlur(canvas, canvas, cv::Size(ksize, ksize), sigma, sigma, cv::BORDER_REPLICATE);
  }
  cv::Mat small;
  cv::resize(canvas, small, cv::Size(w, h), 0, 0, cv::INTER_AREA);
  cv::Mat out;
  small.convertTo(out, CV_8U);  // rounds and saturates
  return out;
}

}  // namespace comic::test
