#include "frontend/comic/side_mask.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <opencv2/imgproc.hpp>

#include "frontend/comic/iso_curve.h"
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

// The side mask as first written (a breadth-first fill with bounds tests on the 23x23 patch), kept
// as the reference that the framed fill of ComputeSideMask must reproduce label for label.
std::vector<PatchSide> ReferenceSideMask(const cv::Mat& gray, double threshold,
                                         const cv::Point2f& curve_point, const cv::Point& centre) {
  constexpr int kSize = kPatchSize;
  std::vector<PatchSide> mask(kSize * kSize, PatchSide::kNone);
  const cv::Rect patch(centre.x - kPatchRadius, centre.y - kPatchRadius, kSize, kSize);
  const IsoCurveTracer tracer(gray, patch, threshold);
  CurveEdge seed;
  if (!tracer.FindNearestCrossing(curve_point, 2, &seed)) return mask;
  IsoCurve curve;
  tracer.Trace(seed, 8 * kSize * kSize, &curve);
  std::array<uint8_t, kSize * kSize> cut_right{}, cut_down{}, near_curve{};
  auto local_index = [&](const cv::Point& p) { return (p.y - patch.y) * kSize + (p.x - patch.x); };
  std::vector<int> queue;
  for (const CurveEdge& edge : curve.edges) {
    const cv::Point lo(std::min(edge.inside.x, edge.outside.x),
                       std::min(edge.inside.y, edge.outside.y));
    (edge.inside.y == edge.outside.y ? cut_right : cut_down)[local_index(lo)] = 1;
    const int inside = local_index(edge.inside);
    const int outside = local_index(edge.outside);
    if (mask[inside] == PatchSide::kNone) {
      mask[inside] = PatchSide::kMinus;
      queue.push_back(inside);
    }
    if (mask[outside] == PatchSide::kNone) {
      mask[outside] = PatchSide::kPlus;
      queue.push_back(outside);
    }
    const double v_in = tracer.Value(edge.inside);
    const double t = (threshold - v_in) / (tracer.Value(edge.outside) - v_in);
    if (t < 0.5) near_curve[inside] = 1;
    if (t > 0.5) near_curve[outside] = 1;
  }
  const cv::Rect image_rect(0, 0, gray.cols, gray.rows);
  for (size_t head = 0; head < queue.size(); ++head) {
    const int index = queue[head];
    const int u = index % kSize, v = index / kSize;
    auto visit = [&](int nu, int nv, bool cut) {
      if (cut || nu < 0 || nv < 0 || nu >= kSize || nv >= kSize) return;
      const int next = nv * kSize + nu;
      if (mask[next] != PatchSide::kNone) return;
      if (!image_rect.contains(cv::Point(patch.x + nu, patch.y + nv))) return;
      mask[next] = mask[index];
      queue.push_back(next);
    };
    visit(u + 1, v, u + 1 < kSize && cut_right[index]);
    visit(u - 1, v, u > 0 && cut_right[index - 1]);
    visit(u, v + 1, v + 1 < kSize && cut_down[index]);
    visit(u, v - 1, v > 0 && cut_down[index - kSize]);
  }
  for (int i = 0; i < kSize * kSize; ++i) {
    if (near_curve[i]) mask[i] = PatchSide::kNone;
  }
  return mask;
}

TEST(SideMask, TheFramedFillGivesTheReferenceFillsLabelsOnRandomPatches) {
  // Smooth and rough random images (many curves, saddles, curves ending at the image border),
  // random levels, centres anywhere (patches partly outside the image) and curve points off the
  // centre (no curve within 2 px: all kNone).
  cv::RNG rng(2026);
  int with_sides = 0, partial = 0;
  for (int image_index = 0; image_index < 40; ++image_index) {
    cv::Mat noise(70, 90, CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0, 1);
    cv::GaussianBlur(noise, noise, cv::Size(), image_index % 2 == 0 ? 2.5 : 0.8);
    cv::Mat gray;
    cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
    noise.convertTo(gray, CV_8U);
    for (int k = 0; k < 60; ++k) {
      const cv::Point centre(rng.uniform(0, gray.cols), rng.uniform(0, gray.rows));
      const cv::Point2f curve_point(centre.x + rng.uniform(-3.f, 3.f),
                                    centre.y + rng.uniform(-3.f, 3.f));
      const double threshold = rng.uniform(40, 215) + 0.5;
      const std::vector<PatchSide> expected =
          ReferenceSideMask(gray, threshold, curve_point, centre);
      ASSERT_EQ(ComputeSideMask(gray, threshold, curve_point, centre), expected)
          << "image " << image_index << ", centre " << centre << ", level " << threshold;
      const bool sided =
          std::find(expected.begin(), expected.end(), PatchSide::kPlus) != expected.end();
      with_sides += sided;
      partial +=
          sided && !cv::Rect(0, 0, gray.cols, gray.rows)
                        .contains(cv::Point(centre.x - kPatchRadius, centre.y - kPatchRadius));
    }
  }
  EXPECT_GT(with_sides, 1000);  // most cases draw a curve
  EXPECT_GT(partial, 100);      // many of them cut off by the image border
}

}  // namespace
}  // namespace comic::frontend
