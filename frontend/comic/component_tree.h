// The component tree of an image block: every connected component of every lower level set
// {p : I(p) <= l} (4-connected), with its area and the length of its boundary inside the block.
// The iso-curves of the block at level l + 0.5 are exactly the boundaries of these components, so
// this is the "MSER-like algorithm run in an image block" of paper §3 on which CoMIC's
// initialisation stage measures stability (Eq. 1). The upper level sets {I > l} (the other
// polarity) are the lower level sets of 255 - I, which Build() takes as a flag.
//
// Built by union-find region growing over the pixels sorted by grey value (counting sort), in
// time linear in the block's pixels up to the inverse-Ackermann factor (Najman & Couprie 2006;
// Berger et al. 2007; the same complexity as the Nistér & Stewénius 2008 MSER the paper cites).
// Area and boundary length are accumulated incrementally: a pixel's contribution to the boundary
// of the component it joins is (its neighbours not yet in the set) - (its neighbours already in
// it), which is additive over the component.
//
//   ComponentTree tree;                       // reuse one per thread: buffers are kept
//   tree.Build(image(block_rect), /*upper_sets=*/false);
//   for (int node : tree.Nodes()) { ... tree.Level(node), tree.Area(node), tree.Perimeter(node) }
//
// Nodes and pixels are indices into a padded (width + 2) x (height + 2) grid; PixelX/PixelY map
// them back to block coordinates.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace comic::frontend {

class ComponentTree {
 public:
  // Builds the tree of `block` (CV_8UC1, any stride, at least 1x1). With `upper_sets` the tree of
  // the upper level sets is built, i.e. that of 255 - block; Level() and Value() then report the
  // inverted grey values.
  void Build(const cv::Mat& block, bool upper_sets);

  int width() const { return width_; }
  int height() const { return height_; }
  bool upper_sets() const { return upper_sets_; }
  // Row stride of the padded grid: the 4-neighbours of pixel p are p +- 1 and p +- Stride().
  int Stride() const { return width_ + 2; }
  int PixelIndex(int x, int y) const { return (y + 1) * Stride() + x + 1; }
  int PixelX(int pixel) const { return pixel % Stride() - 1; }
  int PixelY(int pixel) const { return pixel / Stride() - 1; }
  bool InBlock(int pixel) const { return grow_[pixel].zpar != kOutside; }
  // The (possibly inverted) grey value of a pixel of the block.
  int Value(int pixel) const { return values_[pixel]; }

  // Nodes in processing order: every node comes after all of its descendants; the last is the
  // root (the whole block).
  const std::vector<int>& Nodes() const { return nodes_; }
  int Root() const { return nodes_.back(); }
  // Grey level at which the component appears; it is unchanged for levels up to
  // Level(Parent(node)) - 1.
  int Level(int node) const { return values_[node]; }
  int Parent(int node) const { return node == Root() ? -1 : parent_[node]; }
  // The child with the largest area (ties: the first processed), -1 for a leaf. Following main
  // children is how the component "at a lower level" is chosen, as in MSER.
  int MainChild(int node) const { return main_child_[node]; }
  int Area(int node) const { return area_[node]; }
  // Boundary length inside the block in pixel edges: the number of 4-neighbour pairs (in, out)
  // with both pixels in the block. Edges against the block border are not part of the
  // iso-curve portion in the block and are not counted.
  int Perimeter(int node) const { return perimeter_[node]; }
  // The node a pixel belongs to at its own grey level.
  int NodeOfPixel(int pixel) const;

  // The component containing `node` at `level` >= Level(node): its highest ancestor with
  // Level <= level.
  int AncestorAtLevel(int node, int level) const;
  // The component at `level` on the main-child line of `node`: `node` itself if
  // level >= Level(node), otherwise the first main descendant with Level <= level, or -1 when the
  // line ends (the component does not exist yet at that level).
  int MainDescendantAtLevel(int node, int level) const;
  // Area of MainDescendantAtLevel (0 when it does not exist).
  int MainDescendantArea(int node, int level) const;

 private:
  static constexpr int32_t kOutside = -2;
  static constexpr int32_t kUnprocessed = -1;

  // Per-pixel state of the region growing.
  struct GrowRecord {
    int32_t zpar;          // union-find parent; kOutside marks the padding
    int32_t top;           // for a union-find root: the top pixel of its component in the tree
    int32_t parent;        // tree parent during growing
    uint8_t rank;          // union-find rank
    int16_t contribution;  // the pixel's contribution to its component's boundary length
  };

  int width_ = 0;
  int height_ = 0;
  bool upper_sets_ = false;
  std::vector<uint8_t> values_;  // padded grid
  std::vector<int32_t> order_;   // pixels sorted by value (stable)
  std::vector<int32_t> parent_;  // tree parent (canonical after Build)
  std::vector<GrowRecord> grow_;
  std::vector<int32_t> area_;        // valid on canonical pixels
  std::vector<int32_t> perimeter_;   // valid on canonical pixels
  std::vector<int32_t> main_child_;  // valid on canonical pixels
  std::vector<int> nodes_;
};

}  // namespace comic::frontend
