// Loading a report page (io/report/html_page.h) in Debian's headless Chromium, for the tests that
// check a page draws: one launch gives the DOM after the scripts ran (--dump-dom) and a
// screenshot. The page says itself whether it drew: <html data-comic-page="drawn"> (or "error",
// with the messages in #comic-page-errors), and a 3-D view leaves data-scene-pixels (pixels it
// drew, read back from WebGL) and data-scene-rect (where its canvas is on the page).
//
// WebGL under headless Chromium: Debian's build falls back to SwiftShader (software) only when
// asked with --enable-unsafe-swiftshader (the silent fallback is deprecated); --use-angle=
// swiftshader picks it directly. Pages are local files written by the test: nothing untrusted.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <regex>
#include <string>

#include "tests/test_support.h"

namespace comic::test {

struct BrowserPage {
  std::string dom;     // the document after its scripts ran
  cv::Mat screenshot;  // BGR, the window's size
};

// The value of attribute `name` of the <html> element in `dom` ("" when absent).
inline std::string HtmlAttribute(const std::string& dom, const std::string& name) {
  std::smatch match;
  const std::regex html_tag("<html[^>]*>");
  if (!std::regex_search(dom, match, html_tag)) return "";
  const std::string tag = match.str();
  const std::regex attribute(" " + name + "=\"([^\"]*)\"");
  return std::regex_search(tag, match, attribute) ? match[1].str() : "";
}

// Loads `html_file` in headless Chromium in a window of `width` x `height` CSS pixels; with
// `webgl` false, in a browser that offers no WebGL at all (--disable-webgl --disable-3d-apis), as
// on a machine without a GPU or with WebGL switched off. std::nullopt, with the reason in `why`,
// when Chromium is not installed or cannot start here (the caller skips); a page that loads but
// fails is a BrowserPage whose DOM says so.
inline std::optional<BrowserPage> LoadInChromium(const std::string& html_file, int width,
                                                 int height, std::string* why, bool webgl = true) {
  if (RunCommand("command -v chromium").exit_code != 0) {
    *why = "chromium is not installed (scripts/install_deps.sh installs it)";
    return std::nullopt;
  }
  ScopedTempDir profile;  // a new empty profile for every launch
  const std::string screenshot = profile.File("screenshot.png");
  const std::string command =
      "timeout 180 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync " +
      std::string(webgl ? "--use-angle=swiftshader --enable-unsafe-swiftshader "
                        : "--disable-webgl --disable-3d-apis ") +
      "--hide-scrollbars "
      "--user-data-dir=" +
      profile.File("profile") + " --window-size=" + std::to_string(width) + "," +
      std::to_string(height) + " --screenshot=" + screenshot + " --dump-dom 'file://" + html_file +
      "' 2>/dev/null";
  const CommandResult result = RunCommand(command);
  BrowserPage page;
  page.dom = result.output;
  page.screenshot = cv::imread(screenshot, cv::IMREAD_COLOR);
  if (page.dom.find("<html") == std::string::npos) {
    *why = "chromium did not start here (exit " + std::to_string(result.exit_code) + ")";
    return std::nullopt;
  }
  return page;
}

// Pixels of `rect` in `image` that differ from `background` (BGR) by more than `tolerance` in sum.
inline int CountPixelsUnlike(const cv::Mat& image, const cv::Rect& rect,
                             const cv::Vec3b& background, int tolerance = 30) {
  const cv::Rect inside = rect & cv::Rect(0, 0, image.cols, image.rows);
  int count = 0;
  for (int y = inside.y; y < inside.y + inside.height; ++y) {
    for (int x = inside.x; x < inside.x + inside.width; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      const int difference = std::abs(p[0] - background[0]) + std::abs(p[1] - background[1]) +
                             std::abs(p[2] - background[2]);
      count += difference > tolerance;
    }
  }
  return count;
}

}  // namespace comic::test
