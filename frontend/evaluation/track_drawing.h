// Pictures of tracks on a frame, for the evaluation reports and for inspecting a tracker.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/evaluation/region_labels.h"
#include "frontend/matching/track.h"
#include "io/report/page_sections.h"

namespace comic::frontend {

struct TrackDrawingOptions {
  // Draw each track's path over at most this many frames up to the drawn one.
  int history = 5;
  // Also mark the frame's features that are in no track through it (small grey crosses).
  bool show_untracked = true;
};

// A copy of `bgr` (CV_8UC3, the size the features live in) with the tracks through `frame`: each
// one's path over its last observations and a dot at its feature in `frame`, coloured by that
// feature's label (boundary red, interior green; outside or unlabelled yellow). `labels` is empty
// or holds one label per feature of `frame`; `region_labels` is empty or the frame's label map
// (LabelRegion), whose region edge is outlined. Throws comic::Error(kInvalidArgument) for a frame
// out of range or inputs of the wrong size.
cv::Mat DrawTracks(const cv::Mat& bgr, const FeatureTracks& tracks, int frame,
                   const std::vector<RegionLabel>& labels = {},
                   const cv::Mat& region_labels = cv::Mat(),
                   const TrackDrawingOptions& options = {});

// What DrawTracks' colours mean, as a page legend (io/report/page_sections.h); `with_regions`:
// the boundary / interior / outside colours and the region's outline.
std::vector<io::PageLegendEntry> TrackDrawingLegend(bool with_regions);

}  // namespace comic::frontend
