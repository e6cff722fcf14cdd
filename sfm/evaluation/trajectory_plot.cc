#include "sfm/evaluation/trajectory_plot.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::sfm {

PlotPlane PlotPlaneFromAxes(int right_axis, int up_axis) {
  COMIC_CHECK(
      right_axis >= 0 && right_axis < 3 && up_axis >= 0 && up_axis < 3 && right_axis != up_axis,
      kInvalidArgument,
      "plot axes must be two different indices in 0..2, got " << right_axis << ", " << up_axis);
  const char* names[] = {"x", "y", "z"};
  PlotPlane plane;
  plane.right = Eigen::Vector3d::Unit(right_axis);
  plane.up = Eigen::Vector3d::Unit(up_axis);
  plane.right_label = names[right_axis];
  plane.up_label = names[up_axis];
  return plane;
}

PlotPlane PlotPlaneFromCenters(const std::vector<Eigen::Vector3d>& centers) {
  if (centers.size() < 3) return PlotPlaneFromAxes(0, 2);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& c : centers) mean += c;
  mean /= static_cast<double>(centers.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& c : centers) covariance += (c - mean) * (c - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  // Eigenvalues ascending: the last two span the plane of largest spread.
  PlotPlane plane;
  plane.right = solver.eigenvectors().col(2);
  plane.up = solver.eigenvectors().col(1);
  // Fix the signs so the view does not flip with round-off: the largest component positive.
  for (Eigen::Vector3d* axis : {&plane.right, &plane.up}) {
    int largest = 0;
    axis->cwiseAbs().maxCoeff(&largest);
    if ((*axis)(largest) < 0) *axis = -*axis;
  }
  plane.right_label = "principal axis 1";
  plane.up_label = "principal axis 2";
  return plane;
}

void TrajectoryPlotOptions::Check() const {
  COMIC_CHECK(width >= 200 && height >= 200, kInvalidArgument,
              "trajectory plot must be at least 200x200 pixels");
}

cv::Mat RenderTrajectoryPlot(const std::vector<std::optional<Eigen::Vector3d>>& estimated_centers,
                             const std::vector<std::optional<Eigen::Vector3d>>& true_centers,
                             const PlotPlane& plane, const TrajectoryPlotOptions& options) {
  options.Check();
  const auto to_plane = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(plane.right.dot(p), plane.up.dot(p));
  };
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d high = Eigen::Vector2d::Constant(std::numeric_limits<double>::lowest());
  for (const auto* centers : {&estimated_centers, &true_centers}) {
    for (const auto& c : *centers) {
      if (!c) continue;
      low = low.cwiseMin(to_plane(*c));
      high = high.cwiseMax(to_plane(*c));
    }
  }
  cv::Mat image(options.height, options.width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int margin_top = 60, margin = 50;
  if (low.x() > high.x()) {
    cv::putText(image, "no camera positions", {margin, options.height / 2},
                cv::FONT_HERSHEY_SIMPLEX, 0.7, {0, 0, 0}, 1, cv::LINE_AA);
    return image;
  }
  const double extent = std::max({high.x() - low.x(), high.y() - low.y(), 1e-9});
  const double scale = std::min(options.width - 2 * margin, options.height - margin - margin_top) /
                       extent;  // pixels per world unit, equal on both axes
  const Eigen::Vector2d middle = 0.5 * (low + high);
  const auto to_pixel = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d q = to_plane(p) - middle;
    return cv::Point2d(options.width / 2.0 + scale * q.x(),
                       margin_top + (options.height - margin - margin_top) / 2.0 - scale * q.y());
  };
  constexpr int kShift = 4;  // sub-pixel drawing
  const auto fixed = [&](const cv::Point2d& p) {
    return cv::Point(static_cast<int>(std::lround(p.x * (1 << kShift))),
                     static_cast<int>(std::lround(p.y * (1 << kShift))));
  };
  const cv::Scalar kEstimated(30, 30, 210), kTrue(150, 215, 150), kError(120, 120, 120);
  const size_t n = std::max(estimated_centers.size(), true_centers.size());
  const auto at = [](const std::vector<std::optional<Eigen::Vector3d>>& v, size_t i) {
    return i < v.size() ? v[i] : std::nullopt;
  };
  for (size_t i = 0; i < n; ++i) {
    if (at(estimated_centers, i) && at(true_centers, i)) {
      cv::line(image, fixed(to_pixel(*at(estimated_centers, i))),
               fixed(to_pixel(*at(true_centers, i))), kError, 1, cv::LINE_AA, kShift);
    }
  }
  // The truth broad and light underneath, the estimate thin on top, so both stay visible where
  // they coincide.
  struct Style {
    const std::vector<std::optional<Eigen::Vector3d>>* centers;
    cv::Scalar color;
    int thickness;
    int radius;
  };
  for (const Style& style :
       {Style{&true_centers, kTrue, 6, 5}, Style{&estimated_centers, kEstimated, 1, 2}}) {
    std::optional<cv::Point2d> previous;
    for (const auto& center : *style.centers) {
      if (!center) {
        previous.reset();
        continue;
      }
      const cv::Point2d p = to_pixel(*center);
      if (previous) {
        cv::line(image, fixed(*previous), fixed(p), style.color, style.thickness, cv::LINE_AA,
                 kShift);
      }
      cv::circle(image, fixed(p), style.radius << kShift, style.color, cv::FILLED, cv::LINE_AA,
                 kShift);
      previous = p;
    }
  }
  // First frame marked with a ring.
  for (const auto* centers : {&true_centers, &estimated_centers}) {
    for (const auto& c : *centers) {
      if (c) {
        cv::circle(image, fixed(to_pixel(*c)), 7 << kShift, {0, 0, 0}, 1, cv::LINE_AA, kShift);
        break;
      }
    }
  }

  // Scale bar: the largest 1-2-5 step that fits a quarter of the width.
  const double target = (options.width - 2 * margin) / 4.0 / scale;
  const double power = std::pow(10.0, std::floor(std::log10(target)));
  double step = power;
  for (double factor : {2.0, 5.0, 10.0}) {
    if (factor * power <= target) step = factor * power;
  }
  const int bar = static_cast<int>(std::lround(step * scale));
  const int y_bar = options.height - 20;
  cv::line(image, {margin, y_bar}, {margin + bar, y_bar}, {0, 0, 0}, 2);
  char label[64];
  std::snprintf(label, sizeof(label), "%g units", step);
  cv::putText(image, label, {margin + bar + 8, y_bar + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0},
              1, cv::LINE_AA);
  const std::string axes = "right: " + plane.right_label + ", up: " + plane.up_label;
  cv::putText(image, axes, {options.width - margin - 8 * static_cast<int>(axes.size()), y_bar + 5},
              cv::FONT_HERSHEY_SIMPLEX, 0.45, {80, 80, 80}, 1, cv::LINE_AA);

  // Title and legend.
  cv::putText(image, options.title, {margin, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.6, {0, 0, 0}, 1,
              cv::LINE_AA);
  int x = margin;
  const bool has_truth = std::any_of(true_centers.begin(), true_centers.end(),
                                     [](const auto& c) { return c.has_value(); });
  for (const auto& [text, color] :
       {std::make_pair(std::string(has_truth ? "estimated (Sim(3)-aligned)" : "estimated"),
                       kEstimated),
        std::make_pair(std::string(has_truth ? "ground truth" : ""), kTrue)}) {
    if (text.empty()) continue;
    cv::circle(image, {x + 5, 45}, 5, color, cv::FILLED, cv::LINE_AA);
    cv::putText(image, text, {x + 15, 50}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1,
                cv::LINE_AA);
    x += 15 + 9 * static_cast<int>(text.size()) + 20;
  }
  return image;
}

}  // namespace comic::sfm
