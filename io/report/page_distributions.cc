#include "io/report/page_distributions.h"

#include <cmath>

#include "io/core/error.h"

namespace comic::io {

PageSection HistogramSection(const Histogram& histogram) {
  COMIC_CHECK(histogram.edges.size() == histogram.counts.size() + 1, kInvalidArgument,
              "histogram: " << histogram.edges.size() << " edges for " << histogram.counts.size()
                            << " bins (one more edge than bins)");
  for (size_t k = 0; k + 1 < histogram.edges.size(); ++k) {
    COMIC_CHECK(std::isfinite(histogram.edges[k]) && histogram.edges[k] < histogram.edges[k + 1],
                kInvalidArgument, "histogram: the edges must ascend");
  }
  for (int64_t count : histogram.counts) {
    COMIC_CHECK(count >= 0, kInvalidArgument, "histogram: negative count " << count);
  }
  COMIC_CHECK(histogram.overflow >= 0, kInvalidArgument, "histogram: negative overflow");
  return {{"type", "histogram"},          {"title", histogram.title},
          {"x_label", histogram.x_label}, {"y_label", histogram.y_label},
          {"color", histogram.color},     {"edges", histogram.edges},
          {"counts", histogram.counts},   {"overflow", histogram.overflow},
          {"note", histogram.note}};
}

PageSection HeatMapSection(const HeatMap& map) {
  const size_t cells = map.cell_first_frames.size();
  COMIC_CHECK(
      map.values.size() == cells * cells, kInvalidArgument,
      "heat map: " << map.values.size() << " values for " << cells << " x " << cells << " cells");
  COMIC_CHECK(cells == 0 || map.cell_first_frames[0] == 0, kInvalidArgument,
              "heat map: the first cell must start at frame 0");
  for (size_t k = 0; k < cells; ++k) {
    COMIC_CHECK(map.cell_first_frames[k] < map.num_frames &&
                    (k == 0 || map.cell_first_frames[k - 1] < map.cell_first_frames[k]),
                kInvalidArgument, "heat map: the cells must ascend within the frames");
  }
  for (int64_t value : map.values) {
    COMIC_CHECK(value >= 0, kInvalidArgument, "heat map: negative value " << value);
  }
  return {{"type", "heatmap"},
          {"title", map.title},
          {"value_label", map.value_label},
          {"num_frames", map.num_frames},
          {"cell_first_frames", map.cell_first_frames},
          {"values", map.values},
          {"note", map.note}};
}

}  // namespace comic::io
