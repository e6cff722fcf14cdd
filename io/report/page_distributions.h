// The distribution sections of a report page (html_page.h): a histogram of values in equal bins
// (e.g. the reprojection errors of a model) and a heat map of a square matrix between frames
// (e.g. the tracks two frames share). Drawn by io/report/web/charts.js: the histogram as SVG
// bars, the heat map on a canvas (up to a few hundred cells a side).
//
//   Histogram errors;
//   errors.edges = {0.0, 0.25, 0.5};  errors.counts = {120, 31};  errors.overflow = 2;
//   page.sections.push_back(HistogramSection(errors));
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/report/page_sections.h"

namespace comic::io {

struct Histogram {
  std::string title;
  std::string x_label;          // with the unit, e.g. "reprojection error (px)"
  std::string y_label;          // e.g. "observations"
  std::string color;            // of the bars
  std::vector<double> edges;    // ascending: bin k is [edges[k], edges[k + 1])
  std::vector<int64_t> counts;  // one per bin
  int64_t overflow = 0;         // values beyond edges.back() (drawn as one more bar, marked)
  std::string note;
};

// Throws comic::Error(kInvalidArgument) unless there is one more edge than counts, the edges
// ascend and no count is negative.
PageSection HistogramSection(const Histogram& histogram);

// A square matrix whose rows and columns are cells of consecutive frames (one frame each when
// there are few): cell k holds frames cell_first_frames[k] up to the next cell's first - 1 (the
// last up to num_frames - 1).
struct HeatMap {
  std::string title;
  std::string value_label;  // what a cell counts, e.g. "shared tracks"
  int num_frames = 0;
  std::vector<int> cell_first_frames;  // ascending, the first 0
  std::vector<int64_t> values;         // row-major, cells x cells, non-negative
  std::string note;
};

// Throws comic::Error(kInvalidArgument) for values not cells x cells, or cells that do not
// ascend from frame 0 within num_frames.
PageSection HeatMapSection(const HeatMap& map);

}  // namespace comic::io
