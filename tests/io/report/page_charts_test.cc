// Line charts, top views and timelines as page sections: missing values become gaps (null), and
// inconsistent inputs are refused.
#include "io/report/page_charts.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::io {
namespace {

TEST(LineChartSection, KeepsGapsAsNull) {
  LineChart chart;
  chart.y_label = "position error (m)";
  chart.series.push_back({"model 1", "#e0452b", {0, 1, 2}, {0.1, std::nan(""), 0.3}});
  chart.marks.push_back({"not registered", "#f0a000", {1}});
  const PageSection section = LineChartSection(chart);
  EXPECT_EQ(section["type"], "lines");
  EXPECT_TRUE(section["series"][0]["y"][1].is_null());
  EXPECT_EQ(section["marks"][0]["x"], nlohmann::json({1.0}));
  chart.series[0].x.pop_back();
  EXPECT_THROW(LineChartSection(chart), Error);
}

TEST(TopViewSection, LinksNeedTwoSeriesOfOneLength) {
  TopView view;
  view.unit = "m";
  view.series.push_back({"truth", "#3aa655", {{0, 0}, {1, 0}}});
  view.series.push_back({"model 1", "#e0452b", {{0, 0.1}, {std::nan(""), std::nan("")}}});
  view.links = {0, 1};
  const PageSection section = TopViewSection(view);
  EXPECT_TRUE(section["series"][1]["points"][1].is_null());
  EXPECT_EQ(section["links"], nlohmann::json({0, 1}));
  view.links = {0, 2};
  EXPECT_THROW(TopViewSection(view), Error);
  view.links = {0, 1};
  view.series[1].points.pop_back();
  EXPECT_THROW(TopViewSection(view), Error);
}

Timeline ThreeFrames() {
  Timeline timeline;
  timeline.states = {{"registered", "registered", "", "solid"},
                     {"unregistered", "not registered", "#c3c9cf", "solid"}};
  timeline.groups = {{"model 1", "#e0452b"}};
  timeline.frame_states = {0, 1, 0};
  timeline.frame_groups = {0, -1, 0};
  timeline.notes = {{1, 1, "too few 3-D points"}};
  return timeline;
}

TEST(TimelineSection, TakesStatesGroupsAndNotesPerFrame) {
  const PageSection section = TimelineSection(ThreeFrames());
  EXPECT_EQ(section["frame_states"], nlohmann::json({0, 1, 0}));
  EXPECT_EQ(section["frame_groups"], nlohmann::json({0, -1, 0}));
  EXPECT_EQ(section["notes"][0]["text"], "too few 3-D points");
  Timeline no_groups = ThreeFrames();
  no_groups.frame_groups.clear();
  EXPECT_EQ(TimelineSection(no_groups)["frame_groups"], nlohmann::json({-1, -1, -1}));
}

TEST(TimelineSection, RefusesIndicesOutOfRange) {
  Timeline bad_state = ThreeFrames();
  bad_state.frame_states[2] = 2;
  EXPECT_THROW(TimelineSection(bad_state), Error);
  Timeline bad_group = ThreeFrames();
  bad_group.frame_groups[0] = 1;
  EXPECT_THROW(TimelineSection(bad_group), Error);
  Timeline bad_note = ThreeFrames();
  bad_note.notes[0].last = 3;
  EXPECT_THROW(TimelineSection(bad_note), Error);
  Timeline bad_names = ThreeFrames();
  bad_names.frame_names = {"a.png"};
  EXPECT_THROW(TimelineSection(bad_names), Error);
}

}  // namespace
}  // namespace comic::io
