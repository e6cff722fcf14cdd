// The side mask of a CoMIC feature: which pixels of its 23 x 23 patch lie on the ic+ and ic- sides
// of its MSICS (paper §4, Fig. 7), used by the matcher to compare the two sides separately.
//
// The MSICS is only ~25 samples long, and the patch may hold other texture, so the sides are
// split geometrically by the feature's own iso-curve, not by thresholding the patch: the curve is
// traced at the MSICS's threshold through the whole patch (continuing the MSICS along the same
// level line until it leaves the patch or closes), its crossings cut the 4-neighbour links they
// pass between, and the patch is flood-filled from both sides of the cut. ic+ (kPlus) is the
// bright side (values above the level), ic- (kMinus) the dark side. Pixels whose centre lies
// within half a pixel of the curve (mixed values) and pixels outside the image are kNone. Where
// the curve ends inside the patch (at the image border) the two fills meet halfway.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

// Side labels of the kPatchSize x kPatchSize patch centred on `centre` (row-major, as
// Feature::side_mask) for the iso-curve of `gray` (CV_8UC1) at `threshold` passing nearest to
// `curve_point`. All kNone if no curve of that threshold passes within 2 px of curve_point.
std::vector<PatchSide> ComputeSideMask(const cv::Mat& gray, double threshold,
                                       const cv::Point2f& curve_point, const cv::Point& centre);

}  // namespace comic::frontend
