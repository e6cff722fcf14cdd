// Where a feature's patch lies in the next frame, found by aligning the patch itself rather than
// by re-detecting it (issue 30): pyramidal Lucas–Kanade (Lucas & Kanade 1981; Bouguet's pyramidal
// scheme, as OpenCV's calcOpticalFlowPyrLK) with an affine photometric model, I2(x + d) ≈
// g·I1(x) + b, so a change of exposure or of the camera's gain does not pull the alignment, and
// with optional per-pixel weights, so a feature on an object's silhouette can be aligned by its
// object side alone (the part of the patch that moves with it; paper §4, Fig. 7) while the
// background behind it changes.
//
//   ImagePyramid pyramid1(gray1, options.levels), pyramid2(gray2, options.levels);  // once per
//   frame PatchAlignment a = AlignPatch(pyramid1, feature.Position(), pyramid2, predicted, {},
//   options); if (a.converged) { /* a.position in frame 2, a.residual after gain and bias */ }
//
// Each level: the template (the window around the point in frame 1, sampled bilinearly) and its
// gradients are fixed; every iteration samples frame 2 at the current displacement, fits gain and
// bias in closed form (least squares over the weighted pixels), and takes a Gauss–Newton step on
// the translation with the template gradients scaled by the gain. The result at a level,
// doubled, starts the next finer one; the prediction (e.g. the feature's velocity) starts the
// coarsest, so a motion of up to about 2^levels · window/2 pixels from the prediction is found.
// Deterministic: the result depends only on the images, the points and the options.
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

struct PatchAlignmentOptions {
  // Pyramid levels above the frame (each half the size of the one below).
  int levels = 3;
  // Window side in pixels at every level (odd); the matcher's patch by default.
  int window = kPatchSize;
  // Gauss–Newton iterations per level at most, and the step (pixels of that level) below which a
  // level has converged.
  int max_iterations = 20;
  double min_step_px = 0.02;
  // Windows whose template has a smaller minimum eigenvalue of its mean gradient moment (grey
  // levels² per pixel²; a flat or straight-edge window that cannot fix both coordinates) are not
  // aligned.
  double min_eigenvalue = 0.5;
  // Gains outside [min_gain, max_gain] are a failure (a patch matched to a flat region).
  double min_gain = 0.2;
  double max_gain = 5.0;
  // AlignFeatures (track_continuation.h): an alignment counts only if aligning back from where
  // it ended returns within this distance of the start (pixels; 0 = no check).
  double max_forward_backward_px = 0.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// A frame and its half-size copies (CV_32F) for alignment.
class ImagePyramid {
 public:
  ImagePyramid() = default;
  // `gray` CV_8UC1; throws comic::Error(kInvalidArgument) otherwise. Levels that would be smaller
  // than the window are not built. `window` is the side of the windows to be aligned.
  ImagePyramid(const cv::Mat& gray, int levels, int window = kPatchSize);

  int NumLevels() const { return static_cast<int>(levels_.size()); }
  const cv::Mat& Level(int l) const { return levels_[l]; }
  cv::Size Size() const { return levels_.empty() ? cv::Size() : levels_[0].size(); }
  // The same levels as cv::buildOpticalFlowPyramid makes them (8-bit, with its border), for
  // cv::calcOpticalFlowPyrLK.
  const std::vector<cv::Mat>& OpticalFlowLevels() const { return flow_levels_; }

 private:
  std::vector<cv::Mat> levels_;
  std::vector<cv::Mat> flow_levels_;
};

// Per-pixel weights of the window (window² values, row-major, 0 = not used); empty = all 1.
using AlignmentWeights = std::vector<float>;

// The weights of a side of a feature's side mask (kPatchSize² labels): 1 on `side`, 0 elsewhere;
// only for options.window == kPatchSize. Throws comic::Error(kInvalidArgument) otherwise.
AlignmentWeights SideWeights(const std::vector<PatchSide>& side_mask, PatchSide side);

// The smallest eigenvalue of the mean gradient moment matrix (central differences, grey levels²
// per pixel²) over the window² pixels around the rounded `point` of `gray` (CV_8UC1), the border
// replicated: what AlignPatch's min_eigenvalue test reads at level 0 (for a window on the pixel
// grid). Small for a flat window or a straight edge, which no alignment can pin down in both
// coordinates.
double WindowMinEigenvalue(const cv::Mat& gray, cv::Point2f point, int window);

struct PatchAlignment {
  bool converged = false;  // every level ran, the point stayed inside, gain in range
  cv::Point2f position;    // in frame 2 (valid only if converged)
  // Mean squared difference (grey levels²) over the weighted pixels between frame 2 at
  // `position` and gain·template + bias, at the finest level.
  float residual = 0.0f;
  float gain = 1.0f;
  float bias = 0.0f;
  // Normalised cross-correlation of the template and frame 2 at `position` (weighted).
  float correlation = 0.0f;
  // The same at half resolution (pyramid level 1; 0 without it): motion blur that differs
  // between the frames lowers it less.
  float coarse_correlation = 0.0f;
};

// Aligns the window around `point` of pyramid1 to pyramid2, starting at `guess` (both in pixels
// of level 0). Throws comic::Error(kInvalidArgument) for pyramids of different sizes or level
// counts, weights of the wrong size, or bad options.
PatchAlignment AlignPatch(const ImagePyramid& pyramid1, cv::Point2f point,
                          const ImagePyramid& pyramid2, cv::Point2f guess,
                          const AlignmentWeights& weights, const PatchAlignmentOptions& options);

}  // namespace comic::frontend
