// The component tree of a whole image, nodes only: every connected component (4-connected) of every
// lower level set {p : I(p) <= l} at a grey level where it holds pixels of value l, with its area,
// its boundary length inside the image and its first pixel in raster order. It is the tree the
// direct search (comic_direct_detector.h) reads the stable iso-curves from: the same nodes, areas,
// boundaries, parents and main children as ComponentTree built on the whole image, without
// ComponentTree's per-pixel records (union-find parents, ranks, per-pixel node, areas and
// perimeters), which the direct search never reads.
//
// Built by flooding, as linear-time MSER does (Nistér & Stewénius 2008): the flood always moves to
// the lowest pixel on its boundary (one stack of pixels per grey level), a stack of components
// holds the current lineage, and a component becomes a node when the flood leaves its level. Per
// pixel it keeps a grey value, two flags and one entry in a boundary stack; per node a small
// record.
//
//   ImageComponentTree tree;                   // reuse one per thread: buffers are kept
//   tree.Build(image, /*upper_sets=*/false);  // upper_sets: the tree of 255 - image
//   for (int node : tree.Nodes()) { ... tree.Level(node), tree.Area(node), tree.Perimeter(node) }
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace comic::frontend {

class ImageComponentTree {
 public:
  // Builds the tree of `image` (CV_8UC1, any stride, at least 1x1). With `upper_sets` the tree of
  // the upper level sets is built, i.e. that of 255 - image; Level() then reports inverted values.
  void Build(const cv::Mat& image, bool upper_sets);

  int width() const { return width_; }
  int height() const { return height_; }
  bool upper_sets() const { return upper_sets_; }

  // Nodes in processing order: every node comes after all of its descendants; the last is the
  // root (the whole image). Node ids are indices in [0, NumNodes()).
  const std::vector<int>& Nodes() const { return order_; }
  int NumNodes() const { return static_cast<int>(nodes_.size()); }
  int Root() const { return order_.back(); }
  // Grey level (of the possibly inverted values) at which the component appears; it is unchanged
  // for levels up to Level(Parent(node)) - 1.
  int Level(int node) const { return nodes_[node].level; }
  int Parent(int node) const { return nodes_[node].parent; }
  // The child with the largest area, -1 for a leaf; ties go to the child ComponentTree processes
  // first (lower level, then lower CanonicalPixel), so that both trees choose alike.
  int MainChild(int node) const { return nodes_[node].main_child; }
  int Area(int node) const { return nodes_[node].area; }
  // Boundary length inside the image in pixel edges (4-neighbour pairs (in, out), both pixels in
  // the image).
  int Perimeter(int node) const { return nodes_[node].perimeter; }
  // The component's first pixel in raster order (y * width + x): the pixel above it (or, on the
  // first row, to its left) is outside the component and not in one of its holes.
  int FirstPixel(int node) const { return nodes_[node].first_pixel; }
  // The last pixel in raster order among the node's pixels of value Level(node) (y * width + x):
  // the pixel ComponentTree names the node by, so sorting by it orders nodes as ComponentTree ids.
  int CanonicalPixel(int node) const { return nodes_[node].canonical_pixel; }

  // The component containing `node` at `level` >= Level(node): its highest ancestor with
  // Level <= level.
  int AncestorAtLevel(int node, int level) const;
  // The component at `level` on the main-child line of `node`: `node` itself if
  // level >= Level(node), otherwise the first main descendant with Level <= level, or -1 when the
  // line ends.
  int MainDescendantAtLevel(int node, int level) const;
  // Area of MainDescendantAtLevel (0 when it does not exist).
  int MainDescendantArea(int node, int level) const;

 private:
  struct Node {
    int32_t parent;
    int32_t area;
    int32_t perimeter;
    int32_t first_pixel;
    int32_t canonical_pixel;
    int32_t main_child;
    int32_t level;
  };
  // A component of the current lineage while the flood grows it.
  struct Growing {
    int32_t level;
    int32_t node;  // id of the node it becomes
    int32_t area;
    int32_t perimeter;
    int32_t first_pixel;      // padded index
    int32_t canonical_pixel;  // padded index, -1 while it holds no pixel of its level
  };

  // Stage 1 of Build: the padded grid of (possibly inverted) values, the frame's flags, and
  // `start`, where each grey level's boundary stack begins.
  void PadImage(const cv::Mat& image, std::array<int, 257>* start);
  // Stage 3 of Build: padded indices to raster ones; main children with ComponentTree's tie rule.
  void FinishNodes();
  int NewNode();
  // The top component's level becomes `level` (> its level): it is closed as a node, and merged
  // into the components below it that it reaches at `level`, or continued at `level`.
  void RaiseTo(int level);
  void CloseTop(int parent);

  int width_ = 0;
  int height_ = 0;
  bool upper_sets_ = false;
  std::vector<uint8_t> values_;     // padded (width + 2) x (height + 2)
  std::vector<uint8_t> flags_;      // padded: kQueued, kIn, kPadding
  std::vector<uint32_t> boundary_;  // per grey level, a stack of (pixel << 2 | next edge)
  std::vector<Growing> stack_;
  std::vector<Node> nodes_;
  std::vector<int> order_;
};

}  // namespace comic::frontend
