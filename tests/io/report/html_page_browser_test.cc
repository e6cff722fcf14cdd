// Every section type of a report page drawn in a real browser (Debian's headless Chromium): the
// page's scripts run without an error, mark it drawn, and the 3-D view draws (three.js through
// WebGL: pixels read back by the page, and seen in the screenshot where its canvas is). Skipped
// where Chromium is missing or cannot start.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "io/report/data_uri.h"
#include "io/report/html_page.h"
#include "io/report/page_charts.h"
#include "io/report/page_scene.h"
#include "io/report/page_sections.h"
#include "tests/headless_browser.h"

namespace comic::io {
namespace {

using comic::test::HtmlAttribute;

// A ring of coloured points around a circle of cameras looking inwards.
Scene RingScene() {
  Scene scene;
  for (int i = 0; i < 2000; ++i) {
    const double a = 2 * M_PI * i / 2000.0;
    scene.points.emplace_back(3 * std::cos(a), 0.3 * std::sin(7 * a), 3 * std::sin(a));
    scene.colors.push_back({static_cast<uint8_t>(128 + 127 * std::cos(a)), 180,
                            static_cast<uint8_t>(128 + 127 * std::sin(a))});
  }
  SceneCameras cameras;
  cameras.name = "model 1";
  cameras.color = "#e0452b";
  for (int i = 0; i < 24; ++i) {
    const double a = 2 * M_PI * i / 24.0;
    cameras.centers.emplace_back(std::cos(a), 0, std::sin(a));
    // Looking at the centre (z), image rows down the world's +y (so up is -y), x = y × z.
    const Eigen::Vector3d z = -cameras.centers.back().normalized();
    const Eigen::Vector3d y(0, 1, 0);
    Eigen::Matrix3d world_from_camera;
    world_from_camera.col(0) = y.cross(z);
    world_from_camera.col(1) = y;
    world_from_camera.col(2) = z;
    cameras.rotations.emplace_back(world_from_camera);
    cameras.frames.push_back(i);
  }
  scene.cameras.push_back(cameras);
  scene.paths.push_back({"ground truth", "#3aa655", cameras.centers, true});
  scene.up = Eigen::Vector3d(0, -1, 0);
  scene.unit = "m";
  return scene;
}

HtmlPage EverySection() {
  HtmlPage page;
  page.title = "every section";
  page.sections.push_back(FactsSection("Summary", {{"status", "partial", PageTone::kWarning}}));
  page.sections.push_back(NoticeSection(PageTone::kBad, "Why", "no initial pair"));
  page.sections.push_back(SceneSection(RingScene()));
  Timeline timeline;
  timeline.states = {{"registered", "registered", "", "solid"},
                     {"keyframe", "keyframe", "", "marked"},
                     {"unregistered", "not registered", "#c3c9cf", "solid"}};
  timeline.groups = {{"model 1", "#e0452b"}, {"model 2", "#2f7fd0"}};
  for (int f = 0; f < 300; ++f) {
    timeline.frame_states.push_back(f >= 140 && f < 160 ? 2 : (f % 10 == 0 ? 1 : 0));
    timeline.frame_groups.push_back(f >= 140 && f < 160 ? -1 : (f < 140 ? 0 : 1));
  }
  timeline.notes = {{140, 159, "registration/visible_points: 12 of 30"}};
  page.sections.push_back(TimelineSection(timeline));
  LineChart errors;
  errors.x_label = "frame";
  errors.y_label = "position error (m)";
  errors.series.push_back({"model 1", "#e0452b", {0, 1, 2, 3}, {0.1, 0.2, std::nan(""), 0.1}});
  errors.marks.push_back({"not registered", "#f0a000", {2}});
  page.sections.push_back(LineChartSection(errors));
  TopView top;
  top.unit = "m";
  top.right_label = "x";
  top.up_label = "z";
  top.series.push_back({"ground truth", "#3aa655", {{0, 0}, {1, 0}, {2, 1}}, true, 5, "none"});
  top.series.push_back({"model 1", "#e0452b", {{0, 0.1}, {1.1, 0}, {2, 1.1}}, true, 1.6, "dot"});
  top.links = {0, 1};
  page.sections.push_back(TopViewSection(top));
  BarChart bars;
  bars.title = "M_score";
  bars.y_label = "M_score (%)";
  bars.groups = {"boundary", "overall"};
  bars.series = {{"comic", {40.9, 46.2}}, {"harris", {24.7, std::nan("")}}};
  page.sections.push_back(BarChartSection(bars));
  page.sections.push_back(BarChartsSection("side by side", {bars, bars}));
  ReportTable table({"detector", "points"});
  table.AddRow({std::string("comic"), int64_t{907}});
  page.sections.push_back(TableSection("Table", table, "", {"comic/report.html"}));
  const cv::Mat picture(60, 80, CV_8UC3, cv::Scalar(40, 120, 200));
  page.sections.push_back(ImagesSection("Frames", {{ImageDataUri(picture), "frame 0", "bad"}},
                                        {{"#ff0000", "boundary"}}));
  page.sections.push_back(
      ImagesSection("Strip", {{ImageDataUri(picture), "frame 0", ""}}, {}, "", true));
  page.sections.push_back(KeyValuesSection("Options", {{"a", {{"b", 1}}}}));
  page.sections.push_back(JsonSection("report.json", {{"status", "partial"}}));
  page.sections.push_back(TextSection("Text", {"one paragraph"}));
  return page;
}

TEST(HtmlPageInChromium, EverySectionDrawsWithoutAScriptError) {
  if (!ThreeJsAvailable(HtmlPageOptions().three_js_dir)) {
    GTEST_SKIP() << "libjs-three is not installed (scripts/install_deps.sh)";
  }
  comic::test::ScopedTempDir folder;
  const std::string path = folder.File("page.html");
  WriteHtmlPage(path, EverySection());
  std::string why;
  const auto page = comic::test::LoadInChromium(path, 1280, 1200, &why);
  if (!page) GTEST_SKIP() << why;
  EXPECT_EQ(HtmlAttribute(page->dom, "data-comic-page"), "drawn") << page->dom.substr(0, 4000);
  EXPECT_NE(page->dom.find("id=\"comic-page-errors\" hidden"), std::string::npos);
  // Every section got its element, none holds the "could not be drawn" notice.
  EXPECT_NE(page->dom.find("id=\"section-13\""), std::string::npos);
  EXPECT_EQ(page->dom.find(">This section could not be drawn"), std::string::npos);
  EXPECT_NE(page->dom.find("<svg class=\"chart\""), std::string::npos);
  // The 3-D view drew: WebGL pixels read back by the page, and in the screenshot.
  EXPECT_EQ(HtmlAttribute(page->dom, "data-scene"), "drawn");
  EXPECT_GT(std::stoi("0" + HtmlAttribute(page->dom, "data-scene-pixels")), 500);
  int x = 0, y = 0, w = 0, h = 0;
  ASSERT_EQ(std::sscanf(HtmlAttribute(page->dom, "data-scene-rect").c_str(), "%d,%d,%d,%d", &x, &y,
                        &w, &h),
            4);
  ASSERT_FALSE(page->screenshot.empty());
  ASSERT_LE(y + h, page->screenshot.rows) << "the window is too short for the 3-D view";
  const cv::Vec3b background(0x1d, 0x19, 0x15);  // #15191d in BGR
  const cv::Rect canvas(x, y, w, h);
  EXPECT_GT(comic::test::CountPixelsUnlike(page->screenshot, canvas, background), 500);
  // ...and the rest of the canvas is the view's background, not a blank page.
  EXPECT_GT(w * h - comic::test::CountPixelsUnlike(page->screenshot, canvas, background),
            w * h / 2);
}

}  // namespace
}  // namespace comic::io
