// A picture of a stereo evaluation run: for each chosen method, the left image with its accepted
// matches drawn as disparity vectors, green when correct and red when wrong, so that where a
// detector and matcher fail (e.g. at depth discontinuities, tinted blue) is visible at a glance.
//
//   cv::Mat figure = DrawStereoMatchFigure(pair, run, {{"comic",
//   MatchCost::kSplitMinOfFourPairings},
//                                                      {"harris", MatchCost::kFullPatch}}, 400.0);
//   io::WriteImageAtomically("matches.png", figure);
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/evaluation/stereo_evaluation.h"
#include "io/datasets/middlebury.h"
#include "io/report/page_sections.h"

namespace comic::frontend {

// One panel per method, side by side, each the size of the pair's left image plus a title bar.
// In each panel: boundary pixels (disc = 255) tinted blue; every accepted match (cost <= max_cost)
// of a valid left feature as a line from the left feature to its right partner's position,
// green if correct, red if wrong, with a dot on the left feature; valid left features without an
// accepted match as small grey dots; excluded features (unknown disparity, occluded) not drawn.
// A method absent from the run gives a panel saying so. The title gives the method and its
// overall correct / accepted / detected counts. Throws comic::Error(kInvalidArgument) for an
// empty method list.
cv::Mat DrawStereoMatchFigure(const io::MiddleburyPair& pair, const StereoRun& run,
                              const std::vector<StereoMethod>& methods, double max_cost);

// What DrawStereoMatchFigure's colours mean, as a page legend (io/report/page_sections.h);
// `correct_tolerance` is StereoEvaluationOptions::correct_tolerance (pixels).
std::vector<io::PageLegendEntry> StereoMatchFigureLegend(double correct_tolerance);

}  // namespace comic::frontend
