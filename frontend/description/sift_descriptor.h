// A SIFT descriptor (Lowe 2004 §6: 4×4 cells × 8 orientation bins of gradients around the point,
// turned to its orientation) for every feature of any detector, at the feature's own position
// and scale, computed by OpenCV's cv::SIFT::compute and stored the way COLMAP 3.8 stores SIFT:
// 128 uint8 per feature, RootSIFT (COLMAP's default SiftExtractionOptions::normalization =
// L1_ROOT: L1-normalised, square-rooted, × 512, rounded, capped at 255). A descriptor then has
// Euclidean length ≈ 512, so dot(d1, d2) / 512² is the cosine of the angle between two of them —
// what COLMAP's matchers threshold (max_distance 0.7 rad, max_ratio 0.8) and what ours
// (frontend/matching/descriptor_matcher.h) does too. Layout: OpenCV's (cell row, cell column,
// orientation bin), row-major.
//
//   DescriptorOptions options;                            // gradient orientation, RootSIFT
//   cv::Mat descriptors = DescribeFeatures(gray, features, options);
//   // descriptors.row(i): features[i], CV_8UC1, 128 columns
//
// Scale. Our detectors have a scale, but not one meaning: Harris' and Hessian's σ (2 px), FAST's
// circle radius (3 px), MSER's region radius sqrt(area / π), CoMIC's s (8.4 px). The descriptor's
// σ (its window is 12σ wide: 4 cells of 3σ) is a factor times feature.scale — curve_sigma_per_scale
// for features that carry an iso-curve (CoMIC's), sigma_per_scale for the others — clamped to
// [min_sigma, max_sigma]; DescriptorOptionsFor(detector) holds the factors measured per detector
// (docs/descriptors.md: lego pairs against the true epipolar geometry). The image is sampled at
// the SIFT level nearest that σ (frontend/description/scale_levels.h).
//
// Orientation: CoMIC's iso-curve bisector where the feature has a curve, Lowe's dominant gradient
// orientation otherwise (feature_orientation.h): at a corner the gradients of its two edges make
// two near-equal histogram peaks whose winner flips between views, while the bisector is the
// corner's own geometry (docs/descriptors.md: far more correct matches for CoMIC's features).
//
// Deterministic: each descriptor depends only on the image, its feature and the options (OpenCV
// computes the features independently, whatever its thread count).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/description/feature_orientation.h"
#include "frontend/feature.h"

namespace comic::frontend {

inline constexpr int kDescriptorSize = 128;

enum class DescriptorNormalization { kL1Root, kL2 };

// "l1-root", "l2"; Parse throws comic::Error(kInvalidArgument) listing them.
const char* DescriptorNormalizationName(DescriptorNormalization normalization);
DescriptorNormalization ParseDescriptorNormalization(const std::string& name);

struct DescriptorOptions {
  // The descriptor's σ = sigma_per_scale · feature.scale (features without an iso-curve) or
  // curve_sigma_per_scale · feature.scale (with one: CoMIC's), within [min_sigma, max_sigma]
  // (pixels). The defaults are Harris' and CoMIC's (DescriptorOptionsFor).
  double sigma_per_scale = 1.5;
  double curve_sigma_per_scale = 0.5;
  double min_sigma = 1.6;
  double max_sigma = 25.6;
  // Default kIsoCurve: the iso-curve bisector for CoMIC's features, the dominant gradient for
  // the others.
  OrientationOptions orientation;
  // kL1Root: RootSIFT, COLMAP's default; kL2: plain SIFT (L2 unit length, × 512).
  DescriptorNormalization normalization = DescriptorNormalization::kL1Root;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The options measured best for a detector's features ("harris", "comic", "comic+hessian": a
// combined detector takes its first baseline's sigma_per_scale): sigma_per_scale 1.5 for Harris
// and Hessian (σ = 3 px), 1.0 for FAST (3 px) and MSER (the region's radius); curve_sigma_per_scale
// 0.5 for CoMIC (4.2 px). Unknown names get the defaults.
DescriptorOptions DescriptorOptionsFor(const std::string& detector_name);

// The σ a feature is described at (see above).
double DescriptorSigma(const Feature& feature, const DescriptorOptions& options);

// Descriptors of `features` in `gray` (CV_8UC1): features.size() rows × kDescriptorSize columns,
// CV_8UC1, row i for features[i]. No features: an empty 0 × 128 matrix. A feature in a uniform
// region gets a row of zeros (it matches nothing). Throws comic::Error(kInvalidArgument) for a
// wrong image type or bad options.
cv::Mat DescribeFeatures(const cv::Mat& gray, const FeatureSet& features,
                         const DescriptorOptions& options = {});

// A point to describe: position (OpenCV pixel convention), σ (pixels) and orientation (degrees,
// image axes, cv::KeyPoint::angle's convention; COLMAP's keypoint orientation θ in radians is the
// same angle).
struct OrientedPoint {
  float x = 0.0f;
  float y = 0.0f;
  float sigma = kSiftBaseSigma;
  float angle_deg = 0.0f;
};

// The descriptors of given points (what DescribeFeatures does once it has chosen σ and the
// orientation): cv::SIFT::compute on the SIFT level nearest each σ, then `normalization`. For
// COLMAP's own SIFT key points (x − 0.5, y − 0.5, its σ and orientation) this gives COLMAP's
// stored descriptors (tests/frontend/description: against `colmap feature_extractor`).
cv::Mat DescribeOrientedPoints(const cv::Mat& gray, const std::vector<OrientedPoint>& points,
                               DescriptorNormalization normalization);

// Converts OpenCV's SIFT descriptors (CV_32F, L2 length 512 after Lowe's 0.2 clipping) to the
// stored form (CV_8UC1, `normalization`). Exposed for tests.
cv::Mat NormalizeSiftDescriptors(const cv::Mat& opencv_descriptors,
                                 DescriptorNormalization normalization);

}  // namespace comic::frontend
