// Two models of the same frames compared without ground truth: their cameras' rotations on the
// frames both register, after the one rotation that best brings the second model's world onto
// the first's (a model's world is fixed only up to a similarity). Rotations need no scale, so
// models from different matchers, with different points, compare directly. Two right models of
// a clip agree to a fraction of a degree; a model that went wrong (a planar scene's second
// decomposition, a turn it got wrong) turns its cameras degrees away from a right one.
//
// Two measures, because error builds up along a long clip: the absolute one (each camera after
// the best common rotation) grows with the clip's length even between two right models that
// drift apart slowly, while the relative one (the rotation between two nearby frames, which
// needs no alignment) stays small for slow drift and is large when one model turns its cameras
// too far or too little from frame to frame.
//
//   const ModelAgreement agreement = CompareModelRotations(kept, other);
//   if (agreement.common_frames >= 5 &&
//       agreement.median_relative_rotation_difference_deg > 1) ...
#pragma once

#include "sfm/reconstruction.h"

namespace comic::sfm {

struct ModelAgreement {
  int common_frames = 0;  // registered in both (by image id)
  // Over the common frames, after the best common rotation (0 with fewer than 2 frames).
  double median_rotation_difference_deg = 0.0;
  double max_rotation_difference_deg = 0.0;
  // Over the pairs of common frames at most `neighbour_ids` image ids apart: the angle between
  // the two models' rotations from one frame to the other (0 with no such pair).
  int neighbour_pairs = 0;
  double median_relative_rotation_difference_deg = 0.0;
};

// Deterministic; the images are paired by image id (frame order for a video).
ModelAgreement CompareModelRotations(const Reconstruction& a, const Reconstruction& b,
                                     int neighbour_ids = 10);

}  // namespace comic::sfm
