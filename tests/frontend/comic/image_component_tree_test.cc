#include "frontend/comic/image_component_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/comic/component_tree.h"

namespace comic::frontend {
namespace {

// Every node of the whole-image tree against ComponentTree's node of the same canonical pixel:
// level, area, boundary, parent, main child and first pixel (the smallest raster index among the
// pixels of ComponentTree's component).
void ExpectSameTree(const cv::Mat& image, bool upper) {
  ComponentTree reference;
  reference.Build(image, upper);
  ImageComponentTree tree;
  tree.Build(image, upper);
  ASSERT_EQ(static_cast<size_t>(tree.NumNodes()), reference.Nodes().size());
  ASSERT_EQ(tree.Nodes().size(), reference.Nodes().size());
  auto raster = [&](int padded) {
    return reference.PixelY(padded) * image.cols + reference.PixelX(padded);
  };
  // ComponentTree's node of each canonical pixel, and the first pixel of each of its nodes.
  std::map<int, int> reference_node;
  for (int node : reference.Nodes()) reference_node[raster(node)] = node;
  std::map<int, int> first_pixel;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      for (int node = reference.NodeOfPixel(reference.PixelIndex(x, y)); node >= 0;
           node = reference.Parent(node)) {
        if (!first_pixel.count(node)) first_pixel[node] = y * image.cols + x;
      }
    }
  }
  auto same = [&](int node) { return node < 0 ? -1 : raster(node); };
  for (int node : tree.Nodes()) {
    ASSERT_TRUE(reference_node.count(tree.CanonicalPixel(node))) << tree.CanonicalPixel(node);
    const int r = reference_node[tree.CanonicalPixel(node)];
    EXPECT_EQ(tree.Level(node), reference.Level(r));
    EXPECT_EQ(tree.Area(node), reference.Area(r));
    EXPECT_EQ(tree.Perimeter(node), reference.Perimeter(r));
    EXPECT_EQ(tree.FirstPixel(node), first_pixel[r]);
    const int parent = tree.Parent(node);
    EXPECT_EQ(parent < 0 ? -1 : tree.CanonicalPixel(parent), same(reference.Parent(r)));
    const int main = tree.MainChild(node);
    EXPECT_EQ(main < 0 ? -1 : tree.CanonicalPixel(main), same(reference.MainChild(r)));
  }
  EXPECT_EQ(tree.CanonicalPixel(tree.Root()), raster(reference.Root()));
  EXPECT_EQ(tree.Parent(tree.Root()), -1);
  // Descendants first.
  std::vector<int> position(tree.NumNodes());
  for (size_t i = 0; i < tree.Nodes().size(); ++i) position[tree.Nodes()[i]] = static_cast<int>(i);
  for (int node : tree.Nodes()) {
    if (tree.Parent(node) >= 0) {
      EXPECT_LT(position[node], position[tree.Parent(node)]);
    }
  }
}

TEST(ImageComponentTree, SmallImageByHand) {
  cv::Mat image = (cv::Mat_<uint8_t>(5, 5) << 9, 9, 9, 9, 9, 9, 1, 1, 9, 9, 9, 1, 1, 9, 9, 9, 9, 9,
                   5, 9, 9, 9, 9, 9, 9);
  ImageComponentTree tree;
  tree.Build(image, false);
  ASSERT_EQ(tree.NumNodes(), 3);
  const int root = tree.Root();
  EXPECT_EQ(tree.Level(root), 9);
  EXPECT_EQ(tree.Area(root), 25);
  EXPECT_EQ(tree.Perimeter(root), 0);
  const int square = tree.MainChild(root);
  EXPECT_EQ(tree.Level(square), 1);
  EXPECT_EQ(tree.Area(square), 4);
  EXPECT_EQ(tree.Perimeter(square), 8);
  EXPECT_EQ(tree.FirstPixel(square), 1 * 5 + 1);
  EXPECT_EQ(tree.CanonicalPixel(square), 2 * 5 + 2);
  EXPECT_EQ(tree.AncestorAtLevel(square, 8), square);
  EXPECT_EQ(tree.AncestorAtLevel(square, 9), root);
  EXPECT_EQ(tree.MainDescendantAtLevel(root, 3), square);
  EXPECT_EQ(tree.MainDescendantAtLevel(root, 0), -1);
  EXPECT_EQ(tree.MainDescendantArea(root, 0), 0);
}

TEST(ImageComponentTree, FlatAndTinyImages) {
  ImageComponentTree tree;
  tree.Build(cv::Mat(6, 7, CV_8UC1, cv::Scalar(42)), false);
  ASSERT_EQ(tree.NumNodes(), 1);
  EXPECT_EQ(tree.Area(tree.Root()), 42);
  EXPECT_EQ(tree.Perimeter(tree.Root()), 0);
  EXPECT_EQ(tree.FirstPixel(tree.Root()), 0);
  tree.Build(cv::Mat(1, 1, CV_8UC1, cv::Scalar(3)), true);
  ASSERT_EQ(tree.NumNodes(), 1);
  EXPECT_EQ(tree.Level(tree.Root()), 252);
}

TEST(ImageComponentTree, SameNodesAsComponentTreeOnRandomImages) {
  cv::RNG rng(2024);
  for (int trial = 0; trial < 12; ++trial) {
    const int rows = 1 + rng.uniform(0, 23), cols = 1 + rng.uniform(0, 29);
    cv::Mat image(rows, cols, CV_8UC1);
    // Few levels (merges, flat zones, equal-area children), or the full range.
    rng.fill(image, cv::RNG::UNIFORM, 0, trial % 3 == 0 ? 256 : 2 + trial);
    for (bool upper : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "trial " << trial << " upper " << upper);
      ExpectSameTree(image, upper);
    }
  }
}

TEST(ImageComponentTree, SameNodesAsComponentTreeOnASmoothImage) {
  cv::Mat image(40, 50, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      image.at<uint8_t>(y, x) =
          static_cast<uint8_t>(128 + 60 * std::sin(x * 0.3) * std::cos(y * 0.2) + (x * y) % 7);
    }
  }
  ExpectSameTree(image, false);
  ExpectSameTree(image, true);
  ExpectSameTree(image(cv::Rect(3, 5, 30, 20)), false);  // a view with a stride
}

}  // namespace
}  // namespace comic::frontend
