#include "io/report/page_charts.h"

#include <cmath>

#include "io/core/error.h"

namespace comic::io {

namespace {

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json Numbers(const std::vector<double>& values) {
  nlohmann::json array = nlohmann::json::array();
  for (double v : values) array.push_back(NumberOrNull(v));
  return array;
}

nlohmann::json PointOrNull(const TopViewPoint& p) {
  if (!std::isfinite(p[0]) || !std::isfinite(p[1])) return nullptr;
  return {p[0], p[1]};
}

}  // namespace

PageSection LineChartSection(const LineChart& chart) {
  nlohmann::json series = nlohmann::json::array();
  for (const LineChartSeries& s : chart.series) {
    COMIC_CHECK(s.x.size() == s.y.size(), kInvalidArgument,
                "line chart: series '" << s.name << "' has " << s.x.size() << " x and "
                                       << s.y.size() << " y values");
    series.push_back(
        {{"name", s.name}, {"color", s.color}, {"x", Numbers(s.x)}, {"y", Numbers(s.y)}});
  }
  nlohmann::json marks = nlohmann::json::array();
  for (const LineChartMarks& m : chart.marks) {
    marks.push_back({{"label", m.label}, {"color", m.color}, {"x", Numbers(m.x)}});
  }
  return {{"type", "lines"},          {"title", chart.title}, {"x_label", chart.x_label},
          {"y_label", chart.y_label}, {"series", series},     {"marks", marks},
          {"note", chart.note}};
}

PageSection TopViewSection(const TopView& view) {
  const int num_series = static_cast<int>(view.series.size());
  if (view.links[0] >= 0 || view.links[1] >= 0) {
    COMIC_CHECK(view.links[0] >= 0 && view.links[0] < num_series && view.links[1] >= 0 &&
                    view.links[1] < num_series,
                kInvalidArgument, "top view: links name a series that is not there");
    COMIC_CHECK(
        view.series[view.links[0]].points.size() == view.series[view.links[1]].points.size(),
        kInvalidArgument, "top view: linked series must have one point per frame each");
  }
  nlohmann::json series = nlohmann::json::array();
  for (const TopViewSeries& s : view.series) {
    nlohmann::json points = nlohmann::json::array();
    for (const TopViewPoint& p : s.points) points.push_back(PointOrNull(p));
    series.push_back({{"name", s.name},
                      {"color", s.color},
                      {"points", points},
                      {"line", s.line},
                      {"width", s.width},
                      {"marker", s.marker}});
  }
  return {{"type", "topview"},
          {"title", view.title},
          {"right_label", view.right_label},
          {"up_label", view.up_label},
          {"unit", view.unit},
          {"series", series},
          {"links", view.links[0] >= 0 ? nlohmann::json(view.links) : nlohmann::json(nullptr)},
          {"note", view.note}};
}

PageSection TimelineSection(const Timeline& timeline) {
  const size_t num_frames = timeline.frame_states.size();
  COMIC_CHECK(timeline.frame_groups.empty() || timeline.frame_groups.size() == num_frames,
              kInvalidArgument, "timeline: frame_groups must be empty or one per frame");
  COMIC_CHECK(timeline.frame_names.empty() || timeline.frame_names.size() == num_frames,
              kInvalidArgument, "timeline: frame_names must be empty or one per frame");
  for (int state : timeline.frame_states) {
    COMIC_CHECK(state >= 0 && state < static_cast<int>(timeline.states.size()), kInvalidArgument,
                "timeline: frame state " << state << " is not one of the " << timeline.states.size()
                                         << " states");
  }
  for (int group : timeline.frame_groups) {
    COMIC_CHECK(group >= -1 && group < static_cast<int>(timeline.groups.size()), kInvalidArgument,
                "timeline: frame group " << group << " is not one of the " << timeline.groups.size()
                                         << " groups");
  }
  nlohmann::json states = nlohmann::json::array();
  for (const TimelineState& s : timeline.states) {
    states.push_back({{"key", s.key}, {"label", s.label}, {"color", s.color}, {"style", s.style}});
  }
  nlohmann::json groups = nlohmann::json::array();
  for (const TimelineGroup& g : timeline.groups) {
    groups.push_back({{"label", g.label}, {"color", g.color}});
  }
  nlohmann::json notes = nlohmann::json::array();
  for (const TimelineNote& n : timeline.notes) {
    COMIC_CHECK(n.first >= 0 && n.first <= n.last && n.last < static_cast<int>(num_frames),
                kInvalidArgument,
                "timeline: note on frames " << n.first << "-" << n.last << " out of range");
    notes.push_back({{"first", n.first}, {"last", n.last}, {"text", n.text}});
  }
  return {{"type", "timeline"},
          {"title", timeline.title},
          {"states", states},
          {"groups", groups},
          {"frame_states", timeline.frame_states},
          {"frame_groups", timeline.frame_groups.empty()
                               ? nlohmann::json(std::vector<int>(num_frames, -1))
                               : nlohmann::json(timeline.frame_groups)},
          {"frame_names", timeline.frame_names},
          {"notes", notes},
          {"note", timeline.note}};
}

}  // namespace comic::io
