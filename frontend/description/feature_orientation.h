// The orientation a descriptor is measured in, so that a view turned in its plane gives the same
// descriptor. Three ways:
//   kGradient  the dominant gradient orientation (Lowe 2004 §5): a 36-bin histogram of the
//              gradient directions around the feature, weighted by magnitude and a Gaussian of
//              1.5σ, smoothed, its highest peak refined by a parabola. Defined alike for every
//              detector.
//   kUpright   0 for every feature (COLMAP's `upright`): more distinctive when the views are
//              known not to turn (a rig, a turntable), useless when they do.
//   kIsoCurve  for CoMIC features, the direction from the corner into the bend of its maximally
//              stable iso-curve segment (the mean of the unit vectors to the curve points within
//              2σ on both arms, paper §2.2): the corner's own geometry instead of a histogram
//              peak, which at a corner flips between its two edges' near-equal peaks. Features
//              without a curve (the baselines) fall back to kGradient. The default.
// Angles are in degrees in [0, 360), in image axes (x right, y down): atan2(∂I/∂y, ∂I/∂x) for
// kGradient, so 90 means "down" on screen. This is cv::KeyPoint::angle's convention.
//
//   ScaleLevelImages images(gray);
//   const std::vector<float> angles = ComputeOrientations(features, sigmas, options, &images);
#pragma once

#include <string>
#include <vector>

#include "frontend/description/scale_levels.h"
#include "frontend/feature.h"

namespace comic::frontend {

enum class OrientationMode { kGradient, kUpright, kIsoCurve };

// "gradient", "upright", "iso-curve"; Parse throws comic::Error(kInvalidArgument) listing them.
const char* OrientationModeName(OrientationMode mode);
OrientationMode ParseOrientationMode(const std::string& name);

struct OrientationOptions {
  OrientationMode mode = OrientationMode::kIsoCurve;
  // kGradient: histogram bins over 360°, Gaussian weight σ_w = weight_sigma_factor · σ, window
  // radius radius_factor · σ_w (Lowe: 36, 1.5, 3).
  int num_bins = 36;
  double weight_sigma_factor = 1.5;
  double radius_factor = 3.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The dominant gradient orientation (degrees, see above) of a point at (x, y) of the input image
// with scale σ, measured on `images` at NearestScaleLevel(σ). A point without any gradient in its
// window gets 0.
float DominantGradientOrientation(double x, double y, double sigma,
                                  const OrientationOptions& options, ScaleLevelImages* images);

// kIsoCurve's angle for a feature with a curve (see above); −1 when the curve has no point within
// 2σ other than the corner, or its unit vectors cancel out (a straight curve).
float IsoCurveOrientation(const Feature& feature, double sigma);

// One angle per feature (degrees), features[i] described at scale sigmas[i]. Throws
// comic::Error(kInvalidArgument) for bad options or sizes that differ.
std::vector<float> ComputeOrientations(const FeatureSet& features,
                                       const std::vector<double>& sigmas,
                                       const OrientationOptions& options, ScaleLevelImages* images);

}  // namespace comic::frontend
