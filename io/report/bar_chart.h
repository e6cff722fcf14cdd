// Grouped bar charts rendered to an image, for the evaluation reports (e.g. M_score per detector
// for boundary / non-boundary / overall features), so every app draws the same kind of figure.
//
//   BarChart chart;
//   chart.title = "M_score(5) %";
//   chart.y_label = "M_score(5) (%)";
//   chart.groups = {"boundary", "non-boundary", "overall"};
//   chart.series = {{"comic", {40.9, 50.8, 46.2}}, {"harris", {24.7, 45.8, 37.8}}};
//   WriteImageAtomically("scores.png", DrawBarChart(chart));
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace comic::io {

struct BarChartSeries {
  std::string name;            // legend entry
  std::vector<double> values;  // one per group; NaN = no bar
};

struct BarChart {
  std::string title;
  std::string
      y_label;  // what the bars measure, with the unit (e.g. "ATE (m)"), drawn on the y axis
  std::vector<std::string> groups;  // x-axis categories
  std::vector<BarChartSeries> series;
};

// Renders `chart` as a CV_8UC3 image of `size`: one cluster of bars per group, one colour per
// series (legend on top), value labels above the bars, y axis from 0 to the largest value with
// y_label written along it.
// Throws comic::Error(kInvalidArgument) if a series has not one value per group, or for a size
// smaller than 200x150.
cv::Mat DrawBarChart(const BarChart& chart, const cv::Size& size = {960, 420});

}  // namespace comic::io
