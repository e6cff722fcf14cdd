// Two models of the same frames compared without ground truth: their cameras' rotations on the
// frames both register, after the one rotation that best brings the second model's world onto
// the first's (a model's world is fixed only up to a similarity). Rotations need no scale, so
// models from different matchers, with different points, compare directly. Two right models of
// a clip agree to a fraction of a degree; a model that went wrong (a planar scene's second
// decomposition, a turn it got wrong) turns its cameras degrees away from a right one.
//
//   const ModelAgreement agreement = CompareModelRotations(kept, other);
//   if (agreement.common_frames >= 5 && agreement.median_rotation_difference_deg > 2) ...
#pragma once

#include "sfm/reconstruction.h"

namespace comic::sfm {

struct ModelAgreement {
  int common_frames = 0;  // registered in both (by image id)
  // Over the common frames, after the best common rotation (0 with fewer than 2 frames).
  double median_rotation_difference_deg = 0.0;
  double max_rotation_difference_deg = 0.0;
};

// Deterministic; the images are paired by image id.
ModelAgreement CompareModelRotations(const Reconstruction& a, const Reconstruction& b);

}  // namespace comic::sfm
