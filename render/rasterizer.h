// Draws a Scene as a camera sees it: every planar piece is rasterised through the homography
// between its plane and the image into a supersampled z-buffer (anti-aliased outlines), and the
// visible samples are shaded by a trilinear texture lookup (texture.h). Depth and the piece seen
// are those at each pixel's centre, so they are exact, not averaged across an outline.
//
// For a piece, the map from the normalised ray (u, v, 1) of a sample to the piece's (s, t) is the
// inverse of M = [R·s_axis | R·t_axis | R·origin + t]: G = M⁻¹ gives (s/z, t/z, 1/z) = G (u, v, 1),
// so the inverse depth 1/z is affine along an image row and the piece's outline cuts each row in
// one span found in closed form (pinhole lens). A distorted lens maps each sample through a table
// of its undistorted ray (Lens::NormalizedFromPixel), computed once.
//
//   Rasterizer rasterizer(lens, RasterOptions());
//   RenderedView view = rasterizer.Render(scene, cam_from_world);
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "render/lens.h"
#include "render/pose.h"
#include "render/scene.h"

namespace comic::render {

struct RasterOptions {
  // Samples per pixel along each axis (supersampling^2 per pixel, box-filtered): 1..8.
  int supersampling = 3;
  // Nothing nearer than this (metres) is drawn.
  double near_plane = 0.05;

  // Throws comic::Error(kInvalidArgument) naming the field.
  void Check() const;
};

struct RenderedView {
  cv::Mat color;  // CV_32FC3, BGR in 0..255 (empty for RenderGeometry)
  cv::Mat depth;  // CV_32F: z in metres of the surface at each pixel centre; 0 where none (sky)
  cv::Mat piece;  // CV_32S: index of the piece seen at each pixel centre; -1 where none
};

class Rasterizer {
 public:
  // Throws comic::Error(kInvalidArgument) for a bad lens or options.
  Rasterizer(const Lens& lens, const RasterOptions& options);

  const Lens& lens() const { return lens_; }
  const RasterOptions& options() const { return options_; }

  RenderedView Render(const Scene& scene, const Pose& cam_from_world) const;
  // Only the colour (motion-blur sub-frames).
  cv::Mat RenderColor(const Scene& scene, const Pose& cam_from_world) const;
  // Only depth and pieces.
  RenderedView RenderGeometry(const Scene& scene, const Pose& cam_from_world) const;

  // The normalised ray (u, v) of pixel centre (x, y) as the renderer uses it.
  Eigen::Vector2d RayOfPixel(int x, int y) const;

 private:
  // A regular grid of sample positions: pixel coordinate = offset + index * step.
  struct SampleGrid {
    int cols = 0;
    int rows = 0;
    double offset = 0.0;
    double step = 1.0;
    cv::Mat rays;             // distorted lens: CV_32FC2 (u, v) per sample; empty for a pinhole
    cv::Mat tile_ray_bounds;  // distorted lens: per tile, CV_32FC4 (u_min, u_max, v_min, v_max)
  };
  struct ZBuffer {
    cv::Mat inverse_depth;  // CV_32F, 0 = nothing
    cv::Mat piece;          // CV_32S, -1 = nothing
  };

  struct PieceView;      // a piece as this camera sees it (rasterizer.cc)
  struct ShadingPieces;  // what shading needs of every piece, in float

  SampleGrid MakeGrid(int per_pixel) const;
  std::vector<PieceView> ViewPieces(const Scene& scene, const Pose& pose) const;
  // Rasterises rows [row_begin, row_end) of `grid` into `band` (its row r is grid row
  // row_begin + r).
  void RasterizeRows(const Scene& scene, const std::vector<PieceView>& views,
                     const SampleGrid& grid, int row_begin, int row_end, ZBuffer* band) const;
  // Colour of pixel rows [y_begin, y_end) from `band`, their samples.
  void ShadeRows(const Scene& scene, const Pose& pose, const ShadingPieces& shading,
                 const ZBuffer& band, int y_begin, int y_end, cv::Mat* colour) const;
  // Depth (from the planes, in double) and pieces at the pixel centres.
  RenderedView Geometry(const std::vector<PieceView>& views, const ZBuffer& centre) const;
  RenderedView Draw(const Scene& scene, const Pose& pose, bool colour, bool geometry) const;

  Lens lens_;
  RasterOptions options_;
  SampleGrid samples_;
  SampleGrid centres_;  // used when the sample grid has no sample at the pixel centres
};

}  // namespace comic::render
