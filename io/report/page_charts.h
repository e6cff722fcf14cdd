// The chart sections of a report page (html_page.h): values along the frames, a top view of
// camera paths with a metric scale, and a registration timeline of one cell per frame. Drawn as
// SVG (and a canvas for long timelines) by io/report/web/charts.js.
//
//   LineChart errors;
//   errors.title = "Position error per frame";
//   errors.x_label = "frame";
//   errors.y_label = "error (m)";
//   errors.series.push_back({"comic", "#d62728", frames, metres});
//   page.sections.push_back(LineChartSection(errors));
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/report/page_sections.h"

namespace comic::io {

struct LineChartSeries {
  std::string name;
  std::string color;
  std::vector<double> x;  // ascending
  std::vector<double> y;  // one per x; NaN: a gap in the line
};

// Ticks under the x axis at given x values (e.g. the frames that were not registered).
struct LineChartMarks {
  std::string label;
  std::string color;
  std::vector<double> x;
};

struct LineChart {
  std::string title;
  std::string x_label;  // with the unit, e.g. "frame" or "time (s)"
  std::string y_label;  // with the unit, e.g. "position error (m)"
  std::vector<LineChartSeries> series;
  std::vector<LineChartMarks> marks;
  std::string note;
};

// Throws comic::Error(kInvalidArgument) for a series whose x and y differ in length.
PageSection LineChartSection(const LineChart& chart);

// A point of a top view; NaN coordinates: none (the line breaks there).
using TopViewPoint = std::array<double, 2>;

struct TopViewSeries {
  std::string name;
  std::string color;
  std::vector<TopViewPoint> points;  // in order (frames); NaN: missing
  bool line = true;                  // joined in order; false: markers only
  double width = 2.0;                // line width or marker size in CSS pixels
  std::string marker = "dot";        // "dot", "cross" or "none"
};

struct TopView {
  std::string title;
  std::string right_label;  // the world direction drawn to the right, e.g. "x"
  std::string up_label;     // and up the page, e.g. "z"
  std::string unit;         // "m", or e.g. "model units" when the scale is unknown
  std::vector<TopViewSeries> series;
  // Thin grey segments from series[a].points[i] to series[b].points[i] (the error of each
  // camera): {a, b}, or {-1, -1} for none.
  std::array<int, 2> links = {-1, -1};
  std::string note;
};

// Equal scale on both axes, ticks and a grid in `unit`, a scale bar and a legend. Throws
// comic::Error(kInvalidArgument) for links naming a missing series or series of other lengths.
PageSection TopViewSection(const TopView& view);

// What a frame's cell shows: its state and, for states drawn in a model's colour, the model.
struct TimelineState {
  std::string key;    // e.g. "registered", "keyframe", "unregistered"
  std::string label;  // the legend's words
  std::string color;  // the cell colour when it has no group (or "" to use the group's)
  // "solid", "outline" (the group colour as a frame), "light" (pale) or "marked" (solid with a
  // dark top bar, e.g. keyframes).
  std::string style = "solid";
};

struct TimelineGroup {
  std::string label;  // e.g. "model 1 (sparse/0)"
  std::string color;
};

// A range of frames with words (why they are not registered), listed under the timeline and
// shown when a cell of it is pointed at.
struct TimelineNote {
  int first = 0;
  int last = 0;
  std::string text;
};

struct Timeline {
  std::string title;
  std::vector<TimelineState> states;
  std::vector<TimelineGroup> groups;
  std::vector<int> frame_states;         // per frame: index into states
  std::vector<int> frame_groups;         // per frame: index into groups or -1 (empty: all -1)
  std::vector<std::string> frame_names;  // per frame, or empty
  std::vector<TimelineNote> notes;
  std::string note;
};

// Throws comic::Error(kInvalidArgument) for indices out of range or per-frame lists of other
// lengths.
PageSection TimelineSection(const Timeline& timeline);

}  // namespace comic::io
