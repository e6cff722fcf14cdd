#include "sfm/evaluation/trajectory_plot.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
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

namespace {

using Centers = std::vector<std::optional<Eigen::Vector3d>>;

const cv::Scalar kEstimated(30, 30, 210), kTrue(150, 215, 150), kError(120, 120, 120);
const cv::Scalar kUnregistered(0, 160, 240), kGrid(232, 232, 232), kInk(0, 0, 0);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kShift = 4;  // sub-pixel drawing

int TextWidth(const std::string& text, double scale) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, 1, &baseline).width;
}

void Text(cv::Mat* image, const std::string& text, cv::Point origin, double scale,
          const cv::Scalar& color = kInk) {
  cv::putText(*image, text, origin, kFont, scale, color, 1, cv::LINE_AA);
}

// `text` in lines at most `width` pixels wide: broken at spaces, and inside words (paths) that
// are wider than a line.
std::vector<std::string> WrapText(const std::string& text, double scale, int width) {
  std::vector<std::string> lines(1);
  std::string word;
  const auto place = [&](const std::string& w) {
    const std::string joined = lines.back().empty() ? w : lines.back() + " " + w;
    if (TextWidth(joined, scale) <= width || lines.back().empty()) {
      lines.back() = joined;
    } else {
      lines.push_back(w);
    }
    while (TextWidth(lines.back(), scale) > width && lines.back().size() > 1) {
      size_t cut = lines.back().size() - 1;
      while (cut > 1 && TextWidth(lines.back().substr(0, cut), scale) > width) --cut;
      const std::string rest = lines.back().substr(cut);
      lines.back().resize(cut);
      lines.push_back(rest);
    }
  };
  for (char c : text + " ") {
    if (c != ' ') {
      word += c;
    } else if (!word.empty()) {
      place(word);
      word.clear();
    }
  }
  return lines;
}

// The largest 1-2-5 step giving at least `count` intervals over `extent`.
double TickStep(double extent, int count) {
  const double raw = extent / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double factor : {1.0, 2.0, 5.0}) {
    if (factor * power >= raw) return factor * power;
  }
  return 10.0 * power;
}

std::string TickLabel(double value, double step) {
  const int digits = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", std::min(digits, 6),
                std::abs(value) < step * 1e-9 ? 0.0 : value);
  return text;
}

// The plot area and the map from the plane to its pixels, equal scale on both axes.
struct PlotFrame {
  cv::Rect area;
  Eigen::Vector2d middle;
  double scale = 1.0;  // pixels per unit
  cv::Point2d ToPixel(const Eigen::Vector2d& q) const {
    return {area.x + area.width / 2.0 + scale * (q.x() - middle.x()),
            area.y + area.height / 2.0 - scale * (q.y() - middle.y())};
  }
  Eigen::Vector2d ToPlane(double x, double y) const {
    return {middle.x() + (x - area.x - area.width / 2.0) / scale,
            middle.y() - (y - area.y - area.height / 2.0) / scale};
  }
};

cv::Point Fixed(const cv::Point2d& p) {
  return cv::Point(static_cast<int>(std::lround(p.x * (1 << kShift))),
                   static_cast<int>(std::lround(p.y * (1 << kShift))));
}

// Grid, ticks and their labels on the left and bottom edges, the axis names with the unit, and
// a scale bar of one grid step.
void DrawAxes(const PlotFrame& frame, const PlotPlane& plane, const std::string& unit,
              cv::Mat* image) {
  const cv::Rect& a = frame.area;
  const Eigen::Vector2d low = frame.ToPlane(a.x, a.y + a.height);
  const Eigen::Vector2d high = frame.ToPlane(a.x + a.width, a.y);
  const double step = TickStep(std::max(high.x() - low.x(), high.y() - low.y()), 8);
  for (double v = std::ceil(low.x() / step) * step; v <= high.x(); v += step) {
    const int x = static_cast<int>(std::lround(frame.ToPixel({v, low.y()}).x));
    cv::line(*image, {x, a.y}, {x, a.y + a.height}, kGrid, 1);
    cv::line(*image, {x, a.y + a.height}, {x, a.y + a.height + 5}, kInk, 1);
    const std::string label = TickLabel(v, step);
    Text(image, label, {x - TextWidth(label, 0.4) / 2, a.y + a.height + 19}, 0.4);
  }
  for (double v = std::ceil(low.y() / step) * step; v <= high.y(); v += step) {
    const int y = static_cast<int>(std::lround(frame.ToPixel({low.x(), v}).y));
    cv::line(*image, {a.x, y}, {a.x + a.width, y}, kGrid, 1);
    cv::line(*image, {a.x - 5, y}, {a.x, y}, kInk, 1);
    const std::string label = TickLabel(v, step);
    Text(image, label, {a.x - 8 - TextWidth(label, 0.4), y + 4}, 0.4);
  }
  cv::rectangle(*image, a, kInk, 1);
  const std::string right = plane.right_label + " (" + unit + ")";
  Text(image, right, {a.x + a.width / 2 - TextWidth(right, 0.45) / 2, a.y + a.height + 38}, 0.45);
  Text(image, plane.up_label + " (" + unit + ")", {4, a.y - 8}, 0.45);
  const int bar = static_cast<int>(std::lround(step * frame.scale));
  const int y_bar = image->rows - 14;
  cv::line(*image, {a.x, y_bar}, {a.x + bar, y_bar}, kInk, 3);
  Text(image, TickLabel(step, step) + " " + unit + " (one grid step, equal scale on both axes)",
       {a.x + bar + 8, y_bar + 5}, 0.45);
}

// The grey error segments, the truth broad and light underneath, the estimate thin on top (so
// both stay visible where they coincide), first frames ringed, unregistered frames crossed.
void DrawPaths(const PlotFrame& frame, const PlotPlane& plane, const Centers& estimated,
               const Centers& truth, cv::Mat* image) {
  const auto pixel = [&](const Eigen::Vector3d& p) {
    return frame.ToPixel({plane.right.dot(p), plane.up.dot(p)});
  };
  const auto at = [](const Centers& v, size_t i) { return i < v.size() ? v[i] : std::nullopt; };
  const size_t n = std::max(estimated.size(), truth.size());
  for (size_t i = 0; i < n; ++i) {
    if (at(estimated, i) && at(truth, i)) {
      cv::line(*image, Fixed(pixel(*at(estimated, i))), Fixed(pixel(*at(truth, i))), kError, 1,
               cv::LINE_AA, kShift);
    }
  }
  const std::pair<const Centers*, std::array<int, 2>> styles[] = {{&truth, {6, 5}},
                                                                  {&estimated, {1, 2}}};
  for (const auto& [centers, style] : styles) {
    const cv::Scalar color = centers == &truth ? kTrue : kEstimated;
    bool joined = false;  // the previous frame had a centre
    cv::Point2d previous;
    for (const auto& center : *centers) {
      if (!center) {
        joined = false;
        continue;
      }
      const cv::Point2d p = pixel(*center);
      if (joined) cv::line(*image, Fixed(previous), Fixed(p), color, style[0], cv::LINE_AA, kShift);
      cv::circle(*image, Fixed(p), style[1] << kShift, color, cv::FILLED, cv::LINE_AA, kShift);
      previous = p;
      joined = true;
    }
    for (const auto& c : *centers) {
      if (c) {
        cv::circle(*image, Fixed(pixel(*c)), 7 << kShift, kInk, 1, cv::LINE_AA, kShift);
        break;
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (at(estimated, i) || !at(truth, i)) continue;
    const cv::Point p = Fixed(pixel(*at(truth, i)));
    const int r = 5 << kShift;
    cv::line(*image, p + cv::Point(-r, -r), p + cv::Point(r, r), kUnregistered, 2, cv::LINE_AA,
             kShift);
    cv::line(*image, p + cv::Point(-r, r), p + cv::Point(r, -r), kUnregistered, 2, cv::LINE_AA,
             kShift);
  }
}

// The legend line: what the colours are, and how many frames have no estimate.
int DrawLegend(const Centers& estimated, const Centers& truth, int y, cv::Mat* image) {
  const bool has_truth =
      std::any_of(truth.begin(), truth.end(), [](const auto& c) { return c.has_value(); });
  int missing = 0;
  for (size_t i = 0; i < estimated.size(); ++i) missing += !estimated[i];
  std::vector<std::pair<std::string, cv::Scalar>> entries = {
      {has_truth ? "estimated (Sim(3)-aligned)" : "estimated", kEstimated}};
  if (has_truth) entries.push_back({"ground truth", kTrue});
  if (missing > 0) {
    entries.push_back({std::to_string(missing) + (missing == 1 ? " frame" : " frames") +
                           " not registered" + (has_truth ? " (x: true position)" : ""),
                       kUnregistered});
  }
  int x = 20;
  for (const auto& [text, color] : entries) {
    if (x + 15 + TextWidth(text, 0.5) > image->cols - 10) {
      x = 20;
      y += 22;
    }
    cv::circle(*image, {x + 5, y - 5}, 5, color, cv::FILLED, cv::LINE_AA);
    Text(image, text, {x + 15, y}, 0.5);
    x += 15 + TextWidth(text, 0.5) + 20;
  }
  return y;
}

}  // namespace

cv::Mat RenderTrajectoryPlot(const Centers& estimated_centers, const Centers& true_centers,
                             const PlotPlane& plane, const TrajectoryPlotOptions& options) {
  options.Check();
  cv::Mat image(options.height, options.width, CV_8UC3, cv::Scalar(255, 255, 255));
  // Header: the wrapped title, the legend, the note.
  int y = 0;
  for (const std::string& line : WrapText(options.title, 0.6, options.width - 40)) {
    y += 24;
    Text(&image, line, {20, y}, 0.6);
  }
  y = DrawLegend(estimated_centers, true_centers, y + 26, &image);
  if (!options.note.empty()) {
    for (const std::string& line : WrapText(options.note, 0.5, options.width - 40)) {
      y += 22;
      Text(&image, line, {20, y}, 0.5, {60, 60, 60});
    }
  }
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d high = Eigen::Vector2d::Constant(std::numeric_limits<double>::lowest());
  for (const Centers* centers : {&estimated_centers, &true_centers}) {
    for (const auto& c : *centers) {
      if (!c) continue;
      const Eigen::Vector2d q(plane.right.dot(*c), plane.up.dot(*c));
      low = low.cwiseMin(q);
      high = high.cwiseMax(q);
    }
  }
  if (low.x() > high.x()) {
    Text(&image, "no camera positions", {40, options.height / 2}, 0.7);
    return image;
  }
  PlotFrame frame;
  frame.area = cv::Rect(80, y + 34, options.width - 100, options.height - y - 34 - 78);
  COMIC_CHECK(frame.area.width > 20 && frame.area.height > 20, kInvalidArgument,
              "trajectory plot: " << options.width << "x" << options.height
                                  << " pixels leave no room for the plot under the title");
  frame.middle = 0.5 * (low + high);
  const Eigen::Vector2d extent = (high - low).cwiseMax(Eigen::Vector2d::Constant(1e-9)) * 1.08;
  frame.scale = std::min(frame.area.width / extent.x(), frame.area.height / extent.y());
  DrawAxes(frame, plane, options.unit, &image);
  DrawPaths(frame, plane, estimated_centers, true_centers, &image);
  return image;
}

}  // namespace comic::sfm
