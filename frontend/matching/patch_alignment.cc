#include "frontend/matching/patch_alignment.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "io/core/error.h"

namespace comic::frontend {

void PatchAlignmentOptions::Check() const {
  COMIC_CHECK(levels >= 0 && levels <= 8, kInvalidArgument,
              "patch alignment: levels must be in [0, 8], got " << levels);
  COMIC_CHECK(window >= 5 && window % 2 == 1, kInvalidArgument,
              "patch alignment: window must be odd and >= 5, got " << window);
  COMIC_CHECK(max_iterations >= 1, kInvalidArgument,
              "patch alignment: max_iterations must be >= 1, got " << max_iterations);
  COMIC_CHECK(min_step_px > 0, kInvalidArgument, "patch alignment: min_step_px must be > 0");
  COMIC_CHECK(min_eigenvalue >= 0, kInvalidArgument,
              "patch alignment: min_eigenvalue must be >= 0");
  COMIC_CHECK(max_forward_backward_px >= 0, kInvalidArgument,
              "patch alignment: max_forward_backward_px must be >= 0");
  COMIC_CHECK(
      min_gain > 0 && max_gain >= min_gain, kInvalidArgument,
      "patch alignment: needs 0 < min_gain <= max_gain, got " << min_gain << ", " << max_gain);
}

ImagePyramid::ImagePyramid(const cv::Mat& gray, int levels, int window) {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "image pyramid: the image must be a non-empty 8-bit single-channel image");
  cv::Mat level;
  gray.convertTo(level, CV_32F);
  levels_.push_back(level);
  for (int l = 1; l <= levels; ++l) {
    const cv::Mat& below = levels_.back();
    if (below.cols < 2 * kPatchSize || below.rows < 2 * kPatchSize) break;
    cv::Mat half;
    cv::pyrDown(below, half);
    levels_.push_back(half);
  }
  cv::buildOpticalFlowPyramid(gray, flow_levels_, cv::Size(window, window), NumLevels() - 1,
                              /*withDerivatives=*/false);
}

AlignmentWeights SideWeights(const std::vector<PatchSide>& side_mask, PatchSide side) {
  COMIC_CHECK(side_mask.size() == static_cast<size_t>(kPatchSize * kPatchSize), kInvalidArgument,
              "side weights: a side mask has " << kPatchSize * kPatchSize << " labels, got "
                                               << side_mask.size());
  AlignmentWeights weights(side_mask.size());
  for (size_t k = 0; k < side_mask.size(); ++k) weights[k] = side_mask[k] == side ? 1.0f : 0.0f;
  return weights;
}

namespace {

// The window×window grid of a CV_32F image with its top-left sample at (x, y), bilinear: a
// translation shares one pair of fractions over the whole window, so the weights are computed
// once; samples beyond the border take the border's value.
void SampleWindow(const cv::Mat& image, float x, float y, int window, float* out) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const float ax = x - fx, ay = y - fy;
  const float w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay, w11 = ax * ay;
  const bool inside = x0 >= 0 && y0 >= 0 && x0 + window < image.cols && y0 + window < image.rows;
  if (inside) {
    for (int v = 0; v < window; ++v) {
      const float* r0 = image.ptr<float>(y0 + v) + x0;
      const float* r1 = image.ptr<float>(y0 + v + 1) + x0;
      float* o = out + v * window;
      for (int u = 0; u < window; ++u) {
        o[u] = w00 * r0[u] + w01 * r0[u + 1] + w10 * r1[u] + w11 * r1[u + 1];
      }
    }
    return;
  }
  const int max_x = image.cols - 1, max_y = image.rows - 1;
  for (int v = 0; v < window; ++v) {
    const int ya = std::clamp(y0 + v, 0, max_y), yb = std::clamp(y0 + v + 1, 0, max_y);
    const float* r0 = image.ptr<float>(ya);
    const float* r1 = image.ptr<float>(yb);
    for (int u = 0; u < window; ++u) {
      const int xa = std::clamp(x0 + u, 0, max_x), xb = std::clamp(x0 + u + 1, 0, max_x);
      out[v * window + u] = w00 * r0[xa] + w01 * r0[xb] + w10 * r1[xa] + w11 * r1[xb];
    }
  }
}

// The template of one level: values and gradients over the window, and the weights (buffers
// owned by the caller's workspace).
struct Template {
  // Padded to whole lanes (kLanes, below) with zero weight.
  std::vector<float> weights, values, gx, gy;
  float weight_sum = 0, mean = 0, variance = 0;
  float hxx = 0, hxy = 0, hyy = 0;  // weighted gradient moments (sums)
};

void MakeTemplate(const cv::Mat& image, cv::Point2f centre, int window, const float* weights,
                  std::vector<float>* grid, Template* t) {
  const int r = window / 2, side = window + 2, n = window * window;
  const int padded = (n + 7) / 8 * 8;
  grid->resize(side * side);
  SampleWindow(image, centre.x - r - 1, centre.y - r - 1, side, grid->data());
  t->weights.assign(padded, 0.0f);
  for (int k = 0; k < n; ++k) t->weights[k] = weights == nullptr ? 1.0f : weights[k];
  t->values.assign(padded, 0.0f);
  t->gx.assign(padded, 0.0f);
  t->gy.assign(padded, 0.0f);
  float weight_sum = 0, sum = 0, sum2 = 0, hxx = 0, hxy = 0, hyy = 0;
  const float* g = grid->data();
  for (int v = 0; v < window; ++v) {
    for (int u = 0; u < window; ++u) {
      const int k = v * window + u, c = (v + 1) * side + (u + 1);
      const float value = g[c];
      const float gx = 0.5f * (g[c + 1] - g[c - 1]);
      const float gy = 0.5f * (g[c + side] - g[c - side]);
      t->values[k] = value;
      t->gx[k] = gx;
      t->gy[k] = gy;
      const float w = t->weights[k];
      weight_sum += w;
      sum += w * value;
      sum2 += w * value * value;
      hxx += w * gx * gx;
      hxy += w * gx * gy;
      hyy += w * gy * gy;
    }
  }
  t->weight_sum = weight_sum;
  t->hxx = hxx;
  t->hxy = hxy;
  t->hyy = hyy;
  t->mean = weight_sum > 0 ? sum / weight_sum : 0.0f;
  t->variance = weight_sum > 0 ? std::max(0.0f, sum2 / weight_sum - t->mean * t->mean) : 0.0f;
}

// Smallest eigenvalue of the mean gradient moment matrix.
double MinEigenvalue(double hxx, double hxy, double hyy, double weight_sum) {
  if (weight_sum <= 0) return 0;
  const double a = hxx / weight_sum, b = hxy / weight_sum, c = hyy / weight_sum;
  return 0.5 * (a + c - std::sqrt((a - c) * (a - c) + 4 * b * b));
}

// Frame 2 over the window against the template: the closed-form gain and bias, the mean squared
// residual, the correlation, and the residual's products with the template gradients.
struct Comparison {
  float gain = 1, bias = 0, mean_square = 0, correlation = 0;
  float bx = 0, by = 0;  // Σ w·r·∇T
};

// Weighted sums over the window in kLanes independent partial sums, added in a fixed order at
// the end: the compiler can keep the lanes in vector registers (the result does not depend on
// how it does), where one running float sum would have to be added pixel by pixel.
constexpr int kLanes = 8;

float AddLanes(const float* lanes) {
  float total = 0;
  for (int j = 0; j < kLanes; ++j) total += lanes[j];
  return total;
}

Comparison Compare(const Template& t, const cv::Mat& image, cv::Point2f centre, int window,
                   std::vector<float>* samples) {
  const int r = window / 2, n = window * window;
  // Padded to whole lanes with zero weight.
  const int padded = (n + kLanes - 1) / kLanes * kLanes;
  samples->assign(padded, 0.0f);
  float* w2 = samples->data();
  SampleWindow(image, centre.x - r, centre.y - r, window, w2);
  Comparison c;
  if (t.weight_sum <= 0) return c;
  const float* w = t.weights.data();
  const float* tv = t.values.data();
  float sum[kLanes] = {}, sum2[kLanes] = {}, cross[kLanes] = {};
  for (int k = 0; k < padded; k += kLanes) {
    for (int j = 0; j < kLanes; ++j) {
      const float ww = w[k + j] * w2[k + j];
      sum[j] += ww;
      sum2[j] += ww * w2[k + j];
      cross[j] += ww * (tv[k + j] - t.mean);
    }
  }
  const float mean2 = AddLanes(sum) / t.weight_sum;
  const float cross_total = AddLanes(cross);
  const float variance2 = std::max(0.0f, AddLanes(sum2) / t.weight_sum - mean2 * mean2);
  // Least squares of w2 ≈ gain·T + bias; a flat template keeps gain 1.
  c.gain = t.variance > 1e-6f ? cross_total / (t.weight_sum * t.variance) : 1.0f;
  c.bias = mean2 - c.gain * t.mean;
  c.correlation = t.variance > 1e-6f && variance2 > 1e-6f
                      ? cross_total / (t.weight_sum * std::sqrt(t.variance * variance2))
                      : 0.0f;
  const float* gx = t.gx.data();
  const float* gy = t.gy.data();
  float square[kLanes] = {}, bx[kLanes] = {}, by[kLanes] = {};
  for (int k = 0; k < padded; k += kLanes) {
    for (int j = 0; j < kLanes; ++j) {
      const float residual = w2[k + j] - (c.gain * tv[k + j] + c.bias);
      const float wr = w[k + j] * residual;
      square[j] += wr * residual;
      bx[j] += wr * gx[k + j];
      by[j] += wr * gy[k + j];
    }
  }
  c.mean_square = AddLanes(square) / t.weight_sum;
  c.bx = AddLanes(bx);
  c.by = AddLanes(by);
  return c;
}

bool Inside(cv::Point2f p, const cv::Mat& image, int margin) {
  return p.x >= margin && p.y >= margin && p.x <= image.cols - 1 - margin &&
         p.y <= image.rows - 1 - margin;
}

}  // namespace

double WindowMinEigenvalue(const cv::Mat& gray, cv::Point2f point, int window) {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "window eigenvalue: the image must be a non-empty 8-bit single-channel image");
  const int r = window / 2;
  const int cx = static_cast<int>(std::lround(point.x)),
            cy = static_cast<int>(std::lround(point.y));
  auto at = [&](int x, int y) {
    return static_cast<double>(
        gray.at<uint8_t>(std::clamp(y, 0, gray.rows - 1), std::clamp(x, 0, gray.cols - 1)));
  };
  double hxx = 0, hxy = 0, hyy = 0;
  for (int y = cy - r; y <= cy + r; ++y) {
    for (int x = cx - r; x <= cx + r; ++x) {
      const double gx = 0.5 * (at(x + 1, y) - at(x - 1, y));
      const double gy = 0.5 * (at(x, y + 1) - at(x, y - 1));
      hxx += gx * gx;
      hxy += gx * gy;
      hyy += gy * gy;
    }
  }
  return MinEigenvalue(hxx, hxy, hyy, static_cast<double>(window) * window);
}

PatchAlignment AlignPatch(const ImagePyramid& pyramid1, cv::Point2f point,
                          const ImagePyramid& pyramid2, cv::Point2f guess,
                          const AlignmentWeights& weights, const PatchAlignmentOptions& options) {
  options.Check();
  COMIC_CHECK(pyramid1.NumLevels() > 0 && pyramid1.NumLevels() == pyramid2.NumLevels() &&
                  pyramid1.Size() == pyramid2.Size(),
              kInvalidArgument, "patch alignment: the pyramids differ in size or levels");
  const int window = options.window;
  COMIC_CHECK(weights.empty() || weights.size() == static_cast<size_t>(window * window),
              kInvalidArgument,
              "patch alignment: " << weights.size() << " weights for a " << window << "x" << window
                                  << " window");
  const float* w = weights.empty() ? nullptr : weights.data();
  std::vector<float> grid, samples;
  Template t;
  PatchAlignment result;
  const int top = std::min(options.levels, pyramid1.NumLevels() - 1);
  cv::Point2f d = (guess - point) * (1.0f / static_cast<float>(1 << top));
  const float max_step = 0.25f * window;
  const float min_step2 = static_cast<float>(options.min_step_px * options.min_step_px);
  for (int l = top; l >= 0; --l) {
    const float scale = 1.0f / static_cast<float>(1 << l);
    const cv::Point2f p1 = point * scale;
    MakeTemplate(pyramid1.Level(l), p1, window, w, &grid, &t);
    // A window too weak to fix both coordinates keeps the displacement of the level above; at
    // the finest level it cannot be aligned at all.
    const bool weak = MinEigenvalue(t.hxx, t.hxy, t.hyy, t.weight_sum) < options.min_eigenvalue;
    if (l == 0 && weak) return result;
    const float det = t.hxx * t.hyy - t.hxy * t.hxy;
    const cv::Mat& image2 = pyramid2.Level(l);
    for (int it = 0; it < options.max_iterations && !weak && det > 1e-6f; ++it) {
      if (!Inside(p1 + d, image2, 0)) return result;
      const Comparison c = Compare(t, image2, p1 + d, window, &samples);
      // Gauss–Newton on w2(d + δ) ≈ gain·T + bias with ∇w2 ≈ gain·∇T:
      // δ = −(gain² H)⁻¹ · gain·b = −H⁻¹ b / gain.
      const float g = std::max(c.gain, 1e-3f);
      cv::Point2f step(-(t.hyy * c.bx - t.hxy * c.by) / (det * g),
                       -(t.hxx * c.by - t.hxy * c.bx) / (det * g));
      // Far from the optimum the linearisation is poor: no step longer than a quarter window.
      const float length = std::sqrt(step.dot(step));
      if (length > max_step) step *= max_step / length;
      d += step;
      if (step.dot(step) < min_step2) break;
    }
    if (l > 0) d *= 2.0f;
  }
  const cv::Mat& base2 = pyramid2.Level(0);
  const cv::Point2f position = point + d;
  if (!Inside(position, base2, window / 2)) return result;
  // t is the finest level's template.
  const Comparison c = Compare(t, base2, position, window, &samples);
  if (c.gain < options.min_gain || c.gain > options.max_gain) return result;
  result.converged = true;
  result.position = position;
  result.residual = c.mean_square;
  result.gain = c.gain;
  result.bias = c.bias;
  result.correlation = c.correlation;
  if (pyramid1.NumLevels() > 1) {
    MakeTemplate(pyramid1.Level(1), point * 0.5f, window, w, &grid, &t);
    result.coarse_correlation =
        Compare(t, pyramid2.Level(1), position * 0.5f, window, &samples).correlation;
  }
  return result;
}

}  // namespace comic::frontend
