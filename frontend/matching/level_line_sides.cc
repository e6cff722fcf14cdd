#include "frontend/matching/level_line_sides.h"

#include <algorithm>
#include <cmath>

#include "frontend/comic/side_mask.h"

namespace comic::frontend {

namespace {

// The side holding clearly fewer labelled pixels within 5 px of the centre: a corner's interior
// (an angle below 180°) fills less of a disc around its apex than its exterior. Within 40/60 the
// split is a straight edge and no side is the object.
PatchSide ObjectSideFromGeometry(const std::vector<PatchSide>& mask) {
  constexpr int kRadius = 5;
  int plus = 0, minus = 0;
  for (int v = -kRadius; v <= kRadius; ++v) {
    for (int u = -kRadius; u <= kRadius; ++u) {
      if (u * u + v * v > kRadius * kRadius) continue;
      const PatchSide s = mask[(v + kPatchRadius) * kPatchSize + (u + kPatchRadius)];
      plus += s == PatchSide::kPlus;
      minus += s == PatchSide::kMinus;
    }
  }
  const int total = plus + minus;
  if (total == 0) return PatchSide::kNone;
  if (plus * 10 < total * 4) return PatchSide::kPlus;
  if (minus * 10 < total * 4) return PatchSide::kMinus;
  return PatchSide::kNone;
}

}  // namespace

bool HasBothSides(const std::vector<PatchSide>& mask) {
  const bool plus = std::find(mask.begin(), mask.end(), PatchSide::kPlus) != mask.end();
  const bool minus = std::find(mask.begin(), mask.end(), PatchSide::kMinus) != mask.end();
  return plus && minus;
}

PatchSide ObjectSideFromPolarity(Polarity polarity) {
  switch (polarity) {
    case Polarity::kBright:
      return PatchSide::kPlus;
    case Polarity::kDark:
      return PatchSide::kMinus;
    case Polarity::kNone:
      break;
  }
  return PatchSide::kNone;
}

LevelLineSides ComputeLevelLineSides(const cv::Mat& gray, const Feature& feature) {
  LevelLineSides sides;
  if (feature.HasSideMask()) {
    sides.mask = feature.side_mask;
    sides.object_side = feature.polarity != Polarity::kNone
                            ? ObjectSideFromPolarity(feature.polarity)
                            : ObjectSideFromGeometry(sides.mask);
    return sides;
  }
  if (!PatchFits(feature, gray.size())) return sides;
  const cv::Point centre(static_cast<int>(std::lround(feature.x)),
                         static_cast<int>(std::lround(feature.y)));
  int lo = 255, hi = 0;
  for (int y = centre.y - 2; y <= centre.y + 2; ++y) {
    const uint8_t* row = gray.ptr<uint8_t>(y);
    for (int x = centre.x - 2; x <= centre.x + 2; ++x) {
      lo = std::min<int>(lo, row[x]);
      hi = std::max<int>(hi, row[x]);
    }
  }
  if (hi - lo < kMinSideContrast) return sides;
  // Half-way between the darkest and brightest grey of the neighbourhood, offset by half a grey
  // level so that no pixel lies exactly on the line (CoMIC's curves are at I + 0.5, §2.1).
  const double threshold = std::floor(0.5 * (lo + hi)) + 0.5;
  std::vector<PatchSide> mask = ComputeSideMask(gray, threshold, feature.Position(), centre);
  if (!HasBothSides(mask)) return sides;
  sides.object_side = ObjectSideFromGeometry(mask);
  sides.mask = std::move(mask);
  return sides;
}

}  // namespace comic::frontend
