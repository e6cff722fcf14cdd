#include "frontend/matching/patch_set.h"

#include <algorithm>
#include <cmath>

#include "frontend/matching/level_line_sides.h"
#include "io/core/error.h"

namespace comic::frontend {

PatchSet::PatchSet(const cv::Mat& gray, const FeatureSet& features, PatchSides sides)
    : sides_(sides), patches_(features.size()) {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "patch set: the image must be a non-empty 8-bit single-channel image");
  if (sides == PatchSides::kLevelLines) words_.assign(features.size() * kWordsPerPatch, 0);
  for (size_t i = 0; i < features.size(); ++i) {
    const Feature& feature = features[i];
    FeaturePatch& patch = patches_[i];
    if (!PatchFits(feature, gray.size())) continue;
    patch.valid = true;
    const int cx = static_cast<int>(std::lround(feature.x));
    const int cy = static_cast<int>(std::lround(feature.y));
    for (int v = 0; v < kPatchSize; ++v) {
      const uint8_t* row = gray.ptr<uint8_t>(cy - kPatchRadius + v) + (cx - kPatchRadius);
      std::copy(row, row + kPatchSize, patch.values.begin() + v * kPatchSize);
    }
    if (sides == PatchSides::kLevelLines) {
      // Every detector's points get sides here, and only for the calibrated costs (issue 15).
      const LevelLineSides level_line = ComputeLevelLineSides(gray, feature);
      int16_t* words = &words_[i * kWordsPerPatch];
      std::copy(patch.values.begin(), patch.values.end(), words);
      if (!level_line.mask.empty()) {
        patch.has_sides = true;
        patch.object_side = level_line.object_side;
        for (int k = 0; k < kPatchPixels; ++k) {
          words[kPatchPixels + k] = level_line.mask[k] == PatchSide::kPlus ? -1 : 0;
          words[2 * kPatchPixels + k] = level_line.mask[k] == PatchSide::kMinus ? -1 : 0;
        }
      }
    } else if (sides == PatchSides::kDetector && feature.HasSideMask()) {
      patch.has_sides = true;
      std::copy(feature.side_mask.begin(), feature.side_mask.end(), patch.sides.begin());
    }
  }
}

void PatchSet::DropSides(size_t i) {
  COMIC_CHECK(i < patches_.size(), kInvalidArgument,
              "patch set: feature " << i << " of " << patches_.size());
  patches_[i].has_sides = false;
  patches_[i].object_side = PatchSide::kNone;
}

void PatchSet::Append(const cv::Mat& gray, const FeatureSet& more) {
  PatchSet added(gray, more, sides_);
  patches_.insert(patches_.end(), added.patches_.begin(), added.patches_.end());
  words_.insert(words_.end(), added.words_.begin(), added.words_.end());
}

}  // namespace comic::frontend
