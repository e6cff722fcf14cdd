// Rectified stereo pairs with exact disparity, laid out as a Middlebury 2003 folder so that
// comic_stereo_eval --middlebury reads them unchanged (io/datasets/middlebury.h):
//   im2.png          left image (a frame of the sequence)
//   im6.png          right image: the same camera moved `baseline` metres along its x axis
//   groundtruth.png  left disparity x 4, 8-bit (so at most 63.75 px; 0 = unknown: sky, or
//                    farther than the 8 bits hold)
//   nonocc.png       255 where the left pixel is seen by the right camera (same surface there)
//   disc.png         255 non-occluded pixels in the occlusion-boundary band, 128 other
//                    non-occluded pixels, 0 occluded or unknown (Middlebury's convention)
// A pixel (x, y) of the left image corresponds to (x - d, y) in the right, d = fx · baseline / z.
#pragma once

#include <cstdint>
#include <string>

#include "render/occlusion_boundary.h"
#include "render/rasterizer.h"
#include "render/scene_builder.h"
#include "render/sensor.h"

namespace comic::render {

struct StereoPairOptions {
  double baseline = 0.2;  // metres, right camera to the right of the left one
  // Relative depth difference within which the right camera sees the same surface (nonocc).
  double depth_tolerance = 0.01;
  // disc.png's band: Middlebury's discontinuity regions are the discontinuities dilated by a 9x9
  // window (Scharstein & Szeliski 2002), so 4 px either side.
  BoundaryOptions boundary = {0.03, 4.0};

  void Check() const;
};

// Renders frame `frame` of `built` and its right partner into `folder` (created). Throws
// comic::Error(kInvalidArgument) for a distorted lens (a rectified pair needs a pinhole) or bad
// options, kIo when writing fails.
void WriteStereoPair(const BuiltScene& built, const Rasterizer& rasterizer, uint64_t seed,
                     const SensorOptions& sensor, int frame, const StereoPairOptions& options,
                     const std::string& folder);

}  // namespace comic::render
