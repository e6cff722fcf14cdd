#include "frontend/comic/component_tree.h"

#include <array>
#include <utility>

#include "io/core/error.h"

namespace comic::frontend {

void ComponentTree::Build(const cv::Mat& block, bool upper_sets) {
  COMIC_CHECK(!block.empty() && block.type() == CV_8UC1, kInvalidArgument,
              "ComponentTree: expected a non-empty 8-bit single-channel block");
  width_ = block.cols;
  height_ = block.rows;
  upper_sets_ = upper_sets;
  const int stride = Stride();
  const int padded_size = stride * (height_ + 2);
  const int num_pixels = width_ * height_;

  // Everything the region growing touches per pixel sits in one record, so that visiting the
  // pixels in grey order (a random walk over the block) costs one cache line per pixel.
  grow_.assign(padded_size, GrowRecord{kOutside, 0, 0, 0, 0});
  values_.resize(padded_size);
  parent_.resize(padded_size);
  area_.resize(padded_size);
  perimeter_.resize(padded_size);
  main_child_.resize(padded_size);

  // Copy into the padded grid and count grey values (counting sort: linear, stable).
  std::array<int, 257> start{};
  const uint8_t flip = upper_sets ? 255 : 0;
  for (int y = 0; y < height_; ++y) {
    const uint8_t* row = block.ptr<uint8_t>(y);
    const int base = PixelIndex(0, y);
    for (int x = 0; x < width_; ++x) {
      const uint8_t value = row[x] ^ flip;  // 255 - v for 8-bit values
      values_[base + x] = value;
      grow_[base + x].zpar = kUnprocessed;
      ++start[value + 1];
    }
  }
  for (int v = 0; v < 256; ++v) start[v + 1] += start[v];
  order_.resize(num_pixels);
  for (int y = 0; y < height_; ++y) {
    const int base = PixelIndex(0, y);
    for (int x = 0; x < width_; ++x) order_[start[values_[base + x]]++] = base + x;
  }

  // Region growing in increasing grey order: each new pixel becomes the tree parent of the
  // components of its already-processed neighbours (their values are <= its own). The union-find
  // forest (zpar, union by rank, path halving) is separate from the tree: `top` maps a
  // union-find root to its component's current top pixel in the tree.
  GrowRecord* g = grow_.data();
  auto find = [g](int x) {
    while (g[x].zpar != x) {
      g[x].zpar = g[g[x].zpar].zpar;
      x = g[x].zpar;
    }
    return x;
  };
  const int offsets[4] = {-1, 1, -stride, stride};
  for (int i = 0; i < num_pixels; ++i) {
    const int p = order_[i];
    g[p].zpar = p;
    g[p].top = p;
    g[p].parent = p;
    int root_p = p;
    int in_block = 0;
    int processed = 0;
    for (int offset : offsets) {
      const int q = p + offset;
      const int32_t z = g[q].zpar;
      in_block += z != kOutside;
      if (z < 0) continue;  // outside the block, or not yet in the level set
      ++processed;
      int root_q = find(q);
      if (root_q == root_p) continue;
      g[g[root_q].top].parent = p;
      if (g[root_p].rank < g[root_q].rank) std::swap(root_p, root_q);
      g[root_q].zpar = root_p;
      if (g[root_p].rank == g[root_q].rank) ++g[root_p].rank;
      g[root_p].top = p;
    }
    // Boundary pairs: the pixel adds one per neighbour still outside the set and removes the one
    // each processed neighbour had counted towards it.
    g[p].contribution = static_cast<int16_t>(in_block - 2 * processed);
  }

  // Canonicalise (from the root down): every pixel points to the canonical pixel of its own level
  // component, and canonical pixels to the canonical pixel of their parent component.
  for (int i = num_pixels - 1; i >= 0; --i) {
    const int p = order_[i];
    const int q = g[p].parent;
    const int qq = g[q].parent;
    parent_[p] = values_[qq] == values_[q] ? qq : q;
    g[p].parent = parent_[p];
  }
  // Accumulate area and boundary length from the leaves up. The canonical pixel of a component
  // is the last one processed in it, so all contributions arrive before it passes its own on.
  for (int i = 0; i < num_pixels; ++i) {
    const int p = order_[i];
    area_[p] = 1;
    perimeter_[p] = g[p].contribution;
    main_child_[p] = -1;
  }
  nodes_.clear();
  const int root = order_[num_pixels - 1];
  for (int i = 0; i < num_pixels; ++i) {
    const int p = order_[i];
    const int q = parent_[p];
    const bool canonical = p == root || values_[q] != values_[p];
    if (canonical) nodes_.push_back(p);
    if (p == root) continue;
    area_[q] += area_[p];
    perimeter_[q] += perimeter_[p];
    if (canonical && (main_child_[q] < 0 || area_[p] > area_[main_child_[q]])) {
      main_child_[q] = p;
    }
  }
}

int ComponentTree::NodeOfPixel(int pixel) const {
  const int q = parent_[pixel];
  return (q == pixel || values_[q] != values_[pixel]) ? pixel : q;
}

int ComponentTree::AncestorAtLevel(int node, int level) const {
  for (;;) {
    const int parent = Parent(node);
    if (parent < 0 || Level(parent) > level) return node;
    node = parent;
  }
}

int ComponentTree::MainDescendantAtLevel(int node, int level) const {
  while (node >= 0 && Level(node) > level) node = main_child_[node];
  return node;
}

int ComponentTree::MainDescendantArea(int node, int level) const {
  const int descendant = MainDescendantAtLevel(node, level);
  return descendant < 0 ? 0 : area_[descendant];
}

}  // namespace comic::frontend
