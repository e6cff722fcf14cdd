#include "frontend/evaluation/stereo_match_figure.h"

#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

constexpr int kTitleHeight = 28;
const cv::Scalar kCorrect(60, 200, 60);  // BGR
const cv::Scalar kWrong(40, 40, 230);
const cv::Scalar kUnmatched(170, 170, 170);
const cv::Scalar kBoundaryTint(255, 160, 60);

std::string Css(const cv::Scalar& bgr) {
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", static_cast<int>(bgr[2]),
                static_cast<int>(bgr[1]), static_cast<int>(bgr[0]));
  return text;
}

cv::Mat BasePanel(const io::MiddleburyPair& pair) {
  cv::Mat base;
  cv::cvtColor(pair.left_gray, base, cv::COLOR_GRAY2BGR);
  if (!pair.disc.empty()) {
    // Blend the boundary region towards blue so the matches on it stand out.
    cv::Mat tint(base.size(), base.type(), kBoundaryTint);
    cv::Mat blended;
    cv::addWeighted(base, 0.7, tint, 0.3, 0.0, blended);
    blended.copyTo(base, pair.disc == 255);
  }
  return base;
}

cv::Mat Panel(const io::MiddleburyPair& pair, const StereoRun& run, const StereoMethod& method,
              double max_cost) {
  cv::Mat image = BasePanel(pair);
  std::string title = method.Label();
  const StereoMatching* matching = nullptr;
  for (const StereoMatching& m : run.matchings) {
    if (m.method == method) matching = &m;
  }
  if (matching == nullptr) {
    title += ": not evaluated";
  } else {
    const StereoDetection& detection = run.DetectionFor(method.detector);
    std::vector<bool> matched(detection.left.size(), false);
    int accepted = 0;
    int correct = 0;
    for (size_t k = 0; k < matching->mutual.size(); ++k) {
      const PatchMatch& m = matching->mutual[k];
      if (matching->verdict[k] < 0 || m.cost > max_cost) continue;
      matched[m.index1] = true;
      ++accepted;
      correct += matching->verdict[k];
      const cv::Scalar colour = matching->verdict[k] == 1 ? kCorrect : kWrong;
      const Feature& l = detection.left[m.index1];
      const Feature& r = detection.right[m.index2];
      cv::line(image, l.Position(), r.Position(), colour, 1, cv::LINE_AA);
      cv::circle(image, l.Position(), 2, colour, cv::FILLED, cv::LINE_AA);
    }
    for (size_t i = 0; i < detection.left.size(); ++i) {
      const StereoPixelClass c = detection.left_class[i];
      if (matched[i] || (c != StereoPixelClass::kBoundary && c != StereoPixelClass::kNonBoundary)) {
        continue;
      }
      cv::circle(image, detection.left[i].Position(), 1, kUnmatched, cv::FILLED);
    }
    std::ostringstream threshold;
    threshold << max_cost;
    title += ", T = " + threshold.str() + ": " + std::to_string(correct) + " correct (green) / " +
             std::to_string(accepted) + " accepted / " + std::to_string(detection.detected[2]) +
             " detected";
  }
  cv::Mat panel(image.rows + kTitleHeight, image.cols, CV_8UC3, cv::Scalar(255, 255, 255));
  image.copyTo(panel(cv::Rect(0, kTitleHeight, image.cols, image.rows)));
  cv::putText(panel, title, {6, kTitleHeight - 9}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1,
              cv::LINE_AA);
  return panel;
}

}  // namespace

std::vector<io::PageLegendEntry> StereoMatchFigureLegend(double correct_tolerance) {
  char correct[160];
  std::snprintf(correct, sizeof(correct),
                "correct match: a line from the left feature to where its right partner was "
                "found, within %.1f px of the true position",
                correct_tolerance);
  // The tint is blended at 30 % over the grey image: show the colour it gives on mid grey.
  const cv::Scalar tinted = 0.7 * cv::Scalar(128, 128, 128) + 0.3 * kBoundaryTint;
  return {{Css(kCorrect), correct},
          {Css(kWrong), "wrong match: its partner is farther than that from the true position"},
          {Css(kUnmatched), "a valid left feature without an accepted match (grey dot)"},
          {Css(tinted),
           "blue band: pixels near a depth discontinuity (Middlebury's disc.png = "
           "255), the boundary region of the paper's split"}};
}

cv::Mat DrawStereoMatchFigure(const io::MiddleburyPair& pair, const StereoRun& run,
                              const std::vector<StereoMethod>& methods, double max_cost) {
  COMIC_CHECK(!methods.empty(), kInvalidArgument, "stereo figure: no methods to draw");
  COMIC_CHECK(!pair.left_gray.empty() && pair.left_gray.type() == CV_8UC1, kInvalidArgument,
              "stereo figure: the left image must be a non-empty 8-bit grey image");
  std::vector<cv::Mat> panels;
  for (const StereoMethod& method : methods) panels.push_back(Panel(pair, run, method, max_cost));
  cv::Mat figure;
  cv::hconcat(panels, figure);
  return figure;
}

}  // namespace comic::frontend
