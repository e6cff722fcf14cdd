// Boundary / non-boundary / outside labels of an object region (paper §5: scores are reported
// separately for points on the object boundary, internal points and all points on the object;
// features off the object are left out).
//
// One rule for every kind of region. The region is a binary mask per frame: a DAVIS object mask,
// or a VOT polygon / OTB box rasterised (the paper approximates the object region of tracking
// sequences by the ground-truth box; io/datasets/region_annotations.h). A pixel is
//   kBoundary  if it lies within `band` pixels of the region's edge, on either side — measured
//              centre to centre to the nearest pixel across the edge;
//   kInterior  if it is inside the region and farther than `band` from the edge;
//   kOutside   if it is outside the region and farther than `band` from the edge.
// The band reaches outside the mask because a corner on the silhouette is often localised a
// pixel or two off the annotation (annotations are not pixel-exact, boxes least of all). The
// default band, 11 px = the 23x23 patch's half-width, makes "boundary" mean "the matching patch
// straddles the object's edge" — exactly the features the paper's split matching is for. For a
// box region, "boundary" is the band along the box's sides: it contains the object's true
// silhouette only where the box is tight, so box-based boundary scores are an approximation, as
// in the paper.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

enum class RegionLabel : uint8_t { kOutside = 0, kBoundary = 1, kInterior = 2 };

const char* RegionLabelName(RegionLabel label);  // "outside", "boundary", "interior"

// Per-pixel labels (CV_8UC1 holding RegionLabel values) of a CV_8UC1 region mask (non-zero =
// object) with boundary band `band` pixels (> 0). An all-zero mask labels everything kOutside; a
// mask without background, everything kInterior. Throws comic::Error(kInvalidArgument) for an
// empty mask, a wrong type or band <= 0.
cv::Mat LabelRegion(const cv::Mat& mask, double band);

// The label of each feature: that of the pixel at its rounded position (kOutside off the image).
std::vector<RegionLabel> LabelFeatures(const cv::Mat& labels, const FeatureSet& features);

// The mask of pixels labelled kBoundary or kInterior (the object region a threshold is equalised
// on): 255 there, 0 elsewhere.
cv::Mat EvaluatedRegionMask(const cv::Mat& labels);

}  // namespace comic::frontend
