#include "frontend/comic/corner_feature.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "frontend/comic/side_mask.h"
#include "tests/frontend/synthetic_images.h"

namespace comic::frontend {
namespace {

TEST(CornerFeature, CarriesTheCornerAndTheSideMaskOfItsCurve) {
  // A bright square whose top-left vertex is at (30, 30).
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({80, 80}, 50),
                                             {test::MakeSquare({30.0, 30.0}, 40, 200)}, 1.0);
  CornerOnCurve corner;
  corner.position = {30.4f, 29.6f};
  corner.stability = 0.123456789;
  corner.cornerness = 0.2;
  corner.level = 125;
  corner.polarity = Polarity::kBright;
  corner.apex = {31.0f, 31.0f};
  corner.curve_threshold = 125.5;
  const std::vector<cv::Point2f> segment = {{30.0f, 40.0f}, {30.0f, 30.0f}, {40.0f, 30.0f}};
  const Feature feature = MakeCornerFeature(image, 8.4, corner, segment);
  EXPECT_EQ(feature.x, 30.4f);
  EXPECT_EQ(feature.y, 29.6f);
  EXPECT_EQ(feature.scale, 8.4f);
  EXPECT_EQ(feature.response, static_cast<float>(0.123456789));
  EXPECT_EQ(feature.cornerness, 0.2f);
  EXPECT_EQ(feature.level, 125);
  EXPECT_EQ(feature.polarity, Polarity::kBright);
  EXPECT_EQ(feature.curve, segment);
  // The mask is that of the patch centred on the rounded position (30, 30).
  ASSERT_TRUE(feature.HasSideMask());
  EXPECT_EQ(feature.side_mask, ComputeSideMask(image, 125.5, {31.0f, 31.0f}, {30, 30}));
  EXPECT_GT(std::count(feature.side_mask.begin(), feature.side_mask.end(), PatchSide::kPlus), 100);
  EXPECT_GT(std::count(feature.side_mask.begin(), feature.side_mask.end(), PatchSide::kMinus), 300);
}

TEST(CornerFeature, NoCurveAtTheThresholdGivesAnUnsidedMask) {
  // No level line at 240.5 in an image of 50 and 200: every pixel is kNone.
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({80, 80}, 50),
                                             {test::MakeSquare({30.0, 30.0}, 40, 200)}, 1.0);
  CornerOnCurve corner;
  corner.position = {30.0f, 30.0f};
  corner.apex = {31.0f, 31.0f};
  corner.curve_threshold = 240.5;
  const Feature feature = MakeCornerFeature(image, 8.4, corner, {});
  ASSERT_EQ(feature.side_mask.size(), static_cast<size_t>(kPatchSize * kPatchSize));
  EXPECT_TRUE(std::all_of(feature.side_mask.begin(), feature.side_mask.end(),
                          [](PatchSide side) { return side == PatchSide::kNone; }));
  EXPECT_TRUE(feature.curve.empty());
}

}  // namespace
}  // namespace comic::frontend
