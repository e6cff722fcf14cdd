// The typed sections of a report page: what each puts in the page's JSON, and the inputs each
// refuses.
#include "io/report/page_sections.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::io {
namespace {

TEST(FactsSection, KeepsOrderAndTone) {
  const PageSection section =
      FactsSection("Summary", {{"status", "partial", PageTone::kWarning}, {"frames", "40"}});
  EXPECT_EQ(section["type"], "facts");
  ASSERT_EQ(section["facts"].size(), 2u);
  EXPECT_EQ(section["facts"][0]["tone"], "warning");
  EXPECT_EQ(section["facts"][1]["label"], "frames");
  EXPECT_EQ(section["facts"][1]["tone"], "neutral");
  EXPECT_EQ(NoticeSection(PageTone::kBad, "Why", "no pair")["tone"], "bad");
}

TEST(TableSection, WritesCellsAsTheMarkdownTableDoes) {
  ReportTable table({"detector", "ATE m", "points"});
  table.SetPrecision("ATE m", 2);
  table.AddRow({std::string("comic"), 0.01234, int64_t{907}});
  table.AddRow({std::string("harris"), ReportTable::Cell(), int64_t{12}});
  const PageSection section = TableSection("Compared", table, "a note", {"comic/report.html", ""});
  EXPECT_EQ(section["rows"][0], nlohmann::json({"comic", "0.01", "907"}));
  EXPECT_EQ(section["rows"][1][1], "");
  EXPECT_EQ(section["numeric"], nlohmann::json({false, true, true}));
  EXPECT_EQ(section["links"][0], "comic/report.html");
  EXPECT_THROW(TableSection("Compared", table, "", {"one link for two rows"}), Error);
}

TEST(BarChartSection, CarriesTheAxisLabelAndMissingValuesAsNull) {
  BarChart chart;
  chart.title = "ATE";
  chart.y_label = "ATE RMSE (m)";
  chart.groups = {"ATE"};
  chart.series = {{"comic", {0.007}}, {"mser", {std::nan("")}}};
  const PageSection section = BarChartSection(chart);
  EXPECT_EQ(section["y_label"], "ATE RMSE (m)");
  EXPECT_TRUE(section["series"][1]["values"][0].is_null());
  chart.series[1].values = {1.0, 2.0};
  EXPECT_THROW(BarChartSection(chart), Error);
}

TEST(BarChartsSection, NeedsTheSameSeriesInEveryChart) {
  BarChart a, b;
  a.groups = b.groups = {"x"};
  a.series = {{"comic", {1.0}}, {"harris", {2.0}}};
  b.series = {{"comic", {3.0}}, {"harris", {4.0}}};
  const PageSection section = BarChartsSection("per detector", {a, b});
  EXPECT_EQ(section["type"], "bars");
  EXPECT_EQ(section["charts"].size(), 2u);
  b.series[1].name = "fast";
  EXPECT_THROW(BarChartsSection("per detector", {a, b}), Error);
  EXPECT_THROW(BarChartsSection("per detector", {}), Error);
}

TEST(KeyValuesSection, FlattensNestedObjects) {
  const nlohmann::json options = {{"frames", "clip"},
                                  {"matching", {{"chosen", "sequential"}, {"gain", 0.5}}},
                                  {"frame_size", {1226, 370}}};
  const PageSection section = KeyValuesSection("Options", options);
  const nlohmann::json expected = nlohmann::json::parse(
      R"([["frame_size", [1226, 370]], ["frames", "clip"], ["matching.chosen", "sequential"],
          ["matching.gain", 0.5]])");
  EXPECT_EQ(section["rows"], expected);
}

TEST(ImagesSection, KeepsCaptionsToneAndLegend) {
  const PageSection section =
      ImagesSection("Frames", {{"data:image/jpeg;base64,AA==", "frame 3", "bad"}},
                    {{"#ff0000", "boundary"}}, "note", true);
  EXPECT_EQ(section["images"][0]["tone"], "bad");
  EXPECT_EQ(section["legend"][0]["label"], "boundary");
  EXPECT_TRUE(section["thumbnails"].get<bool>());
}

}  // namespace
}  // namespace comic::io
