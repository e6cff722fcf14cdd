// The sections of a report page (html_page.h) that hold text, tables and pictures, built from
// typed values so that every page says things the same way. Each function returns the section as
// the JSON io/report/web/page.js draws ({"type": ..., "title": ..., ...}).
//
//   page.sections.push_back(FactsSection("Summary", {{"status", "partial", PageTone::kWarning},
//                                                     {"registered", "180 / 196 frames"}}));
//   page.sections.push_back(TableSection("Scores", table));
//   page.sections.push_back(BarChartSection(chart));  // the same BarChart as the PNG
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/report/bar_chart.h"
#include "io/report/report_table.h"

namespace comic::io {

using PageSection = nlohmann::json;

// How a fact or notice reads: plain, good (green), a warning (amber) or bad (red).
enum class PageTone { kNeutral, kGood, kWarning, kBad };
const char* PageToneName(PageTone tone);  // "neutral", "good", "warning", "bad"

// A colour swatch and what it means, for the legends the pictures need.
struct PageLegendEntry {
  std::string color;  // CSS colour, e.g. "#d62728"
  std::string label;
};

struct PageFact {
  std::string label;
  std::string value;
  PageTone tone = PageTone::kNeutral;
};

// A list of label: value lines (the summary of a run).
PageSection FactsSection(const std::string& title, const std::vector<PageFact>& facts);

// A boxed message, e.g. the diagnosis of a failed run.
PageSection NoticeSection(PageTone tone, const std::string& title, const std::string& text);

// Paragraphs of plain text.
PageSection TextSection(const std::string& title, const std::vector<std::string>& paragraphs);

// `table` as an HTML table with the cells as ReportTable formats them (ToMarkdown's text);
// `note` under it (may be empty). Rows may link to another page: `row_links` is empty or one
// relative URL per row (empty: no link), put on the first cell.
PageSection TableSection(const std::string& title, const ReportTable& table,
                         const std::string& note = "",
                         const std::vector<std::string>& row_links = {});

// `chart` drawn as an SVG bar chart with its y-axis label, value labels and legend.
PageSection BarChartSection(const BarChart& chart, const std::string& note = "");

// Several small bar charts side by side (e.g. ATE, points and registered frames per detector),
// their series in the same colours under one legend. Throws comic::Error(kInvalidArgument) for
// no chart or charts whose series differ in names.
PageSection BarChartsSection(const std::string& title, const std::vector<BarChart>& charts,
                             const std::string& note = "");

struct PageImage {
  std::string src;      // a data: URI (data_uri.h)
  std::string caption;  // under the image
  std::string tone;     // "" or a PageToneName: a coloured frame (e.g. an unregistered frame)
};

// Pictures in a grid with their captions and a legend of the colours drawn on them. `thumbnails`
// draws them small in one scrolling strip.
PageSection ImagesSection(const std::string& title, const std::vector<PageImage>& images,
                          const std::vector<PageLegendEntry>& legend = {},
                          const std::string& note = "", bool thumbnails = false);

// A JSON object as a two-column table of its leaves ("matching.chosen": "sequential"), e.g. the
// options of a run.
PageSection KeyValuesSection(const std::string& title, const nlohmann::json& object);

// A JSON document shown folded (the run's whole report.json).
PageSection JsonSection(const std::string& title, const nlohmann::json& document);

}  // namespace comic::io
