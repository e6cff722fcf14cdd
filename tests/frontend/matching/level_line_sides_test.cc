#include "frontend/matching/level_line_sides.h"

#include <gtest/gtest.h>

namespace comic::frontend {
namespace {

Feature At(float x, float y) {
  Feature f;
  f.x = x;
  f.y = y;
  return f;
}

PatchSide SideAt(const std::vector<PatchSide>& mask, int u, int v) {
  return mask[(v + kPatchRadius) * kPatchSize + (u + kPatchRadius)];
}

TEST(LevelLineSides, TheCornerOfABrightSquareSplitsItsPatchIntoSquareAndBackground) {
  // Bright square [30, 70)² on a dark background; a Harris-like point at its top-left corner.
  cv::Mat gray(100, 100, CV_8UC1, cv::Scalar(40));
  gray(cv::Rect(30, 30, 40, 40)).setTo(200);
  const LevelLineSides sides = ComputeLevelLineSides(gray, At(30, 30));
  ASSERT_EQ(sides.mask.size(), static_cast<size_t>(kPatchSize * kPatchSize));
  int plus = 0, minus = 0;
  for (int v = -kPatchRadius; v <= kPatchRadius; ++v) {
    for (int u = -kPatchRadius; u <= kPatchRadius; ++u) {
      const PatchSide s = SideAt(sides.mask, u, v);
      if (s == PatchSide::kNone) continue;
      // Pixel (30 + u, 30 + v) is in the square iff u >= 0 and v >= 0.
      EXPECT_EQ(s, u >= 0 && v >= 0 ? PatchSide::kPlus : PatchSide::kMinus) << u << "," << v;
      (s == PatchSide::kPlus ? plus : minus)++;
    }
  }
  EXPECT_GE(plus, 100);  // the square's quarter of the patch, minus the curve's pixels
  EXPECT_GE(minus, 300);
  // The corner points into the square: a quarter of the disc around it.
  EXPECT_EQ(sides.object_side, PatchSide::kPlus);
}

TEST(LevelLineSides, AReversedContrastSwapsTheSidesButNotTheObject) {
  cv::Mat gray(100, 100, CV_8UC1, cv::Scalar(220));
  gray(cv::Rect(30, 30, 40, 40)).setTo(90);
  const LevelLineSides sides = ComputeLevelLineSides(gray, At(30, 30));
  ASSERT_FALSE(sides.mask.empty());
  EXPECT_EQ(SideAt(sides.mask, 5, 5), PatchSide::kMinus);   // the square, now dark
  EXPECT_EQ(SideAt(sides.mask, -5, -5), PatchSide::kPlus);  // the background, now bright
  EXPECT_EQ(sides.object_side, PatchSide::kMinus);
}

TEST(LevelLineSides, AStraightEdgeHasSidesButNoObjectSide) {
  cv::Mat gray(100, 100, CV_8UC1, cv::Scalar(40));
  gray(cv::Rect(50, 0, 50, 100)).setTo(200);
  const LevelLineSides sides = ComputeLevelLineSides(gray, At(50, 50));
  ASSERT_FALSE(sides.mask.empty());
  EXPECT_EQ(SideAt(sides.mask, 5, 0), PatchSide::kPlus);
  EXPECT_EQ(SideAt(sides.mask, -5, 0), PatchSide::kMinus);
  EXPECT_EQ(sides.object_side, PatchSide::kNone);
}

TEST(LevelLineSides, NoSidesOnAFlatPatchOrWhereThePatchDoesNotFit) {
  cv::Mat gray(100, 100, CV_8UC1, cv::Scalar(128));
  gray(cv::Rect(50, 0, 50, 100)).setTo(128 + kMinSideContrast - 1);  // below the contrast
  EXPECT_TRUE(ComputeLevelLineSides(gray, At(50, 50)).mask.empty());
  gray(cv::Rect(50, 0, 50, 100)).setTo(200);
  EXPECT_TRUE(ComputeLevelLineSides(gray, At(5, 50)).mask.empty());  // 23x23 patch off the image
}

TEST(LevelLineSides, AFeatureWithItsOwnMaskKeepsItAndItsPolaritySaysWhichSideIsTheObject) {
  cv::Mat gray(100, 100, CV_8UC1, cv::Scalar(40));
  Feature f = At(50, 50);
  f.side_mask.assign(kPatchSize * kPatchSize, PatchSide::kMinus);
  f.side_mask[0] = PatchSide::kPlus;
  f.polarity = Polarity::kDark;
  const LevelLineSides sides = ComputeLevelLineSides(gray, f);  // a flat image: not recomputed
  EXPECT_EQ(sides.mask, f.side_mask);
  EXPECT_EQ(sides.object_side, PatchSide::kMinus);
  EXPECT_EQ(ObjectSideFromPolarity(Polarity::kBright), PatchSide::kPlus);
  EXPECT_EQ(ObjectSideFromPolarity(Polarity::kNone), PatchSide::kNone);
}

}  // namespace
}  // namespace comic::frontend
