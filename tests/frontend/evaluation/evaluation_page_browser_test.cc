// comic_stereo_eval's report.html (issue 28, item 3) in a real browser (Debian's headless
// Chromium): the page's scripts run without an error and draw its tables, its bar chart, the
// match figure and the legend of the figure's colours. Skipped where Chromium is missing or cannot
// start. One small synthetic pair: one browser launch, a few seconds.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frontend/evaluation/evaluation_page.h"
#include "frontend/evaluation/stereo_match_figure.h"
#include "tests/frontend/synthetic_stereo_scene.h"
#include "tests/headless_browser.h"

namespace comic::frontend {
namespace {

using comic::test::HtmlAttribute;
using comic::test::ScopedTempDir;

size_t Count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(EvaluationPageInChromium, TheStereoPageDrawsItsTablesChartFigureAndLegend) {
  StereoEvaluationOptions options;
  options.working_height = 0;
  options.methods = {{"harris", MatchCost::kFullPatch}, {"fast", MatchCost::kFullPatch}};
  options.target_counts = {60};
  io::MiddleburyPair pair = test::SyntheticStereoScene::Make();
  pair.name = "synthetic";
  const std::vector<StereoPairEvaluation> results = {EvaluateStereoPair(pair, options)};
  const cv::Mat figure =
      DrawStereoMatchFigure(pair, results[0].runs[0], options.methods, options.max_cost);
  ScopedTempDir dir;
  const std::string path = dir.File("report.html");
  io::WriteHtmlPage(path,
                    StereoEvaluationPage(BuildStereoReport(results, options), results, options,
                                         {{"matches_synthetic.png", figure}}, "comic_stereo_eval"));
  std::string why;
  const auto page = comic::test::LoadInChromium(path, 1000, 800, &why);
  if (!page) GTEST_SKIP() << why;
  EXPECT_EQ(HtmlAttribute(page->dom, "data-comic-page"), "drawn");
  EXPECT_NE(page->dom.find("id=\"comic-page-errors\" hidden"), std::string::npos);
  // Drawn as HTML, not only present in the page's JSON: the seven tables, the chart, the figure
  // and the legend swatches followed by their words.
  EXPECT_EQ(Count(page->dom, "<table"), 7u);
  EXPECT_EQ(Count(page->dom, "<svg class=\"chart\""), 1u);
  EXPECT_EQ(Count(page->dom, "<img"), 1u);
  EXPECT_EQ(Count(page->dom, "class=\"swatch\""), 4u + 2u);  // the figure's and the chart's
  EXPECT_NE(page->dom.find("</span>correct match"), std::string::npos);
  EXPECT_NE(page->dom.find("</span>blue band"), std::string::npos);
  ASSERT_FALSE(page->screenshot.empty());
  // Not a blank window: the page's text and table lines differ from its background.
  EXPECT_GT(comic::test::CountPixelsUnlike(
                page->screenshot, cv::Rect(0, 0, page->screenshot.cols, page->screenshot.rows),
                page->screenshot.at<cv::Vec3b>(0, 0)),
            1000);
}

}  // namespace
}  // namespace comic::frontend
