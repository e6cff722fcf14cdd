// The single-file page: self-contained (no address outside the file), its data intact and unable
// to break out of its element, three.js inlined only for a 3-D view, deterministic.
#include "io/report/html_page.h"

#include <gtest/gtest.h>

#include <regex>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/report/page_scene.h"
#include "io/report/page_sections.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

// The JSON of the page's data element.
nlohmann::json PageData(const std::string& html) {
  const std::string open = std::string("id=\"") + kPageDataElementId + "\">";
  const size_t begin = html.find(open);
  EXPECT_NE(begin, std::string::npos);
  const size_t start = begin + open.size();
  const size_t end = html.find("</script>", start);
  return nlohmann::json::parse(html.substr(start, end - start));
}

size_t Count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

HtmlPage TextPage() {
  HtmlPage page;
  page.title = "a <title> & \"quotes\"";
  page.subtitle = "comic_sfm frames --output out";
  page.sections.push_back(FactsSection("Summary", {{"status", "success", PageTone::kGood}}));
  // Data that would end the script element, or look like a placeholder of the template.
  page.sections.push_back(
      TextSection("Tricky", {"</script><script>alert(1)</script>", "<!-- @DATA@ @SCRIPTS@"}));
  return page;
}

TEST(RenderHtmlPage, HoldsItsDataIntactAndSafe) {
  const std::string html = RenderHtmlPage(TextPage());
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("<title>a &lt;title&gt; &amp; &quot;quotes&quot;</title>"),
            std::string::npos);
  const nlohmann::json data = PageData(html);
  EXPECT_EQ(data["title"], "a <title> & \"quotes\"");
  EXPECT_EQ(data["subtitle"], "comic_sfm frames --output out");
  ASSERT_EQ(data["sections"].size(), 2u);
  EXPECT_EQ(data["sections"][1]["paragraphs"][0], "</script><script>alert(1)</script>");
  EXPECT_EQ(data["sections"][1]["paragraphs"][1], "<!-- @DATA@ @SCRIPTS@");
  // Every "</script>" closes one of the page's own elements: the data's are escaped.
  EXPECT_EQ(Count(html, "<script"), Count(html, "</script>"));
  EXPECT_EQ(Count(html, "alert(1)</script>"), 0u);
  // The scripts that draw the page are in it, and the call that starts them.
  EXPECT_NE(html.find("window.ComicPage"), std::string::npos);
  EXPECT_NE(html.find("ComicPage.render();"), std::string::npos);
}

TEST(RenderHtmlPage, ReferencesNothingOutsideTheFile) {
  const std::string html = RenderHtmlPage(TextPage());
  const std::regex external(R"((src|href)\s*=\s*["']?(https?:|//|file:))");
  EXPECT_FALSE(std::regex_search(html, external));
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
}

TEST(RenderHtmlPage, IsDeterministic) {
  EXPECT_EQ(RenderHtmlPage(TextPage()), RenderHtmlPage(TextPage()));
}

HtmlPage ScenePage() {
  HtmlPage page;
  page.title = "scene";
  Scene scene;
  scene.points = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 1)};
  page.sections.push_back(SceneSection(scene));
  return page;
}

TEST(RenderHtmlPage, InlinesThreeJsOnlyForA3DView) {
  HtmlPageOptions options;
  if (!ThreeJsAvailable(options.three_js_dir)) {
    GTEST_SKIP() << "libjs-three is not installed (scripts/install_deps.sh)";
  }
  const std::string three = ReadFileToString(JoinPaths(options.three_js_dir, "three.min.js"));
  const std::string with_scene = RenderHtmlPage(ScenePage(), options);
  EXPECT_NE(with_scene.find(three), std::string::npos);
  EXPECT_NE(with_scene.find("OrbitControls"), std::string::npos);
  EXPECT_FALSE(PageData(with_scene).contains("three_js_missing"));
  const std::string without = RenderHtmlPage(TextPage(), options);
  EXPECT_EQ(without.find("OrbitControls"), std::string::npos);
  EXPECT_LT(without.size(), 100000u);  // the page's own scripts are small
}

TEST(RenderHtmlPage, SaysWhereThreeJsWasMissing) {
  comic::test::ScopedTempDir empty;
  HtmlPageOptions options;
  options.three_js_dir = empty.path();
  EXPECT_FALSE(ThreeJsAvailable(empty.path()));
  const std::string html = RenderHtmlPage(ScenePage(), options);
  const nlohmann::json data = PageData(html);
  ASSERT_TRUE(data.contains("three_js_missing"));
  EXPECT_NE(data["three_js_missing"].get<std::string>().find("libjs-three"), std::string::npos);
  EXPECT_LT(html.size(), 100000u);  // no three.js (850 kB) in it
}

TEST(WriteHtmlPage, WritesTheRenderedFile) {
  comic::test::ScopedTempDir folder;
  WriteHtmlPage(folder.File("report.html"), TextPage());
  EXPECT_EQ(ReadFileToString(folder.File("report.html")), RenderHtmlPage(TextPage()));
  HtmlPageOptions bad;
  bad.three_js_dir = "";
  EXPECT_THROW(RenderHtmlPage(TextPage(), bad), Error);
}

}  // namespace
}  // namespace comic::io
