// Histograms and heat maps as page sections: what they hold, and inconsistent inputs refused.
#include "io/report/page_distributions.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::io {
namespace {

TEST(HistogramSection, NeedsOneMoreEdgeThanBins) {
  Histogram histogram;
  histogram.edges = {0.0, 0.5, 1.0};
  histogram.counts = {4, 2};
  histogram.overflow = 1;
  const PageSection section = HistogramSection(histogram);
  EXPECT_EQ(section["type"], "histogram");
  EXPECT_EQ(section["counts"], nlohmann::json({4, 2}));
  EXPECT_EQ(section["overflow"], 1);
  histogram.counts.push_back(1);
  EXPECT_THROW(HistogramSection(histogram), Error);
  histogram.counts = {4, -2};
  EXPECT_THROW(HistogramSection(histogram), Error);
  histogram.counts = {4, 2};
  histogram.edges = {0.0, 1.0, 0.5};
  EXPECT_THROW(HistogramSection(histogram), Error);
}

TEST(HeatMapSection, NeedsASquareOfAscendingCells) {
  HeatMap map;
  map.num_frames = 5;
  map.cell_first_frames = {0, 3};
  map.values = {0, 7, 7, 1};
  const PageSection section = HeatMapSection(map);
  EXPECT_EQ(section["type"], "heatmap");
  EXPECT_EQ(section["values"][1], 7);
  map.values.pop_back();
  EXPECT_THROW(HeatMapSection(map), Error);
  map.values = {0, 7, 7, 1};
  map.cell_first_frames = {1, 3};
  EXPECT_THROW(HeatMapSection(map), Error);
  map.cell_first_frames = {0, 5};
  EXPECT_THROW(HeatMapSection(map), Error);
}

}  // namespace
}  // namespace comic::io
