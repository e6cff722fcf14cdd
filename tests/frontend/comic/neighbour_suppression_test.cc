#include "frontend/comic/neighbour_suppression.h"

#include <gtest/gtest.h>

#include <vector>

namespace comic::frontend {
namespace {

struct Candidate {
  cv::Point2f position;
  int group = 0;
};

cv::Point2f PositionOf(const Candidate& c) { return c.position; }

std::vector<cv::Point2f> Positions(const std::vector<Candidate>& candidates) {
  std::vector<cv::Point2f> positions;
  for (const Candidate& c : candidates) positions.push_back(c.position);
  return positions;
}

TEST(NeighbourSuppression, KeepsTheFirstAndDropsNeighboursUpToTheRadiusInclusive) {
  // Seeds on the pixel grid one radius apart are neighbours (the seeds' suppression relies on it).
  const std::vector<Candidate> kept = SuppressNeighbours(
      std::vector<Candidate>{{{0, 0}}, {{1, 0}}, {{2.5f, 0}}, {{-3, -3}}, {{-3.5f, -3}}}, 1.0,
      PositionOf);
  EXPECT_EQ(Positions(kept), (std::vector<cv::Point2f>{{0, 0}, {2.5f, 0}, {-3, -3}}));
}

TEST(NeighbourSuppression, OnlyTheSameGroupSuppresses) {
  const auto same_group = [](const Candidate& a, const Candidate& b) { return a.group == b.group; };
  const std::vector<Candidate> kept =
      SuppressNeighbours(std::vector<Candidate>{{{5, 5}, 0}, {{5.5f, 5}, 1}, {{5, 5.5f}, 0}}, 2.0,
                         PositionOf, same_group);
  EXPECT_EQ(Positions(kept), (std::vector<cv::Point2f>{{5, 5}, {5.5f, 5}}));
}

TEST(NeighbourSuppression, ARadiusOfZeroOrASmallOneKeepsWhatIsApart) {
  const std::vector<Candidate> twins = {{{1, 1}}, {{1, 1}}};
  EXPECT_EQ(SuppressNeighbours(twins, 0.0, PositionOf).size(), 2u);
  // A radius under a pixel: cells stay a pixel wide, neighbours within the radius still found.
  const std::vector<Candidate> kept = SuppressNeighbours(
      std::vector<Candidate>{{{0.95f, 0}}, {{1.05f, 0}}, {{1.5f, 0}}}, 0.25, PositionOf);
  EXPECT_EQ(Positions(kept), (std::vector<cv::Point2f>{{0.95f, 0}, {1.5f, 0}}));
}

}  // namespace
}  // namespace comic::frontend
