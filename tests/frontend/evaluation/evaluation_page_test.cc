// The evaluation apps' report.html (issue 28, item 3): the stereo page on the synthetic pair and
// the tracking page on the bundled clip hold every table, the bar charts with labelled axes, the
// figures as images and the legends that say what the figures' colours mean; the stereo legend's
// colours are the ones the figure draws. evaluation_page_browser_test.cc loads them in Chromium.
#include "frontend/evaluation/evaluation_page.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "frontend/evaluation/stereo_match_figure.h"
#include "frontend/evaluation/track_drawing.h"
#include "io/image/image_sequence.h"
#include "tests/frontend/synthetic_stereo_scene.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

using test::SyntheticStereoScene;

// The section of `page` titled `title` (null when there is none).
nlohmann::json Section(const io::HtmlPage& page, const std::string& title) {
  for (const nlohmann::json& section : page.sections) {
    if (section.value("title", "") == title) return section;
  }
  return nullptr;
}

std::vector<std::string> Titles(const io::HtmlPage& page) {
  std::vector<std::string> titles;
  for (const nlohmann::json& section : page.sections) titles.push_back(section.value("title", ""));
  return titles;
}

bool Contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

cv::Vec3b Bgr(const std::string& css) {
  unsigned r = 0, g = 0, b = 0;
  EXPECT_EQ(std::sscanf(css.c_str(), "#%02x%02x%02x", &r, &g, &b), 3) << css;
  return cv::Vec3b(b, g, r);
}

int CountColour(const cv::Mat& image, const cv::Vec3b& colour) {
  int count = 0;
  for (auto it = image.begin<cv::Vec3b>(); it != image.end<cv::Vec3b>(); ++it) {
    count += *it == colour;
  }
  return count;
}

struct StereoFixture {
  StereoEvaluationOptions options;
  std::vector<StereoPairEvaluation> results;
  StereoReport report;
  cv::Mat figure;
};

StereoFixture SyntheticStereo() {
  StereoFixture fixture;
  fixture.options.working_height = 0;
  fixture.options.methods = {{"harris", MatchCost::kFullPatch}, {"fast", MatchCost::kFullPatch}};
  fixture.options.target_counts = {60};
  io::MiddleburyPair pair = SyntheticStereoScene::Make();
  pair.name = "synthetic";
  fixture.results.push_back(EvaluateStereoPair(pair, fixture.options));
  fixture.report = BuildStereoReport(fixture.results, fixture.options);
  fixture.figure = DrawStereoMatchFigure(pair, fixture.results[0].runs[0], fixture.options.methods,
                                         fixture.options.max_cost);
  return fixture;
}

TEST(EvaluationPage, StereoPageHoldsTheTablesChartsFigureAndLegend) {
  const StereoFixture stereo = SyntheticStereo();
  const io::HtmlPage page = StereoEvaluationPage(stereo.report, stereo.results, stereo.options,
                                                 {{"matches_synthetic.png", stereo.figure}},
                                                 "comic_stereo_eval left.png right.png");
  EXPECT_EQ(page.title, "comic_stereo_eval · 1 pair");
  EXPECT_EQ(page.subtitle, "comic_stereo_eval left.png right.png");
  for (const char* title : {"Protocol", "Pairs", "Scores", "Matched precision", "Repeatability",
                            "Detections", "Beside the paper", "Matches"}) {
    EXPECT_FALSE(Section(page, title).is_null()) << title;
  }
  // The tables are the report's, row for row.
  const std::string scores = Section(page, "Scores").dump();
  EXPECT_TRUE(Contains(scores, "harris/full")) << scores.substr(0, 400);
  EXPECT_TRUE(Contains(scores, "fast/full"));
  // One bar chart per pair: both methods, the three regions, a labelled y axis.
  const nlohmann::json chart = Section(page, "synthetic");
  ASSERT_FALSE(chart.is_null()) << nlohmann::json(Titles(page)).dump();
  const std::string chart_text = chart.dump();
  EXPECT_TRUE(Contains(chart_text, "M_score(1) (% of detected)")) << chart_text;
  EXPECT_TRUE(Contains(chart_text, "non-boundary"));
  // The figure as an image, with the legend its PNG lacks.
  const std::string matches = Section(page, "Matches").dump();
  EXPECT_TRUE(Contains(matches, "data:image/")) << matches.substr(0, 200);
  EXPECT_TRUE(Contains(matches, "matches_synthetic.png"));
  for (const char* words : {"correct match", "wrong match", "without an accepted match",
                            "blue band", "depth discontinuity"}) {
    EXPECT_TRUE(Contains(matches, words)) << words;
  }
}

TEST(EvaluationPage, StereoLegendColoursAreTheFiguresColours) {
  const StereoFixture stereo = SyntheticStereo();
  const std::vector<io::PageLegendEntry> legend = StereoMatchFigureLegend(1.5);
  ASSERT_EQ(legend.size(), 4u);
  EXPECT_TRUE(Contains(legend[0].label, "within 1.5 px")) << legend[0].label;
  // Correct matches, unmatched features and (on this exact shift) some wrong ones are drawn in
  // exactly the legend's colours; the band's colour is the tint over mid grey, not a drawn colour.
  EXPECT_GT(CountColour(stereo.figure, Bgr(legend[0].color)), 0) << legend[0].color;
  EXPECT_GT(CountColour(stereo.figure, Bgr(legend[2].color)), 0) << legend[2].color;
  for (const io::PageLegendEntry& entry : legend) EXPECT_EQ(entry.color.size(), 7u);
}

TEST(EvaluationPage, TrackPageHoldsEveryTableChartAndTheOverlayLegend) {
  io::ImageSequenceOptions clip_options;
  clip_options.last_frame = 5;
  clip_options.resize_height = 185;
  const io::ImageSequence clip =
      io::ImageSequence::Open(test::ExampleDir() + "/image_l", clip_options);
  const cv::Size size = clip.FrameSize();
  const RegionMaskSource regions = [size](size_t) {
    cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
    mask(cv::Rect(size.width / 3, 0, size.width / 3, size.height)).setTo(255);
    return mask;
  };
  TrackEvaluationOptions options;
  options.detectors = {"harris", "fast"};
  options.num_features = 30;
  options.ns = {1, 5};
  const TrackEvaluation evaluation = EvaluateTracking(clip, regions, std::nullopt, options);
  const cv::Mat overlay(60, 80, CV_8UC3, cv::Scalar(30, 60, 90));
  const io::HtmlPage page = TrackEvaluationPage(
      evaluation, {"comic_track_eval clip --masks m", "masks m", {{"tracks_000005.png", overlay}}});
  EXPECT_EQ(page.subtitle, "comic_track_eval clip --masks m");
  const std::string protocol = Section(page, "Protocol").dump();
  EXPECT_TRUE(Contains(protocol, "masks m; boundary band")) << protocol;
  EXPECT_TRUE(Contains(protocol, "30 features")) << protocol;
  for (int n : {1, 5}) {
    const std::string s = std::to_string(n);
    const nlohmann::json table = Section(page, "Scores, n = " + s);
    ASSERT_FALSE(table.is_null()) << nlohmann::json(Titles(page)).dump();
    EXPECT_TRUE(Contains(table.dump(), "harris")) << table.dump().substr(0, 300);
    EXPECT_FALSE(Section(page, "At other SSD thresholds T, n = " + s).is_null());
    const std::string charts =
        Section(page, "M_score(" + s + ") and ResM_" + s + " per detector").dump();
    EXPECT_TRUE(Contains(charts, "M_score(" + s + ") (% of N)")) << charts.substr(0, 300);
    EXPECT_TRUE(Contains(charts, "ResM_" + s + " (features)"));
    EXPECT_TRUE(Contains(charts, "Boundary: within"));
  }
  // No poses: no precision tables.
  for (const std::string& title : Titles(page)) EXPECT_FALSE(Contains(title, "precision")) << title;
  const std::string tracks = Section(page, "Tracks on frames").dump();
  EXPECT_TRUE(Contains(tracks, "tracks_000005.png"));
  EXPECT_TRUE(Contains(tracks, "data:image/"));
  for (const io::PageLegendEntry& entry : TrackDrawingLegend(true)) {
    EXPECT_TRUE(Contains(tracks, entry.label)) << entry.label;
    EXPECT_TRUE(Contains(tracks, entry.color)) << entry.color;
  }
}

}  // namespace
}  // namespace comic::frontend
