#include "frontend/comic/image_component_tree.h"

#include <algorithm>
#include <array>
#include <climits>

#include "io/core/error.h"

namespace comic::frontend {

namespace {

// Pixel flags of the flood.
constexpr uint8_t kQueued = 1;   // reached by the flood (on a boundary stack, or taken)
constexpr uint8_t kIn = 2;       // taken into the current lineage's components
constexpr uint8_t kPadding = 4;  // the one-pixel frame around the image

// A taken pixel's change to its component's boundary length, one term per neighbour: +1 for a
// neighbour in the image not yet taken, -1 for one already taken (that pair was counted once by
// the neighbour), 0 for the frame. Indexed by the neighbour's flags.
constexpr std::array<int, 8> kBoundaryTerm = {1, 1, -1, -1, 0, 0, 0, 0};

constexpr int kEdgeBits = 3;  // the next neighbour to visit, 0..4, stored with a stacked pixel

}  // namespace

int ImageComponentTree::NewNode() {
  nodes_.push_back(Node{-1, 0, 0, 0, -1, -1, 0});
  return static_cast<int>(nodes_.size()) - 1;
}

void ImageComponentTree::CloseTop(int parent) {
  const Growing& g = stack_.back();
  nodes_[g.node] = Node{parent, g.area, g.perimeter, g.first_pixel, g.canonical_pixel, -1, g.level};
  order_.push_back(g.node);
}

void ImageComponentTree::RaiseTo(int level) {
  for (;;) {
    const Growing closed = stack_.back();
    const int below_level = stack_[stack_.size() - 2].level;
    if (level < below_level) {
      // The component grows on at `level` alone: a new node whose first child is the old one.
      const int node = NewNode();
      CloseTop(node);
      stack_.back() = Growing{level, node, closed.area, closed.perimeter, closed.first_pixel, -1};
      return;
    }
    // The flood reaches the component below at its own level: one component from there on.
    CloseTop(stack_[stack_.size() - 2].node);
    stack_.pop_back();
    Growing& below = stack_.back();
    below.area += closed.area;
    below.perimeter += closed.perimeter;
    below.first_pixel = std::min(below.first_pixel, closed.first_pixel);
    if (level <= below.level) return;
  }
}

void ImageComponentTree::PadImage(const cv::Mat& image, std::array<int, 257>* start) {
  const int stride = width_ + 2;
  const int padded_size = stride * (height_ + 2);
  // A histogram sizes the boundary stack of every grey level (a pixel is on at most one stack at
  // a time, once).
  values_.resize(padded_size);
  flags_.assign(padded_size, kQueued | kPadding);
  const uint8_t flip = upper_sets_ ? 255 : 0;
  for (int y = 0; y < height_; ++y) {
    const uint8_t* row = image.ptr<uint8_t>(y);
    uint8_t* values = values_.data() + (y + 1) * stride + 1;
    uint8_t* flags = flags_.data() + (y + 1) * stride + 1;
    for (int x = 0; x < width_; ++x) {
      const uint8_t value = row[x] ^ flip;  // 255 - v for 8-bit values
      values[x] = value;
      flags[x] = 0;
      ++(*start)[value + 1];
    }
  }
  for (int v = 0; v < 256; ++v) (*start)[v + 1] += (*start)[v];
}

void ImageComponentTree::Build(const cv::Mat& image, bool upper_sets) {
  COMIC_CHECK(!image.empty() && image.type() == CV_8UC1, kInvalidArgument,
              "ImageComponentTree: expected a non-empty 8-bit single-channel image");
  width_ = image.cols;
  height_ = image.rows;
  upper_sets_ = upper_sets;
  const int stride = width_ + 2;

  std::array<int, 257> start{};
  PadImage(image, &start);
  boundary_.resize(static_cast<size_t>(width_) * height_);
  std::array<uint32_t*, 256> top;
  for (int v = 0; v < 256; ++v) top[v] = boundary_.data() + start[v];
  std::array<uint64_t, 4> non_empty{};  // bit v: the stack of level v holds pixels
  auto push = [&](int level, uint32_t entry) {
    *top[level]++ = entry;
    non_empty[level >> 6] |= uint64_t{1} << (level & 63);
  };
  // The lowest stacked pixel, the flood's next step; nothing lower than `level` is stacked.
  auto pop = [&](int level, uint32_t* entry) {
    int word = level >> 6;
    uint64_t bits = non_empty[word] & (~uint64_t{0} << (level & 63));
    while (bits == 0) {
      if (++word == 4) return false;
      bits = non_empty[word];
    }
    const int lowest = (word << 6) + __builtin_ctzll(bits);
    *entry = *--top[lowest];
    if (top[lowest] == boundary_.data() + start[lowest]) {
      non_empty[word] &= ~(uint64_t{1} << (lowest & 63));
    }
    return true;
  };

  nodes_.clear();
  order_.clear();
  stack_.clear();
  nodes_.reserve(static_cast<size_t>(width_) * height_ / 4 + 16);
  order_.reserve(static_cast<size_t>(width_) * height_ / 4 + 16);
  stack_.push_back(Growing{256, -1, 0, 0, INT_MAX, -1});  // below every level: never closed
  const uint8_t* values = values_.data();
  uint8_t* flags = flags_.data();

  int pixel = stride + 1;  // the first pixel of the image
  int edge = 0;
  int level = values[pixel];
  flags[pixel] |= kQueued;
  stack_.push_back(Growing{level, NewNode(), 0, 0, INT_MAX, -1});
  // Visits the neighbour at `offset`; at a lower one the flood descends there first, a new
  // component on the stack, and comes back to this pixel later (it waits on its level's stack,
  // with `next_edge`, the neighbour to visit after this one). Returns whether it descended.
  auto visit = [&](int offset, int next_edge) {
    const int next = pixel + offset;
    if (flags[next] & kQueued) return false;
    flags[next] |= kQueued;
    const int next_level = values[next];
    if (next_level >= level) {
      push(next_level, static_cast<uint32_t>(next) << kEdgeBits);
      return false;
    }
    push(level, static_cast<uint32_t>(pixel) << kEdgeBits | next_edge);
    pixel = next;
    level = next_level;
    stack_.push_back(Growing{level, NewNode(), 0, 0, INT_MAX, -1});
    return true;
  };
  for (;;) {
    // The pixel's neighbours from `edge` on (unrolled: this runs four times per pixel).
    for (bool descended = true; descended; edge = 0) {
      switch (edge) {
        case 0:
          if ((descended = visit(1, 1))) break;
          [[fallthrough]];
        case 1:
          if ((descended = visit(stride, 2))) break;
          [[fallthrough]];
        case 2:
          if ((descended = visit(-1, 3))) break;
          [[fallthrough]];
        case 3:
          descended = visit(-stride, 4);
          break;
        default:
          descended = false;
      }
    }
    // Take the pixel into the top component (its level is the pixel's value).
    Growing& grown = stack_.back();
    ++grown.area;
    grown.perimeter += kBoundaryTerm[flags[pixel + 1]] + kBoundaryTerm[flags[pixel - 1]] +
                       kBoundaryTerm[flags[pixel + stride]] + kBoundaryTerm[flags[pixel - stride]];
    grown.first_pixel = std::min(grown.first_pixel, pixel);
    grown.canonical_pixel = std::max(grown.canonical_pixel, pixel);
    flags[pixel] |= kIn;
    uint32_t entry;
    if (!pop(level, &entry)) break;
    pixel = static_cast<int>(entry >> kEdgeBits);
    edge = static_cast<int>(entry & ((1u << kEdgeBits) - 1));
    if (values[pixel] != level) {
      level = values[pixel];
      RaiseTo(level);
    }
  }
  CloseTop(-1);  // the root: the whole image
  FinishNodes();
}

void ImageComponentTree::FinishNodes() {
  const int stride = width_ + 2;
  for (Node& node : nodes_) {
    node.first_pixel = (node.first_pixel / stride - 1) * width_ + node.first_pixel % stride - 1;
    node.canonical_pixel =
        (node.canonical_pixel / stride - 1) * width_ + node.canonical_pixel % stride - 1;
  }
  for (int child : order_) {
    const int parent = nodes_[child].parent;
    if (parent < 0) continue;
    int& main = nodes_[parent].main_child;
    if (main < 0) {
      main = child;
      continue;
    }
    const Node& c = nodes_[child];
    const Node& m = nodes_[main];
    if (c.area > m.area ||
        (c.area == m.area &&
         (c.level < m.level || (c.level == m.level && c.canonical_pixel < m.canonical_pixel)))) {
      main = child;
    }
  }
}

int ImageComponentTree::AncestorAtLevel(int node, int level) const {
  for (;;) {
    const int parent = nodes_[node].parent;
    if (parent < 0 || nodes_[parent].level > level) return node;
    node = parent;
  }
}

int ImageComponentTree::MainDescendantAtLevel(int node, int level) const {
  while (node >= 0 && nodes_[node].level > level) node = nodes_[node].main_child;
  return node;
}

int ImageComponentTree::MainDescendantArea(int node, int level) const {
  const int descendant = MainDescendantAtLevel(node, level);
  return descendant < 0 ? 0 : nodes_[descendant].area;
}

}  // namespace comic::frontend
