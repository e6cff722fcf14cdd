#include "frontend/comic/component_tree.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <queue>
#include <vector>

namespace comic::frontend {
namespace {

cv::Mat Block(const std::vector<std::vector<uint8_t>>& rows) {
  cv::Mat block(static_cast<int>(rows.size()), static_cast<int>(rows[0].size()), CV_8UC1);
  for (int y = 0; y < block.rows; ++y) {
    for (int x = 0; x < block.cols; ++x) block.at<uint8_t>(y, x) = rows[y][x];
  }
  return block;
}

int NodeAt(const ComponentTree& tree, int x, int y) {
  return tree.NodeOfPixel(tree.PixelIndex(x, y));
}

TEST(ComponentTree, AreasPerimetersAndParentsOfASmallBlock) {
  const cv::Mat block =
      Block({{9, 9, 9, 9, 9}, {9, 1, 1, 9, 9}, {9, 1, 1, 9, 9}, {9, 9, 9, 5, 9}, {9, 9, 9, 9, 9}});
  ComponentTree tree;
  tree.Build(block, /*upper_sets=*/false);
  const int square = NodeAt(tree, 1, 1);
  const int single = NodeAt(tree, 3, 3);
  EXPECT_EQ(NodeAt(tree, 2, 2), square);
  EXPECT_EQ(tree.Level(square), 1);
  EXPECT_EQ(tree.Area(square), 4);
  EXPECT_EQ(tree.Perimeter(square), 8);  // each pixel has two neighbours outside
  EXPECT_EQ(tree.Level(single), 5);
  EXPECT_EQ(tree.Area(single), 1);
  EXPECT_EQ(tree.Perimeter(single), 4);
  const int root = tree.Root();
  EXPECT_EQ(tree.Level(root), 9);
  EXPECT_EQ(tree.Area(root), 25);
  EXPECT_EQ(tree.Perimeter(root), 0);  // the block border is not part of any iso-curve
  EXPECT_EQ(tree.Parent(square), root);
  EXPECT_EQ(tree.Parent(single), root);
  EXPECT_EQ(tree.Parent(root), -1);
  EXPECT_EQ(tree.MainChild(root), square);  // the larger child
  EXPECT_EQ(tree.MainChild(square), -1);
  EXPECT_EQ(tree.Nodes().size(), 3u);
  EXPECT_EQ(tree.Nodes().back(), root);
}

TEST(ComponentTree, EdgesAgainstTheBlockBorderAreNotBoundary) {
  const cv::Mat block = Block({{1, 1, 9}, {1, 1, 9}, {9, 9, 9}});
  ComponentTree tree;
  tree.Build(block, false);
  EXPECT_EQ(tree.Perimeter(NodeAt(tree, 0, 0)), 4);
}

TEST(ComponentTree, UpperSetsAreTheTreeOfTheInvertedBlock) {
  const cv::Mat block =
      Block({{9, 9, 9, 9, 9}, {9, 1, 1, 9, 9}, {9, 1, 1, 9, 9}, {9, 9, 9, 5, 9}, {9, 9, 9, 9, 9}});
  ComponentTree tree;
  tree.Build(block, /*upper_sets=*/true);
  EXPECT_TRUE(tree.upper_sets());
  const int bright = NodeAt(tree, 0, 0);
  EXPECT_EQ(tree.Level(bright), 255 - 9);
  EXPECT_EQ(tree.Area(bright), 20);
  EXPECT_EQ(tree.Perimeter(bright), 12);  // 8 around the dark square, 4 around the 5
  EXPECT_EQ(tree.Area(tree.Parent(bright)), 21);
  EXPECT_EQ(tree.Level(tree.Root()), 255 - 1);
  EXPECT_EQ(tree.Area(tree.Root()), 25);
}

TEST(ComponentTree, AncestorAndMainDescendantQueries) {
  // Concentric rings 10 (centre) < 20 < 30 (outside).
  cv::Mat block(9, 9, CV_8UC1, cv::Scalar(30));
  block(cv::Rect(2, 2, 5, 5)).setTo(20);
  block(cv::Rect(4, 4, 1, 1)).setTo(10);
  ComponentTree tree;
  tree.Build(block, false);
  const int centre = NodeAt(tree, 4, 4);
  const int ring = NodeAt(tree, 2, 2);
  EXPECT_EQ(tree.Parent(centre), ring);
  EXPECT_EQ(tree.AncestorAtLevel(centre, 10), centre);
  EXPECT_EQ(tree.AncestorAtLevel(centre, 19), centre);
  EXPECT_EQ(tree.AncestorAtLevel(centre, 20), ring);
  EXPECT_EQ(tree.AncestorAtLevel(centre, 255), tree.Root());
  EXPECT_EQ(tree.MainDescendantAtLevel(tree.Root(), 29), ring);
  EXPECT_EQ(tree.MainDescendantAtLevel(tree.Root(), 15), centre);
  EXPECT_EQ(tree.MainDescendantAtLevel(tree.Root(), 9), -1);
  EXPECT_EQ(tree.MainDescendantArea(tree.Root(), 9), 0);
  EXPECT_EQ(tree.MainDescendantArea(tree.Root(), 25), 25);
  EXPECT_EQ(tree.MainDescendantArea(ring, 40), 25);  // at or above its level: itself
}

TEST(ComponentTree, FlatBlockIsOneNode) {
  ComponentTree tree;
  tree.Build(cv::Mat(6, 7, CV_8UC1, cv::Scalar(42)), false);
  ASSERT_EQ(tree.Nodes().size(), 1u);
  EXPECT_EQ(tree.Area(tree.Root()), 42);
  EXPECT_EQ(tree.Perimeter(tree.Root()), 0);
}

// Brute force: the 4-connected component of {v <= level} containing (x, y), and its boundary
// pairs inside the block.
void FloodComponent(const cv::Mat& block, int x, int y, int level, int* area, int* perimeter) {
  cv::Mat seen(block.size(), CV_8UC1, cv::Scalar(0));
  std::queue<cv::Point> queue;
  queue.push({x, y});
  seen.at<uint8_t>(y, x) = 1;
  *area = 0;
  *perimeter = 0;
  while (!queue.empty()) {
    const cv::Point p = queue.front();
    queue.pop();
    ++*area;
    for (const cv::Point d :
         {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1), cv::Point(0, -1)}) {
      const cv::Point q = p + d;
      if (q.x < 0 || q.y < 0 || q.x >= block.cols || q.y >= block.rows) continue;
      if (block.at<uint8_t>(q) > level) {
        ++*perimeter;
      } else if (!seen.at<uint8_t>(q)) {
        seen.at<uint8_t>(q) = 1;
        queue.push(q);
      }
    }
  }
}

TEST(ComponentTree, EveryNodeMatchesABruteForceFloodFill) {
  cv::Mat block(11, 13, CV_8UC1);
  cv::RNG rng(12345);
  rng.fill(block, cv::RNG::UNIFORM, 0, 6);  // few levels: many merges and flat zones
  for (bool upper : {false, true}) {
    const cv::Mat values = upper ? cv::Mat(255 - block) : block;
    ComponentTree tree;
    tree.Build(block, upper);
    int nodes_checked = 0;
    for (int y = 0; y < block.rows; ++y) {
      for (int x = 0; x < block.cols; ++x) {
        // The component of (x, y) at every level from its own value up.
        const int leaf = NodeAt(tree, x, y);
        const int top = upper ? 255 : 5;  // values span 0..5 (inverted: 250..255)
        for (int level = values.at<uint8_t>(y, x); level <= top; ++level) {
          const int node = tree.AncestorAtLevel(leaf, level);
          int area = 0, perimeter = 0;
          FloodComponent(values, x, y, level, &area, &perimeter);
          ASSERT_EQ(tree.Area(node), area) << x << "," << y << " level " << level;
          ASSERT_EQ(tree.Perimeter(node), perimeter) << x << "," << y << " level " << level;
          ++nodes_checked;
        }
      }
    }
    EXPECT_GT(nodes_checked, 300);
  }
}

}  // namespace
}  // namespace comic::frontend
