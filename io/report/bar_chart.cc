#include "io/report/bar_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::io {
namespace {

// Colour-blind-safe palette (Okabe & Ito), BGR.
const cv::Scalar kPalette[] = {{178, 114, 0},  {0, 159, 230}, {115, 158, 0},  {167, 121, 204},
                               {66, 228, 240}, {0, 94, 213},  {233, 180, 86}, {0, 0, 0}};

void Text(cv::Mat* image, const std::string& text, cv::Point origin, double scale,
          const cv::Scalar& colour = {0, 0, 0}) {
  cv::putText(*image, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

int TextWidth(const std::string& text, double scale) {
  int baseline = 0;
  return cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline).width;
}

// `text` written bottom to top with its centre at `center` (a y-axis label).
void VerticalText(cv::Mat* image, const std::string& text, cv::Point center, double scale) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  cv::Mat strip(size.height + baseline + 4, size.width + 4, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::putText(strip, text, {2, size.height + 2}, cv::FONT_HERSHEY_SIMPLEX, scale, {0, 0, 0}, 1,
              cv::LINE_AA);
  cv::Mat turned;
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  cv::Rect where(center.x - turned.cols / 2, center.y - turned.rows / 2, turned.cols, turned.rows);
  where &= cv::Rect(0, 0, image->cols, image->rows);
  turned(cv::Rect(0, 0, where.width, where.height)).copyTo((*image)(where));
}

}  // namespace

cv::Mat DrawBarChart(const BarChart& chart, const cv::Size& size) {
  COMIC_CHECK(size.width >= 200 && size.height >= 150, kInvalidArgument,
              "bar chart: size must be at least 200x150");
  for (const BarChartSeries& s : chart.series) {
    COMIC_CHECK(s.values.size() == chart.groups.size(), kInvalidArgument,
                "bar chart: series '" << s.name << "' has " << s.values.size() << " values for "
                                      << chart.groups.size() << " groups");
  }
  cv::Mat image(size, CV_8UC3, cv::Scalar(255, 255, 255));
  Text(&image, chart.title, {10, 22}, 0.6);
  // Legend.
  int x = 10;
  for (size_t s = 0; s < chart.series.size(); ++s) {
    const cv::Scalar colour = kPalette[s % (sizeof(kPalette) / sizeof(kPalette[0]))];
    cv::rectangle(image, cv::Rect(x, 32, 12, 12), colour, cv::FILLED);
    Text(&image, chart.series[s].name, {x + 16, 43}, 0.45);
    x += 16 + TextWidth(chart.series[s].name, 0.45) + 18;
  }
  // With a y-axis label, room for it left of the tick values.
  const int label_room = chart.y_label.empty() ? 0 : 22;
  const int left = 50 + label_room, right = size.width - 10, top = 70, bottom = size.height - 30;
  if (!chart.y_label.empty()) VerticalText(&image, chart.y_label, {11, (top + bottom) / 2}, 0.45);
  double max_value = 0.0;
  for (const BarChartSeries& s : chart.series) {
    for (double v : s.values) {
      if (std::isfinite(v)) max_value = std::max(max_value, v);
    }
  }
  if (max_value <= 0.0) max_value = 1.0;
  // A round axis maximum: 1, 2 or 5 times a power of ten.
  const double magnitude = std::pow(10.0, std::floor(std::log10(max_value)));
  double axis_max = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * magnitude >= max_value) {
      axis_max = m * magnitude;
      break;
    }
  }
  auto y_of = [&](double v) {
    return bottom - static_cast<int>(std::lround((bottom - top) * v / axis_max));
  };
  for (int tick = 0; tick <= 4; ++tick) {
    const double v = axis_max * tick / 4;
    const int y = y_of(v);
    cv::line(image, {left, y}, {right, y}, cv::Scalar(220, 220, 220), 1);
    char label[32];
    std::snprintf(label, sizeof(label), "%g", v);
    Text(&image, label, {4 + label_room, y + 4}, 0.4, {80, 80, 80});
  }
  cv::line(image, {left, bottom}, {right, bottom}, cv::Scalar(0, 0, 0), 1);
  if (chart.groups.empty()) return image;
  const double group_width = static_cast<double>(right - left) / chart.groups.size();
  const size_t num_series = std::max<size_t>(1, chart.series.size());
  const double bar_width = group_width * 0.8 / num_series;
  for (size_t g = 0; g < chart.groups.size(); ++g) {
    const double group_left = left + g * group_width + group_width * 0.1;
    for (size_t s = 0; s < chart.series.size(); ++s) {
      const double v = chart.series[s].values[g];
      if (!std::isfinite(v)) continue;
      const int x0 = static_cast<int>(std::lround(group_left + s * bar_width));
      const int x1 = static_cast<int>(std::lround(group_left + (s + 1) * bar_width)) - 2;
      const int y = y_of(std::max(0.0, v));
      cv::rectangle(image, cv::Rect(cv::Point(x0, y), cv::Point(std::max(x0 + 1, x1), bottom)),
                    kPalette[s % (sizeof(kPalette) / sizeof(kPalette[0]))], cv::FILLED);
      char label[32];
      std::snprintf(label, sizeof(label), "%.1f", v);
      const double scale = bar_width > 40 ? 0.4 : 0.3;
      Text(&image, label, {x0, y - 3}, scale, {60, 60, 60});
    }
    const std::string& name = chart.groups[g];
    const int cx = static_cast<int>(left + (g + 0.5) * group_width);
    Text(&image, name, {cx - TextWidth(name, 0.5) / 2, bottom + 20}, 0.5);
  }
  return image;
}

}  // namespace comic::io
