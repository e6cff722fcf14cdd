// A detected feature point, the currency every detector produces and every matcher, tracker and
// evaluation consumes.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace comic::frontend {

// The SSD patch is 23x23 pixels centred on the feature (paper §4).
inline constexpr int kPatchSize = 23;
inline constexpr int kPatchRadius = kPatchSize / 2;

// Which side of the feature's maximally stable iso-curve segment (MSICS) a patch pixel lies on:
// the paper's ic+ and ic− regions (§4, Fig. 7). kNone marks pixels used by neither side (e.g.
// pixels on the curve itself).
enum class PatchSide : uint8_t { kNone = 0, kPlus = 1, kMinus = 2 };

// For CoMIC: which side of the iso-curve the corner's interior (the side where the curve turns,
// angle < 180°) lies on. kBright: the corner points into the region brighter than the level
// (e.g. the corner of a bright square on a dark background); kDark: into the darker region.
enum class Polarity : int8_t { kNone = 0, kBright = 1, kDark = -1 };

struct Feature {
  // Sub-pixel position; pixel centres at integer coordinates (OpenCV convention).
  float x = 0.0f;
  float y = 0.0f;
  // Detection scale in pixels (CoMIC: s; baselines: their integration scale).
  float scale = 0.0f;
  // The score a detection threshold cuts (threshold equalisation, paper §5.1): stability ρ for
  // CoMIC, the detector's own response for the baselines. Larger is stronger.
  float response = 0.0f;
  // CoMIC cornerness κ = det(Σ)/trace(Σ)² (paper §2.2); 0 for the baselines.
  float cornerness = 0.0f;
  // CoMIC iso level I of the MSICS (a grey value; the curve is the level line at I + 0.5);
  // -1 for the baselines.
  int level = -1;
  Polarity polarity = Polarity::kNone;
  // kPatchSize x kPatchSize row-major side labels of the patch centred on the rounded position
  // (pixel (cx + u, cy + v) at index (v + kPatchRadius) * kPatchSize + (u + kPatchRadius)).
  // Empty when the detector has no side information: the matcher then uses the full patch.
  std::vector<PatchSide> side_mask;
  // CoMIC: the points of the MSICS (sub-pixel, image coordinates), for drawing and inspection;
  // empty for the baselines.
  std::vector<cv::Point2f> curve;

  cv::Point2f Position() const { return {x, y}; }
  bool HasSideMask() const { return side_mask.size() == kPatchSize * kPatchSize; }
};

using FeatureSet = std::vector<Feature>;

// Sorts strongest first: by response descending, ties by y then x ascending, so that the
// order is a deterministic function of the features alone.
void SortByResponse(FeatureSet* features);

// True if a kPatchSize x kPatchSize patch centred on the rounded position of `feature` lies
// inside an image of `size`.
bool PatchFits(const Feature& feature, const cv::Size& size);

}  // namespace comic::frontend
