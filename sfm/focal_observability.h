// Whether a reconstruction's camera motion lets bundle adjustment observe the focal length.
//
// Under translation alone (any direction) the focal length is unobservable: with f' = s·f, the
// world points (X/s, Y/s, Z) and translations (tx/s, ty/s, tz) give exactly the same pixels
// f'·(X/s − tx/s)/(Z − tz) = f·(X − tx)/(Z − tz). A rotation about the optical axis commutes with
// that scaling and does not help either; only a rotation that turns the optical axis does (its
// image motion, f·θ·(1 + x²/f²), depends on f). KITTI's forward drive turns its optical axis by
// 1.3° over frames 0-50 and the focal drifts (829/842 px for 707 with --refine-focal, issue 17).
// The test here is that of the viewing directions: the largest angle between the optical axes of
// two registered images.
#pragma once

#include "sfm/reconstruction.h"

namespace comic::sfm {

struct FocalObservabilityOptions {
  // The focal length counts as observable when two registered images' optical axes are at least
  // this far apart (degrees). KITTI 06 frames 0-50: 1.3°; Herz-Jesu-P8 and the dino ring:
  // tens of degrees.
  double min_viewing_angle_deg = 5.0;

  // Throws comic::Error(kInvalidArgument) unless 0 < min_viewing_angle_deg < 180.
  void Check() const;
};

struct FocalObservability {
  bool observable = false;
  // The largest angle between the optical axes of two registered images, degrees.
  double max_viewing_angle_deg = 0.0;
};

FocalObservability AssessFocalObservability(const Reconstruction& reconstruction,
                                            const FocalObservabilityOptions& options);

}  // namespace comic::sfm
