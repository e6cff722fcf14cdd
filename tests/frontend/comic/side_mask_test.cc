#include "frontend/comic/side_mask.h"

#include <gtest/gtest.h>

#include "tests/frontend/synthetic_images.h"

namespace comic::frontend {
namespace {

PatchSide At(const std::vector<PatchSide>& mask, int u, int v) {
  return mask[(v + kPatchRadius) * kPatchSize + (u + kPatchRadius)];
}

TEST(SideMask, SplitsThePatchAlongTheCornerCurve) {
  // A bright square whose top-left vertex is the patch centre.
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({80, 80}, 50),
                                             {test::MakeSquare({30.0, 30.0}, 40, 200)}, 1.0);
  const auto mask = ComputeSideMask(image, 125.5, {31.0f, 31.0f}, {30, 30});
  ASSERT_EQ(mask.size(), static_cast<size_t>(kPatchSize * kPatchSize));
  int plus = 0, minus = 0, none = 0;
  for (int v = -kPatchRadius; v <= kPatchRadius; ++v) {
    for (int u = -kPatchRadius; u <= kPatchRadius; ++u) {
      const PatchSide side = At(mask, u, v);
      plus += side == PatchSide::kPlus;
      minus += side == PatchSide::kMinus;
      none += side == PatchSide::kNone;
      // Clear of the boundary (2 px), the side is the geometric one.
      if (u >= 2 && v >= 2) {
        EXPECT_EQ(side, PatchSide::kPlus) << u << "," << v;
      }
      if (u <= -2 || v <= -2) {
        EXPECT_EQ(side, PatchSide::kMinus) << u << "," << v;
      }
    }
  }
  EXPECT_GT(plus, 100);
  EXPECT_GT(minus, 300);
  EXPECT_GT(none, 10);  // along the curve
  EXPECT_LT(none, 60);
}

TEST(SideMask, FollowsTheCurveNotTheIntensityOfOtherTexture) {
  // A bright spot on the dark side is brighter than the level but is not on the ic+ side.
  cv::Mat image = test::RenderPolygons(test::FlatBackground({80, 80}, 50),
                                       {test::MakeSquare({30.0, 30.0}, 40, 200)}, 1.0);
  image(cv::Rect(22, 34, 3, 3)).setTo(230);
  const auto mask = ComputeSideMask(image, 125.5, {31.0f, 31.0f}, {30, 30});
  EXPECT_EQ(At(mask, -7, 5), PatchSide::kMinus);
  EXPECT_EQ(At(mask, 5, 5), PatchSide::kPlus);
}

TEST(SideMask, PixelsOutsideTheImageOrWithoutACurveAreNone) {
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({40, 40}, 50),
                                             {test::MakeSquare({5.0, 5.0}, 20, 200)}, 1.0);
  const auto mask = ComputeSideMask(image, 125.5, {6.0f, 6.0f}, {5, 5});
  EXPECT_EQ(At(mask, -kPatchRadius, -kPatchRadius), PatchSide::kNone);  // outside the image
  EXPECT_EQ(At(mask, 3, 3), PatchSide::kPlus);
  const auto empty =
      ComputeSideMask(cv::Mat(40, 40, CV_8UC1, cv::Scalar(9)), 125.5, {20.0f, 20.0f}, {20, 20});
  for (PatchSide side : empty) EXPECT_EQ(side, PatchSide::kNone);
}

}  // namespace
}  // namespace comic::frontend
