#include "frontend/matching/descriptor_matcher.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

// `count` random descriptors of length ~512 (sparse non-negative entries, as SIFT's).
cv::Mat RandomDescriptors(int count, int seed) {
  cv::RNG rng(seed);
  cv::Mat descriptors(count, 128, CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < count; ++r) {
    cv::Mat row(1, 128, CV_32F);
    for (int c = 0; c < 128; ++c)
      row.at<float>(c) = rng.uniform(0.f, 1.f) < 0.3f ? rng.uniform(0.f, 1.f) : 0.f;
    row *= 512.0 / std::max(cv::norm(row), 1e-9);
    for (int c = 0; c < 128; ++c) {
      descriptors.at<uint8_t>(r, c) = cv::saturate_cast<uint8_t>(row.at<float>(c));
    }
  }
  return descriptors;
}

TEST(DescriptorMatcher, FindsEachDescriptorInAShuffledNoisyCopy) {
  const cv::Mat a = RandomDescriptors(300, 1);
  std::vector<int> order(a.rows);
  for (int i = 0; i < a.rows; ++i)
    order[i] = (i * 37) % a.rows;  // a permutation (37 and 300 coprime)
  cv::Mat b(a.rows, 128, CV_8UC1);
  cv::RNG rng(2);
  for (int i = 0; i < a.rows; ++i) {
    for (int c = 0; c < 128; ++c) {
      b.at<uint8_t>(order[i], c) =
          cv::saturate_cast<uint8_t>(a.at<uint8_t>(i, c) + rng.uniform(-4, 5));
    }
  }
  const std::vector<PatchMatch> matches = MatchDescriptors(a, b);
  ASSERT_EQ(matches.size(), 300u);
  for (const PatchMatch& m : matches) {
    EXPECT_EQ(m.index2, order[m.index1]);
    EXPECT_LT(m.cost, 0.2f);  // radians (the noise is ~0.13)
  }
  EXPECT_TRUE(std::is_sorted(matches.begin(), matches.end(),
                             [](const auto& x, const auto& y) { return x.index1 < y.index1; }));
}

TEST(DescriptorMatcher, RatioTestRejectsAmbiguousMatches) {
  const cv::Mat a = RandomDescriptors(5, 3);
  cv::Mat b;
  cv::vconcat(a, a.row(2), b);  // descriptor 2 twice in b: as near as each other
  const std::vector<PatchMatch> matches = MatchDescriptors(a, b);
  ASSERT_EQ(matches.size(), 4u);
  for (const PatchMatch& m : matches) EXPECT_NE(m.index1, 2);
  DescriptorMatchOptions no_ratio;
  no_ratio.max_ratio = 1.0;  // best >= 1.0 x second still rejects equal distances
  EXPECT_EQ(MatchDescriptors(a, b, no_ratio).size(), 4u);
}

TEST(DescriptorMatcher, DistanceAndCrossCheck) {
  // Orthogonal descriptors are pi/2 apart: beyond max_distance 0.7.
  cv::Mat a(1, 128, CV_8UC1, cv::Scalar(0)), b(1, 128, CV_8UC1, cv::Scalar(0));
  a.at<uint8_t>(0) = 255;
  a.at<uint8_t>(1) = 255;
  b.at<uint8_t>(2) = 255;
  b.at<uint8_t>(3) = 255;
  EXPECT_TRUE(MatchDescriptors(a, b).empty());
  // a0 and a1 both have b0 as their accepted nearest; b0's nearest is a1: cross check keeps
  // a1-b0 only. (Lengths near 512, as the angle dot / 512^2 assumes.)
  cv::Mat a2(2, 128, CV_8UC1, cv::Scalar(0)), b2(2, 128, CV_8UC1, cv::Scalar(0));
  for (int c = 0; c < 4; ++c) {
    b2.at<uint8_t>(0, c) = 255;      // b0: dims 0-3, length 510
    b2.at<uint8_t>(1, 4 + c) = 255;  // b1: dims 4-7
    a2.at<uint8_t>(0, c) = 210;      // a0: 0.62 rad from b0
    a2.at<uint8_t>(0, 9 + c) = 150;
    a2.at<uint8_t>(1, c) = 250;  // a1: 0.23 rad from b0
  }
  a2.at<uint8_t>(1, 8) = 50;
  DescriptorMatchOptions options;
  const std::vector<PatchMatch> crossed = MatchDescriptors(a2, b2, options);
  ASSERT_EQ(crossed.size(), 1u);
  EXPECT_EQ(crossed[0].index1, 1);
  EXPECT_EQ(crossed[0].index2, 0);
  options.cross_check = false;
  EXPECT_EQ(MatchDescriptors(a2, b2, options).size(), 2u);
}

TEST(DescriptorMatcher, GuidedMatchingComparesOnlyAlongTheEpipolarLine) {
  // Rectified views: x2ᵀ F x1 = y1 − y2, the lines are the rows. a0 looks exactly like b0 and
  // b1; only b0 lies on a0's row, so the ratio test along the row keeps a0-b0 where the plain one
  // rejects it.
  const cv::Mat a = RandomDescriptors(1, 7);
  cv::Mat b;
  cv::vconcat(a, a, b);
  FeatureSet f1(1), f2(2);
  f1[0].x = 10;
  f1[0].y = 50;
  f2[0].x = 30;
  f2[0].y = 51.5f;  // 1.5 px off the row
  f2[1].x = 30;
  f2[1].y = 200;
  const cv::Matx33d rectified(0, 0, 0, 0, 0, -1, 0, 1, 0);
  EXPECT_TRUE(MatchDescriptors(a, b).empty());
  const std::vector<PatchMatch> guided =
      MatchDescriptorsAlongEpipolarLines(a, b, f1, f2, rectified, 2.0);
  ASSERT_EQ(guided.size(), 1u);
  EXPECT_EQ(guided[0].index1, 0);
  EXPECT_EQ(guided[0].index2, 0);
  // A band narrower than the 1.5 px leaves no candidate.
  EXPECT_TRUE(MatchDescriptorsAlongEpipolarLines(a, b, f1, f2, rectified, 1.0).empty());
  EXPECT_THROW(MatchDescriptorsAlongEpipolarLines(a, b, f1, FeatureSet(1), rectified, 2.0), Error);
  EXPECT_THROW(MatchDescriptorsAlongEpipolarLines(a, b, f1, f2, rectified, 0.0), Error);
}

TEST(DescriptorMatcher, DotProductsAreExactIntegers) {
  const cv::Mat a = RandomDescriptors(40, 4), b = RandomDescriptors(30, 5);
  const cv::Mat dots = DescriptorDotProducts(a, b);
  ASSERT_EQ(dots.size(), cv::Size(30, 40));
  for (int i = 0; i < a.rows; ++i) {
    for (int j = 0; j < b.rows; ++j) {
      int64_t dot = 0;
      for (int c = 0; c < 128; ++c) dot += a.at<uint8_t>(i, c) * b.at<uint8_t>(j, c);
      ASSERT_EQ(static_cast<int64_t>(dots.at<float>(i, j)), dot);
    }
  }
}

TEST(DescriptorMatcher, EmptyAndBadInput) {
  const cv::Mat a = RandomDescriptors(3, 6);
  EXPECT_TRUE(MatchDescriptors(a, cv::Mat(0, 128, CV_8UC1)).empty());
  EXPECT_TRUE(MatchDescriptors(cv::Mat(), a).empty());
  EXPECT_THROW(MatchDescriptors(a, cv::Mat(3, 64, CV_8UC1, cv::Scalar(1))), Error);
  EXPECT_THROW(MatchDescriptors(a, cv::Mat(3, 128, CV_32F, cv::Scalar(1))), Error);
  DescriptorMatchOptions bad;
  bad.max_ratio = 0;
  EXPECT_THROW(MatchDescriptors(a, a, bad), Error);
}

}  // namespace
}  // namespace comic::frontend
