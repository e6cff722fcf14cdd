// Per-frame object regions of tracking benchmarks, read from their text files: VOT polygons and
// OTB boxes. Line k of the file is the region of source frame k (0-based), whatever frames a run
// selects.
//
//   comic::io::RegionAnnotations regions =
//       comic::io::ReadRegionFile("vot_bag/groundtruth.txt");  // format detected per file
//   cv::Mat mask = comic::io::RasterizeRegion(regions.polygons[0], source_size, frame_size);
//
// Coordinate convention. Both formats index pixels from 1: OTB states it (x y w h, 1-based), and
// VOT's annotations come from its MATLAB toolkit, which uses the same convention. Returned
// polygons are in the project's convention (pixel centres at integer coordinates, top-left pixel
// centre (0, 0); see frontend/feature.h):
//   - a box (OTB, or a 4-number VOT rectangle) "x y w h" covers the w x h pixels whose top-left
//     one is (x, y), 1-based, so its polygon runs along their outer edges: (x − 1.5, y − 1.5) to
//     (x − 1.5 + w, y − 1.5 + h);
//   - a VOT polygon's vertices are points in 1-based pixel coordinates: 1 is subtracted.
// An annotation convention moves a region by at most a pixel either way — far less than the
// boundary band the evaluation uses (frontend/evaluation/region_labels.h).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace comic::io {

enum class RegionFileFormat {
  kAuto,        // per file: 8 or more numbers per line -> kVotPolygon, 4 -> kOtbBox
  kVotPolygon,  // VOT: "x1,y1,x2,y2,x3,y3,x4,y4" (any even count >= 6), or a "x,y,w,h" rectangle
  kOtbBox,      // OTB: "x y w h", separated by tabs, spaces or commas
};

// "auto", "vot", "otb" (throws comic::Error(kInvalidArgument) for anything else).
RegionFileFormat ParseRegionFileFormat(const std::string& name);
const char* RegionFileFormatName(RegionFileFormat format);

// A region as a closed polygon in 0-based pixel coordinates of the frames as stored. Empty for a
// frame the file marks as unannotated (a VOT line "0" or holding NaN).
using RegionPolygon = std::vector<cv::Point2d>;

struct RegionAnnotations {
  RegionFileFormat format = RegionFileFormat::kAuto;  // the format actually read
  std::vector<RegionPolygon> polygons;                // one per line, line k = source frame k
};

// Reads a VOT or OTB region file. Numbers may be separated by commas, tabs or spaces; blank
// trailing lines are ignored. Throws comic::Error: kNotFound for a missing file, kInvalidData
// naming the file and line for a line that is not a region of the format (wrong count of numbers,
// text, a box with negative size), kInvalidData for a file without any region.
RegionAnnotations ReadRegionFile(const std::string& path,
                                 RegionFileFormat format = RegionFileFormat::kAuto);

// Rasterises `polygon` (coordinates of frames of `source_size`) into a CV_8UC1 mask of
// `target_size` (the frames as a run uses them, e.g. resized to height 700): 255 for the pixels
// whose centre lies inside the polygon (even-odd rule; a centre exactly on a left or top edge is
// inside, on a right or bottom edge outside), 0 elsewhere. Coordinates map by the same per-axis
// factors as the image resize, pixel areas (not centres) scaling: x' = (x + 0.5)·sx − 0.5. So a
// box's mask has exactly its w x h pixels at the source size. An empty polygon gives an all-zero
// mask.
cv::Mat RasterizeRegion(const RegionPolygon& polygon, const cv::Size& source_size,
                        const cv::Size& target_size);

}  // namespace comic::io
