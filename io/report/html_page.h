// A report as one self-contained HTML file: the page's CSS and JavaScript (io/report/web/,
// compiled in), its data as inline JSON and, when it holds a 3-D view, three.js from Debian's
// libjs-three read at write time; images are data: URIs. It opens offline in any browser, can
// be mailed as one file, and draws itself from the JSON, so the numbers on the page are the
// numbers of the run.
//
//   HtmlPage page;
//   page.title = "comic_sfm: kitti06_000-011";
//   page.sections.push_back(FactsSection("Summary", {{"status", "success", PageTone::kGood}}));
//   WriteHtmlPage("out/report.html", page);
//
// The section types and their fields are listed in page_sections.h, page_charts.h and
// page_scene.h; io/report/web/page.js draws them. When the page has drawn, its <html> element
// carries data-comic-page="drawn" (or "error" with the messages in #comic-page-errors), which is
// what the headless-browser tests read.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace comic::io {

struct HtmlPageOptions {
  // Where Debian's libjs-three puts three.js: three.min.js and
  // examples/js/controls/OrbitControls.js are inlined from here into pages with a 3-D view.
  // Without them the page is still written and says what is missing where the view would be.
  std::string three_js_dir = "/usr/share/javascript/three";
  // Throws comic::Error(kInvalidArgument) for an empty three_js_dir.
  void Check() const;
};

struct HtmlPage {
  std::string title;     // the <title> and the heading
  std::string subtitle;  // one line under the heading (e.g. the command), may be empty
  // The sections in order, as made by the *Section functions of page_sections.h, page_charts.h
  // and page_scene.h.
  nlohmann::json sections = nlohmann::json::array();
};

// The id of the <script type="application/json"> element holding {title, subtitle, sections}.
inline constexpr const char* kPageDataElementId = "comic-page-data";

// The whole file. Deterministic: the same page gives the same bytes.
std::string RenderHtmlPage(const HtmlPage& page, const HtmlPageOptions& options = {});

// RenderHtmlPage written atomically (io/core/file_utils.h). Throws comic::Error(kIo).
void WriteHtmlPage(const std::string& path, const HtmlPage& page,
                   const HtmlPageOptions& options = {});

// Whether three.js and its OrbitControls are readable under `three_js_dir`.
bool ThreeJsAvailable(const std::string& three_js_dir);

}  // namespace comic::io
