// numpy arrays <-> the libraries' images, features, matches and tracks: an 8-bit image in, the
// features out as plain columns (comic/__init__.py packs them into structured arrays) and back,
// the matches and tracks as columns.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/feature.h"
#include "frontend/matching/patch_matcher.h"
#include "frontend/matching/tracker.h"
#include "io/core/pixel_budget.h"

namespace comic::python {

namespace py = pybind11;

// An 8-bit numpy image, H x W (grey) or H x W x 3 (BGR, as cv2 reads it), copied into a grey
// cv::Mat; more than `max_pixels` pixels are refused before the copy (the apps' budget).
cv::Mat GrayFromArray(const py::array& image, const std::string& what,
                      int64_t max_pixels = io::kDefaultMaxPixels);

// An 8-bit image (grey or BGR) as a numpy array, H x W or H x W x 3.
py::array_t<uint8_t> ArrayFromImage(const cv::Mat& image);

// The features as columns (x, y, scale, response, cornerness, level, polarity), the side masks
// as an N x 23 x 23 uint8 array (0: neither side, 1: ic+, 2: ic−; all 0 without side information)
// and has_side_mask.
py::dict FeaturesToColumns(const frontend::FeatureSet& features);

// The inverse of FeaturesToColumns (the masks may be None: no side information).
frontend::FeatureSet FeaturesFromColumns(const py::dict& columns, const py::object& side_masks,
                                         const std::string& what);

// index1, index2, cost.
py::dict MatchesToColumns(const std::vector<frontend::PatchMatch>& matches);

// The tracks' frames (features per frame as FeaturesToColumns) and their observations as columns
// (track, frame, feature).
py::dict TracksToPython(const frontend::FeatureTracks& tracks);

}  // namespace comic::python
