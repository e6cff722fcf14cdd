#include "frontend/evaluation/track_drawing.h"

#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {

namespace {

// BGR, and the same colours as CSS for the legends.
const cv::Scalar kRegionEdge(255, 160, 0);
const cv::Scalar kBoundary(0, 0, 255);
const cv::Scalar kInterior(0, 220, 0);
const cv::Scalar kOutside(0, 255, 255);
const cv::Scalar kUntracked(160, 160, 160);

std::string Css(const cv::Scalar& bgr) {
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", static_cast<int>(bgr[2]),
                static_cast<int>(bgr[1]), static_cast<int>(bgr[0]));
  return text;
}

}  // namespace

std::vector<io::PageLegendEntry> TrackDrawingLegend(bool with_regions) {
  if (!with_regions) {
    return {{Css(kOutside),
             "a track through this frame: its path over the last frames and a dot "
             "at its feature"},
            {Css(kUntracked), "a feature in no track through this frame (small cross)"}};
  }
  return {{Css(kBoundary), "track at a feature on the object's boundary (within the band)"},
          {Css(kInterior), "track at a feature inside the object"},
          {Css(kOutside), "track at a feature outside the object"},
          {Css(kRegionEdge), "the object region's outline"},
          {Css(kUntracked), "a feature in no track through this frame (small cross)"}};
}

cv::Mat DrawTracks(const cv::Mat& bgr, const FeatureTracks& tracks, int frame,
                   const std::vector<RegionLabel>& labels, const cv::Mat& region_labels,
                   const TrackDrawingOptions& options) {
  COMIC_CHECK(!bgr.empty() && bgr.type() == CV_8UC3, kInvalidArgument,
              "DrawTracks: expected an 8-bit colour image");
  COMIC_CHECK(frame >= 0 && frame < static_cast<int>(tracks.NumFrames()), kInvalidArgument,
              "DrawTracks: frame " << frame << " out of range");
  const FeatureSet& features = tracks.features[frame];
  COMIC_CHECK(labels.empty() || labels.size() == features.size(), kInvalidArgument,
              "DrawTracks: " << labels.size() << " labels for " << features.size() << " features");
  COMIC_CHECK(region_labels.empty() || region_labels.size() == bgr.size(), kInvalidArgument,
              "DrawTracks: region labels of the wrong size");
  cv::Mat canvas = bgr.clone();
  if (!region_labels.empty()) {
    const cv::Mat object = region_labels != static_cast<int>(RegionLabel::kOutside);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(object, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(canvas, contours, -1, kRegionEdge, 1, cv::LINE_AA);
  }
  const auto colour_of = [&](int feature) {
    if (labels.empty()) return kOutside;
    switch (labels[feature]) {
      case RegionLabel::kBoundary:
        return kBoundary;
      case RegionLabel::kInterior:
        return kInterior;
      case RegionLabel::kOutside:
        break;
    }
    return kOutside;
  };
  std::vector<bool> tracked(features.size(), false);
  constexpr int kShift = 4;  // sub-pixel drawing
  const auto fixed = [](const cv::Point2f& p) {
    return cv::Point(cvRound(p.x * (1 << kShift)), cvRound(p.y * (1 << kShift)));
  };
  for (const Track& track : tracks.tracks) {
    if (track.FirstFrame() > frame || track.LastFrame() < frame) continue;
    std::vector<cv::Point> path;
    int current = -1;
    for (const TrackObservation& obs : track.observations) {
      if (obs.frame > frame || obs.frame < frame - options.history) continue;
      path.push_back(fixed(tracks.FeatureOf(obs).Position()));
      if (obs.frame == frame) current = obs.feature;
    }
    if (current < 0) continue;  // the track skips this frame
    tracked[current] = true;
    const cv::Scalar colour = colour_of(current);
    cv::polylines(canvas, path, false, colour, 1, cv::LINE_AA, kShift);
    cv::circle(canvas, path.back(), 2 << kShift, colour, cv::FILLED, cv::LINE_AA, kShift);
  }
  if (options.show_untracked) {
    for (size_t i = 0; i < features.size(); ++i) {
      if (tracked[i]) continue;
      const cv::Point p(cvRound(features[i].x), cvRound(features[i].y));
      cv::drawMarker(canvas, p, kUntracked, cv::MARKER_CROSS, 5, 1);
    }
  }
  return canvas;
}

}  // namespace comic::frontend
