// Occlusion boundaries of a rendered view: where the surface seen jumps in depth between two
// neighbouring pixels. Neighbours on different pieces meet at a discontinuity unless each piece's
// plane, extended, passes within `depth_ratio` (relative depth) of the other's surface at the other
// pixel — so the crease between two faces of a box, or a box standing on the ground, is not a
// boundary, while a pole in front of a wall, a tree against the sky and the far edge of a
// façade are. Pixels against the sky (nothing drawn) always count.
#pragma once

#include <opencv2/core.hpp>

#include "render/pose.h"
#include "render/rasterizer.h"
#include "render/scene.h"

namespace comic::render {

struct BoundaryOptions {
  // Relative depth difference (each plane extended to the other pixel) that makes a boundary.
  double depth_ratio = 0.03;
  // Half-width of the band marked around each boundary: pixels whose centre is within this many
  // pixels of a pixel touching a discontinuity (those touching it included).
  double band_px = 2.0;

  void Check() const;
};

// CV_8UC1: 255 within the band of an occlusion boundary, 0 elsewhere. `view` must come from
// `rasterizer` with `scene` and `cam_from_world`.
cv::Mat OcclusionBoundaryMask(const Scene& scene, const Pose& cam_from_world,
                              const Rasterizer& rasterizer, const RenderedView& view,
                              const BoundaryOptions& options);

// CV_8UC1: 255 where the pixel centre sees a foreground object (SceneObject::foreground).
cv::Mat ForegroundMask(const Scene& scene, const RenderedView& view);

// CV_16UC1: the object id seen at each pixel centre (0: nothing).
cv::Mat ObjectIds(const Scene& scene, const RenderedView& view);

}  // namespace comic::render
