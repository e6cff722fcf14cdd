#include "frontend/matching/patch_alignment.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

// Smooth random texture (blob scale a few pixels), 8-bit.
cv::Mat Texture(uint64_t seed, int width = 240, int height = 200) {
  cv::Mat noise(height, width, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Mat gray;
  noise.convertTo(gray, CV_8U, 60, 128);
  return gray;
}

// `gray` translated by (dx, dy) (subpixel, bilinear), then g·I + b.
cv::Mat Shifted(const cv::Mat& gray, double dx, double dy, double gain = 1.0, double bias = 0.0) {
  cv::Mat moved;
  const cv::Matx23d translation(1, 0, dx, 0, 1, dy);
  cv::warpAffine(gray, moved, translation, gray.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  cv::Mat out;
  moved.convertTo(out, CV_8U, gain, bias);
  return out;
}

TEST(PatchAlignment, FindsAKnownSubpixelShift) {
  const cv::Mat gray1 = Texture(1);
  const cv::Mat gray2 = Shifted(gray1, 3.4, -2.7);
  PatchAlignmentOptions options;
  const ImagePyramid p1(gray1, options.levels), p2(gray2, options.levels);
  const cv::Point2f point(120, 100);
  const PatchAlignment a = AlignPatch(p1, point, p2, point, {}, options);
  ASSERT_TRUE(a.converged);
  EXPECT_NEAR(a.position.x, 123.4, 0.1);
  EXPECT_NEAR(a.position.y, 97.3, 0.1);
  EXPECT_GT(a.correlation, 0.95);
  EXPECT_NEAR(a.gain, 1.0, 0.1);  // bilinear sampling lowers the contrast a little
}

TEST(PatchAlignment, FindsALargeShiftThroughThePyramid) {
  // 14 px: beyond a single-level window's reach (half window = 11 px), within 2^3 of it.
  const cv::Mat gray1 = Texture(2);
  const cv::Mat gray2 = Shifted(gray1, 14.0, 9.0);
  PatchAlignmentOptions options;
  const ImagePyramid p1(gray1, options.levels), p2(gray2, options.levels);
  const cv::Point2f point(110, 95);
  const PatchAlignment a = AlignPatch(p1, point, p2, point, {}, options);
  ASSERT_TRUE(a.converged);
  EXPECT_NEAR(a.position.x, 124.0, 0.2);
  EXPECT_NEAR(a.position.y, 104.0, 0.2);
}

TEST(PatchAlignment, IgnoresGainAndBias) {
  const cv::Mat gray1 = Texture(3);
  const cv::Mat gray2 = Shifted(gray1, -2.0, 1.5, 0.7, 30.0);
  PatchAlignmentOptions options;
  const ImagePyramid p1(gray1, options.levels), p2(gray2, options.levels);
  const cv::Point2f point(120, 100);
  const PatchAlignment a = AlignPatch(p1, point, p2, point, {}, options);
  ASSERT_TRUE(a.converged);
  EXPECT_NEAR(a.position.x, 118.0, 0.15);
  EXPECT_NEAR(a.position.y, 101.5, 0.15);
  EXPECT_NEAR(a.gain, 0.7, 0.05);
  EXPECT_NEAR(a.bias, 30.0, 8.0);
  // The residual after gain and bias is small (8-bit rounding and interpolation only).
  EXPECT_LT(a.residual, 10.0f);
}

TEST(PatchAlignment, ToleratesMotionBlurOfTheSecondFrame) {
  const cv::Mat gray1 = Texture(4);
  cv::Mat blurred;
  // A horizontal 7-pixel box blur: the smear of a shaky camera.
  cv::blur(Shifted(gray1, 4.0, 2.0), blurred, cv::Size(7, 1));
  PatchAlignmentOptions options;
  const ImagePyramid p1(gray1, options.levels), p2(blurred, options.levels);
  const cv::Point2f point(120, 100);
  const PatchAlignment a = AlignPatch(p1, point, p2, point, {}, options);
  ASSERT_TRUE(a.converged);
  EXPECT_NEAR(a.position.x, 124.0, 0.5);
  EXPECT_NEAR(a.position.y, 102.0, 0.5);
  // Blur lowers the full-resolution correlation more than the half-resolution one.
  EXPECT_GE(a.coarse_correlation, a.correlation);
}

TEST(PatchAlignment, RefusesAFlatWindow) {
  cv::Mat flat(200, 240, CV_8UC1, cv::Scalar(90));
  PatchAlignmentOptions options;
  const ImagePyramid p1(flat, options.levels), p2(flat, options.levels);
  const PatchAlignment a = AlignPatch(p1, {120, 100}, p2, {120, 100}, {}, options);
  EXPECT_FALSE(a.converged);
}

TEST(PatchAlignment, WindowMinEigenvalueIsZeroOnAStraightEdgeAndLargeOnTexture) {
  cv::Mat edge(100, 100, CV_8UC1, cv::Scalar(30));
  edge(cv::Rect(50, 0, 50, 100)).setTo(200);
  EXPECT_NEAR(WindowMinEigenvalue(edge, {50, 50}, kPatchSize), 0.0, 1e-9);
  EXPECT_GT(WindowMinEigenvalue(Texture(5), {120, 100}, kPatchSize), 2.0);
  cv::Mat corner(100, 100, CV_8UC1, cv::Scalar(30));
  corner(cv::Rect(50, 50, 50, 50)).setTo(200);
  EXPECT_GT(WindowMinEigenvalue(corner, {50, 50}, kPatchSize), 1.0);
}

TEST(PatchAlignment, WeightsAlignByOneSideOnly) {
  // The left half of the window moves by +5 px, the right half stays: weighted by the left
  // half, the alignment follows the left.
  const cv::Mat gray1 = Texture(6);
  const cv::Mat moved = Shifted(gray1, 5.0, 0.0);
  cv::Mat gray2 = gray1.clone();
  moved(cv::Rect(0, 0, 125, gray1.rows)).copyTo(gray2(cv::Rect(0, 0, 125, gray1.rows)));
  std::vector<PatchSide> mask(kPatchSize * kPatchSize, PatchSide::kNone);
  for (int r = 0; r < kPatchSize; ++r) {
    for (int c = 0; c < kPatchSize / 2 - 1; ++c) mask[r * kPatchSize + c] = PatchSide::kPlus;
  }
  PatchAlignmentOptions options;
  options.levels = 0;
  const ImagePyramid p1(gray1, options.levels), p2(gray2, options.levels);
  const PatchAlignment a =
      AlignPatch(p1, {120, 100}, p2, {123, 100}, SideWeights(mask, PatchSide::kPlus), options);
  ASSERT_TRUE(a.converged);
  EXPECT_NEAR(a.position.x, 125.0, 0.2);
  EXPECT_NEAR(a.position.y, 100.0, 0.2);
}

TEST(PatchAlignment, IsDeterministic) {
  const cv::Mat gray1 = Texture(7);
  const cv::Mat gray2 = Shifted(gray1, 2.3, 1.1, 1.1, -5.0);
  PatchAlignmentOptions options;
  const ImagePyramid p1(gray1, options.levels), p2(gray2, options.levels);
  const PatchAlignment a = AlignPatch(p1, {100, 90}, p2, {100, 90}, {}, options);
  const PatchAlignment b = AlignPatch(p1, {100, 90}, p2, {100, 90}, {}, options);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.residual, b.residual);
  EXPECT_EQ(a.gain, b.gain);
}

TEST(PatchAlignment, RejectsBadInputs) {
  PatchAlignmentOptions options;
  options.window = 4;
  EXPECT_THROW(options.Check(), Error);
  options = PatchAlignmentOptions();
  options.min_gain = 2.0;
  options.max_gain = 1.0;
  EXPECT_THROW(options.Check(), Error);
  EXPECT_THROW(ImagePyramid(cv::Mat(), 2), Error);
  EXPECT_THROW(ImagePyramid(cv::Mat(50, 50, CV_32F), 2), Error);
  const ImagePyramid small(Texture(8, 120, 100), 3), large(Texture(8), 3);
  EXPECT_THROW(AlignPatch(small, {60, 50}, large, {60, 50}, {}, PatchAlignmentOptions()), Error);
  EXPECT_THROW(AlignPatch(large, {60, 50}, large, {60, 50}, AlignmentWeights(10, 1.0f),
                          PatchAlignmentOptions()),
               Error);
  EXPECT_THROW(SideWeights(std::vector<PatchSide>(3), PatchSide::kPlus), Error);
}

}  // namespace
}  // namespace comic::frontend
