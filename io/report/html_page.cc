#include "io/report/html_page.h"

#include <string_view>
#include <vector>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/version.h"
#include "io/report/web_assets.h"

namespace comic::io {

namespace {

const char* const kThreeFiles[] = {"three.min.js", "examples/js/controls/OrbitControls.js"};

std::string EscapeHtml(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

// JSON inside <script type="application/json">: '<' (only ever inside strings) as \u003c, so no
// "</script>" or "<!--" in the data can end or disturb the element.
std::string ScriptSafeJson(const nlohmann::json& data) {
  const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string safe;
  safe.reserve(text.size());
  for (char c : text) {
    if (c == '<') {
      safe += "\\u003c";
    } else {
      safe += c;
    }
  }
  return safe;
}

// A script inlined as is, unless it holds "</script" (which would end the element early); our
// own and three.js's never do, and one that did is refused rather than broken.
void AppendScript(std::string_view name, std::string_view text, std::string* html) {
  std::string lower(text.size(), ' ');
  for (size_t i = 0; i < text.size(); ++i) {
    lower[i] = static_cast<char>(text[i] >= 'A' && text[i] <= 'Z' ? text[i] + 32 : text[i]);
  }
  COMIC_CHECK(lower.find("</script") == std::string::npos, kInvalidData,
              "cannot inline " << name << " into a page: it contains \"</script\"");
  *html += "<script>\n";
  *html += text;
  *html += "\n</script>\n";
}

bool HasSectionOfType(const HtmlPage& page, const std::string& type) {
  for (const nlohmann::json& section : page.sections) {
    if (section.value("type", "") == type) return true;
  }
  return false;
}

// The libraries of a page with a 3-D view, or a note for the page to show where it would be.
void AppendThreeJs(const HtmlPageOptions& options, nlohmann::json* data, std::string* html) {
  if (!ThreeJsAvailable(options.three_js_dir)) {
    (*data)["three_js_missing"] =
        "three.js was not found in " + options.three_js_dir +
        " when this page was written (Debian package libjs-three; scripts/install_deps.sh)";
    return;
  }
  for (const char* file : kThreeFiles) {
    AppendScript(file, ReadFileToString(JoinPaths(options.three_js_dir, file)), html);
  }
}

// `page_template` with each @NAME@ replaced by its value; the template alone is scanned, so a
// value that happens to hold "@DATA@" stays as it is.
std::string FillTemplate(std::string_view page_template,
                         const std::vector<std::pair<std::string, std::string>>& values) {
  std::string html;
  size_t done = 0;
  std::vector<bool> used(values.size(), false);
  for (size_t at = page_template.find('@'); at != std::string_view::npos;
       at = page_template.find('@', at + 1)) {
    for (size_t v = 0; v < values.size(); ++v) {
      if (page_template.substr(at, values[v].first.size()) != values[v].first) continue;
      html.append(page_template.substr(done, at - done));
      html += values[v].second;
      done = at + values[v].first.size();
      at = done - 1;
      used[v] = true;
      break;
    }
  }
  html.append(page_template.substr(done));
  for (size_t v = 0; v < values.size(); ++v) {
    COMIC_CHECK(used[v], kInvalidData, "page.html lacks the placeholder " << values[v].first);
  }
  return html;
}

}  // namespace

void HtmlPageOptions::Check() const {
  COMIC_CHECK(!three_js_dir.empty(), kInvalidArgument,
              "HtmlPageOptions: three_js_dir must name the folder of three.js");
}

bool ThreeJsAvailable(const std::string& three_js_dir) {
  for (const char* file : kThreeFiles) {
    if (!IsRegularFile(JoinPaths(three_js_dir, file))) return false;
  }
  return true;
}

std::string RenderHtmlPage(const HtmlPage& page, const HtmlPageOptions& options) {
  options.Check();
  COMIC_CHECK(page.sections.is_array(), kInvalidArgument, "HtmlPage: sections must be an array");
  nlohmann::json data = {{"title", page.title},
                         {"subtitle", page.subtitle},
                         {"generator", "comic-sfm " + Version()},
                         {"sections", page.sections}};
  // Our scripts: the page and its charts first, three.js and the 3-D view only where needed.
  std::string scripts;
  AppendScript("page.js", WebAsset("page.js"), &scripts);
  AppendScript("charts.js", WebAsset("charts.js"), &scripts);
  if (HasSectionOfType(page, "scene")) {
    AppendThreeJs(options, &data, &scripts);
    AppendScript("scene_canvas.js", WebAsset("scene_canvas.js"), &scripts);
    AppendScript("scene.js", WebAsset("scene.js"), &scripts);
  }
  scripts += "<script>ComicPage.render();</script>\n";

  return FillTemplate(WebAsset("page.html"), {{"@TITLE@", EscapeHtml(page.title)},
                                              {"@STYLE@", std::string(WebAsset("page.css"))},
                                              {"@DATA_ID@", kPageDataElementId},
                                              {"@DATA@", ScriptSafeJson(data)},
                                              {"@SCRIPTS@", scripts}});
}

void WriteHtmlPage(const std::string& path, const HtmlPage& page, const HtmlPageOptions& options) {
  WriteFileAtomically(path, RenderHtmlPage(page, options));
}

}  // namespace comic::io
