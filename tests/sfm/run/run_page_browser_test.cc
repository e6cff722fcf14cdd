// report.html of real runs in a real browser (Debian's headless Chromium): the bundled example's
// page loads without a script error and draws its 3-D view (WebGL pixels read back by the page
// and seen in the screenshot where its canvas is), and in a browser without WebGL draws the same
// view on a 2-D canvas; a failed run's page draws too. Skipped where Chromium is missing or
// cannot start.
#include <gtest/gtest.h>

#include <cstdio>

#include "io/core/file_utils.h"
#include "sfm/run/reconstruction_run.h"
#include "tests/headless_browser.h"

namespace comic::sfm {
namespace {

using comic::test::ExampleDir;
using comic::test::HtmlAttribute;
using comic::test::ScopedTempDir;

std::string WriteExamplePage(const ScopedTempDir& dir, int last_frame) {
  ReconstructionRunOptions options;
  options.frames = ExampleDir() + "/image_l";
  options.gt = ExampleDir() + "/poses.txt";
  options.sequence.last_frame = last_frame;
  options.output = dir.File("out");
  RunReconstruction(options);
  return io::JoinPaths(options.output, "report.html");
}

// The bundled example's page, written once per test process for the tests that load it.
const std::string& ExamplePage() {
  static const ScopedTempDir dir;
  static const std::string path = WriteExamplePage(dir, -1);
  return path;
}

// The pixels of the 3-D view's canvas (data-scene-rect) in the screenshot unlike its background.
int DrawnInScreenshot(const comic::test::BrowserPage& page) {
  int x = 0, y = 0, w = 0, h = 0;
  EXPECT_EQ(std::sscanf(HtmlAttribute(page.dom, "data-scene-rect").c_str(), "%d,%d,%d,%d", &x, &y,
                        &w, &h),
            4);
  EXPECT_FALSE(page.screenshot.empty());
  EXPECT_LE(y + h, page.screenshot.rows) << "the window is too short for the 3-D view";
  const cv::Vec3b background(0x1d, 0x19, 0x15);  // #15191d in BGR
  const int drawn =
      comic::test::CountPixelsUnlike(page.screenshot, cv::Rect(x, y, w, h), background);
  EXPECT_LT(drawn, w * h / 2);  // on the view's dark background
  return drawn;
}

TEST(RunPageInChromium, TheBundledExampleDrawsIts3DView) {
  if (!io::ThreeJsAvailable(io::HtmlPageOptions().three_js_dir)) {
    GTEST_SKIP() << "libjs-three is not installed (scripts/install_deps.sh)";
  }
  const std::string& path = ExamplePage();
  std::string why;
  const auto page = comic::test::LoadInChromium(path, 1280, 1600, &why);
  if (!page) GTEST_SKIP() << why;
  EXPECT_EQ(HtmlAttribute(page->dom, "data-comic-page"), "drawn");
  EXPECT_NE(page->dom.find("id=\"comic-page-errors\" hidden"), std::string::npos);
  EXPECT_EQ(HtmlAttribute(page->dom, "data-scene"), "drawn");
  EXPECT_GT(std::stoi("0" + HtmlAttribute(page->dom, "data-scene-pixels")), 1000);
  EXPECT_GT(DrawnInScreenshot(*page), 1000);  // points and frusta
}

// Without WebGL (no GPU, or WebGL switched off) the view is projected on a 2-D canvas: the page
// counts the points it drew inside the canvas and the pixels it coloured, and the screenshot
// shows them. The diagnostics sections (charts, table, histogram, match matrix) draw as well.
TEST(RunPageInChromium, TheBundledExampleDraws3DWithoutWebGL) {
  const std::string& path = ExamplePage();
  std::string why;
  const auto page = comic::test::LoadInChromium(path, 1280, 1600, &why, /*webgl=*/false);
  if (!page) GTEST_SKIP() << why;
  EXPECT_EQ(HtmlAttribute(page->dom, "data-comic-page"), "drawn");
  EXPECT_NE(page->dom.find("id=\"comic-page-errors\" hidden"), std::string::npos);
  EXPECT_EQ(HtmlAttribute(page->dom, "data-scene"), "drawn-2d");
  EXPECT_NE(page->dom.find("Drawn without WebGL"), std::string::npos);
  EXPECT_GT(std::stoi("0" + HtmlAttribute(page->dom, "data-scene-points")), 500);
  EXPECT_GT(std::stoi("0" + HtmlAttribute(page->dom, "data-scene-pixels")), 1000);
  EXPECT_GT(DrawnInScreenshot(*page), 1000);
  for (const char* section : {"section-histogram", "section-heatmap", "table-scroll tall"}) {
    EXPECT_NE(page->dom.find(section), std::string::npos) << section;
  }
}

TEST(RunPageInChromium, AFailedRunsPageDraws) {
  ScopedTempDir dir;
  const std::string path = WriteExamplePage(dir, 0);  // one frame: no model
  std::string why;
  const auto page = comic::test::LoadInChromium(path, 1280, 900, &why);
  if (!page) GTEST_SKIP() << why;
  EXPECT_EQ(HtmlAttribute(page->dom, "data-comic-page"), "drawn");
  EXPECT_NE(page->dom.find("Why the reconstruction failed"), std::string::npos);
  EXPECT_EQ(HtmlAttribute(page->dom, "data-scene"), "");  // no 3-D view without a model
}

}  // namespace
}  // namespace comic::sfm
