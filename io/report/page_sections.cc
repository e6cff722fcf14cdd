#include "io/report/page_sections.h"

#include <cmath>

#include "io/core/error.h"

namespace comic::io {

namespace {

// Leaves of a JSON object as "a.b.c" -> value (arrays of scalars stay whole).
void FlattenInto(const std::string& prefix, const nlohmann::json& value, nlohmann::json* rows) {
  if (value.is_object() && !value.empty()) {
    for (const auto& [key, item] : value.items()) {
      FlattenInto(prefix.empty() ? key : prefix + "." + key, item, rows);
    }
    return;
  }
  rows->push_back({prefix, value});
}

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

const char* PageToneName(PageTone tone) {
  switch (tone) {
    case PageTone::kGood:
      return "good";
    case PageTone::kWarning:
      return "warning";
    case PageTone::kBad:
      return "bad";
    case PageTone::kNeutral:
      break;
  }
  return "neutral";
}

PageSection FactsSection(const std::string& title, const std::vector<PageFact>& facts) {
  PageSection section = {{"type", "facts"}, {"title", title}, {"facts", nlohmann::json::array()}};
  for (const PageFact& fact : facts) {
    section["facts"].push_back(
        {{"label", fact.label}, {"value", fact.value}, {"tone", PageToneName(fact.tone)}});
  }
  return section;
}

PageSection NoticeSection(PageTone tone, const std::string& title, const std::string& text) {
  return {{"type", "notice"}, {"title", title}, {"tone", PageToneName(tone)}, {"text", text}};
}

PageSection TextSection(const std::string& title, const std::vector<std::string>& paragraphs) {
  return {{"type", "text"}, {"title", title}, {"paragraphs", paragraphs}};
}

PageSection TableSection(const std::string& title, const ReportTable& table,
                         const std::string& note, const std::vector<std::string>& row_links) {
  COMIC_CHECK(row_links.empty() || row_links.size() == table.NumRows(), kInvalidArgument,
              "TableSection: " << row_links.size() << " links for " << table.NumRows() << " rows");
  nlohmann::json numeric = nlohmann::json::array();
  for (size_t c = 0; c < table.columns().size(); ++c) numeric.push_back(table.IsNumericColumn(c));
  nlohmann::json rows = nlohmann::json::array();
  for (size_t r = 0; r < table.NumRows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (size_t c = 0; c < table.columns().size(); ++c) row.push_back(table.CellText(r, c));
    rows.push_back(std::move(row));
  }
  PageSection section = {{"type", "table"},    {"title", title}, {"columns", table.columns()},
                         {"numeric", numeric}, {"rows", rows},   {"note", note}};
  if (!row_links.empty()) section["links"] = row_links;
  return section;
}

PageSection BarChartSection(const BarChart& chart, const std::string& note) {
  nlohmann::json series = nlohmann::json::array();
  for (const BarChartSeries& s : chart.series) {
    COMIC_CHECK(s.values.size() == chart.groups.size(), kInvalidArgument,
                "bar chart: series '" << s.name << "' has " << s.values.size() << " values for "
                                      << chart.groups.size() << " groups");
    nlohmann::json values = nlohmann::json::array();
    for (double v : s.values) values.push_back(NumberOrNull(v));
    series.push_back({{"name", s.name}, {"values", values}});
  }
  return {{"type", "bars"},         {"title", chart.title}, {"y_label", chart.y_label},
          {"groups", chart.groups}, {"series", series},     {"note", note}};
}

PageSection BarChartsSection(const std::string& title, const std::vector<BarChart>& charts,
                             const std::string& note) {
  COMIC_CHECK(!charts.empty(), kInvalidArgument, "BarChartsSection: no chart");
  PageSection section = {
      {"type", "bars"}, {"title", title}, {"charts", nlohmann::json::array()}, {"note", note}};
  for (const BarChart& chart : charts) {
    COMIC_CHECK(chart.series.size() == charts.front().series.size(), kInvalidArgument,
                "BarChartsSection: every chart needs the same series");
    for (size_t s = 0; s < chart.series.size(); ++s) {
      COMIC_CHECK(chart.series[s].name == charts.front().series[s].name, kInvalidArgument,
                  "BarChartsSection: every chart needs the same series");
    }
    PageSection one = BarChartSection(chart);
    one.erase("type");
    one.erase("note");
    section["charts"].push_back(one);
  }
  return section;
}

PageSection ImagesSection(const std::string& title, const std::vector<PageImage>& images,
                          const std::vector<PageLegendEntry>& legend, const std::string& note,
                          bool thumbnails) {
  nlohmann::json items = nlohmann::json::array();
  for (const PageImage& image : images) {
    items.push_back({{"src", image.src}, {"caption", image.caption}, {"tone", image.tone}});
  }
  nlohmann::json entries = nlohmann::json::array();
  for (const PageLegendEntry& entry : legend) {
    entries.push_back({{"color", entry.color}, {"label", entry.label}});
  }
  return {{"type", "images"},  {"title", title}, {"images", items},
          {"legend", entries}, {"note", note},   {"thumbnails", thumbnails}};
}

PageSection KeyValuesSection(const std::string& title, const nlohmann::json& object) {
  nlohmann::json rows = nlohmann::json::array();
  FlattenInto("", object, &rows);
  return {{"type", "keyvalues"}, {"title", title}, {"rows", rows}};
}

PageSection JsonSection(const std::string& title, const nlohmann::json& document) {
  return {{"type", "json"}, {"title", title}, {"document", document}};
}

}  // namespace comic::io
