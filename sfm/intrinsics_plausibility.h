// Whether a self-calibrated camera is still a camera someone could have filmed with. Bundle
// adjustment refines the focal length and distortion where the motion observes them, but short,
// weakly tracked clips can let it slide far: VOT car1's first 150 frames took f from the prior
// 768 px to 2880 px with k = -1.38 (issue 30). COLMAP rejects such cameras as bogus outside focal
// ratios [0.1, 10] of the prior and |extra parameter| > 1; the range here is narrower, because
// our prior is the same guess for every camera (f = 1.2 max(w, h), a 45 deg field of view) and
// real lenses sit within a factor of three of it.
//
//   const IntrinsicsPlausibility check = CheckIntrinsicsPlausibility(prior, refined, options);
//   if (!check.plausible) { ... reset to the prior, hold fixed, say check.reason ... }
#pragma once

#include <string>

#include "sfm/camera.h"

namespace comic::sfm {

struct IntrinsicsPlausibilityOptions {
  // The focal length (each of fx, fy) must lie within [prior / max_focal_ratio,
  // prior x max_focal_ratio]: KITTI's 707 px is 0.48x the prior of its 1226 px wide frames,
  // Herz-Jesu's 2759.5 px 0.75x; a 3x longer focal is a 16 deg field of view.
  double max_focal_ratio = 3.0;
  // The radial distortion may move the image corner by at most this fraction of its distance
  // from the principal point (|k1 r^2 + k2 r^4| at the corner's normalised radius r), and the
  // distortion must keep the radius growing out to the corner (no fold-over).
  double max_corner_distortion = 0.25;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct IntrinsicsPlausibility {
  bool plausible = true;
  double focal_ratio = 1.0;        // the refined focal over the prior's (the farther of fx, fy)
  double corner_distortion = 0.0;  // the signed fractional displacement of the image corner
  std::string reason;              // empty when plausible
};

IntrinsicsPlausibility CheckIntrinsicsPlausibility(const Camera& prior, const Camera& refined,
                                                   const IntrinsicsPlausibilityOptions& options);

}  // namespace comic::sfm
