// One frame's features as the patch matcher compares them (issue 15): each feature's 23x23 grey
// values and, when a side-aware cost needs them, its side labels — prepared once per frame and
// read by every pair the frame takes part in.
//
//   PatchSet patches1(gray1, features1, SidesFor(options.cost));   // once per frame
//   PatchSet patches2(gray2, features2, SidesFor(options.cost));
//   auto candidates = ComputeCandidateCosts(features1, patches1, features2, patches2, options);
//
// Why a set of its own: the level-line sides of a point without a detector mask (Harris, Hessian,
// FAST, MSER; level_line_sides.h) cost an iso-curve trace and a flood fill, ten times the cost of
// comparing two patches. The tracker matches every frame to the frame after it and the frame
// before it (and to match_window frames), so preparing them per pair computed each mask at least
// twice and dominated the calibrated cost's time (docs/side_aware_matching.md, "Speed").
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

inline constexpr int kPatchPixels = kPatchSize * kPatchSize;

// Which side labels a PatchSet carries.
enum class PatchSides {
  kNone,        // grey values only (the full-patch cost)
  kDetector,    // the detector's own side masks, where it has them (the split costs)
  kLevelLines,  // every feature's sides: its own mask, else the level line through the point
                // (ComputeLevelLineSides), with the object side and the branch-free layout of
                // the calibrated cost
};

// A feature's patch. `valid` = the patch fits in its image; `has_sides` = side labels exist.
// `values` is set only if valid and `sides` only if has_sides (kDetector): neither is
// zero-initialised, since a frame's set is thousands of patches and only those are ever read.
struct FeaturePatch {
  bool valid = false;
  bool has_sides = false;
  PatchSide object_side = PatchSide::kNone;  // kLevelLines only
  std::array<uint8_t, kPatchPixels> values;
  std::array<PatchSide, kPatchPixels> sides;  // kDetector: the detector's labels
};

class PatchSet {
 public:
  PatchSet() = default;
  // `gray` is CV_8UC1 (throws comic::Error(kInvalidArgument) otherwise). Deterministic: depends
  // only on the image, the features and `sides`.
  PatchSet(const cv::Mat& gray, const FeatureSet& features, PatchSides sides);

  PatchSides sides() const { return sides_; }
  size_t size() const { return patches_.size(); }
  const FeaturePatch& operator[](size_t i) const { return patches_[i]; }

  // kLevelLines: the patch's grey values, then one word per pixel that is all ones (-1) on the
  // ic+ side, then one for ic− (kPatchPixels each, zeros without sides), as int16 so that the
  // calibrated cost's loop multiplies and adds 8 pixels per instruction without a branch.
  const int16_t* Values(size_t i) const { return &words_[i * kWordsPerPatch]; }
  const int16_t* SideWords(size_t i, PatchSide side) const {
    return &words_[i * kWordsPerPatch + (side == PatchSide::kPlus ? 1 : 2) * kPatchPixels];
  }

  // Compares feature i by its full patch only from now on (as a feature without sides). The
  // tracker's track-sides cost uses it for a feature whose own match into this frame was won by
  // the full patch.
  void DropSides(size_t i);

  // Adds the patches of `more` features of the same image (`gray`, as given to the constructor),
  // prepared with this set's sides: the tracker's continued features (track_continuation.h).
  void Append(const cv::Mat& gray, const FeatureSet& more);

 private:
  static constexpr size_t kWordsPerPatch = 3 * kPatchPixels;

  PatchSides sides_ = PatchSides::kNone;
  std::vector<FeaturePatch> patches_;
  std::vector<int16_t> words_;  // kLevelLines only
};

}  // namespace comic::frontend
