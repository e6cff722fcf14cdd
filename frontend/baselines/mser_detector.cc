#include "frontend/baselines/mser_detector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "frontend/grid_cell_key.h"
#include "io/core/error.h"

namespace comic::frontend {

void MserDetectorOptions::Check() const {
  COMIC_CHECK(delta >= 1 && delta <= 127, kInvalidArgument,
              "mser: delta must be in [1, 127] grey levels, got " << delta);
  COMIC_CHECK(min_area >= 1, kInvalidArgument, "mser: min_area must be >= 1, got " << min_area);
  COMIC_CHECK(max_area >= min_area, kInvalidArgument,
              "mser: max_area must be >= min_area, got " << max_area);
  COMIC_CHECK(max_variation > 0, kInvalidArgument, "mser: max_variation must be > 0");
  COMIC_CHECK(merge_radius >= 0, kInvalidArgument, "mser: merge_radius must be >= 0");
}

MserDetector::MserDetector(const MserDetectorOptions& options) : options_(options) {
  options_.Check();
}

namespace {

// A component of {I ≤ level} at a level where it changed (grew or merged): the nodes of the
// component tree.
struct Node {
  int level = 0;
  int64_t area = 0;
  int64_t sum_x = 0;
  int64_t sum_y = 0;
  int parent = -1;      // the node of the component containing this one at a higher level
  int main_child = -1;  // the largest component it grew from, -1 for a new component
};

class ComponentTree {
 public:
  // Builds the tree of the dark-extremal components of `gray` (4-connectivity).
  explicit ComponentTree(const cv::Mat& gray) {
    const int width = gray.cols;
    const int height = gray.rows;
    const int n = width * height;
    // Counting sort of the pixels by grey level.
    std::array<int, 257> start{};
    for (int y = 0; y < height; ++y) {
      const uint8_t* row = gray.ptr<uint8_t>(y);
      for (int x = 0; x < width; ++x) ++start[row[x] + 1];
    }
    for (int v = 0; v < 256; ++v) start[v + 1] += start[v];
    std::vector<int> order(n);
    {
      std::array<int, 256> next{};
      std::copy(start.begin(), start.begin() + 256, next.begin());
      for (int y = 0; y < height; ++y) {
        const uint8_t* row = gray.ptr<uint8_t>(y);
        for (int x = 0; x < width; ++x) order[next[row[x]]++] = y * width + x;
      }
    }
    parent_.assign(n, -1);
    size_.assign(n, 0);
    sum_x_.assign(n, 0);
    sum_y_.assign(n, 0);
    node_.assign(n, -1);
    std::vector<int> touched;
    std::vector<std::pair<int, int>> orphans;  // (node of an earlier level, a pixel of its root)
    for (int level = 0; level < 256; ++level) {
      touched.clear();
      orphans.clear();
      for (int k = start[level]; k < start[level + 1]; ++k) {
        const int p = order[k];
        const int px = p % width;
        const int py = p / width;
        parent_[p] = p;
        size_[p] = 1;
        sum_x_[p] = px;
        sum_y_[p] = py;
        touched.push_back(p);
        const int neighbours[4] = {px > 0 ? p - 1 : -1, px + 1 < width ? p + 1 : -1,
                                   py > 0 ? p - width : -1, py + 1 < height ? p + width : -1};
        for (int q : neighbours) {
          if (q < 0 || parent_[q] < 0) continue;
          int a = Find(p);
          int b = Find(q);
          if (a == b) continue;
          for (int root : {a, b}) {
            if (node_[root] >= 0) {
              orphans.emplace_back(node_[root], root);
              node_[root] = -1;
            }
          }
          if (size_[a] < size_[b]) std::swap(a, b);
          parent_[b] = a;
          size_[a] += size_[b];
          sum_x_[a] += sum_x_[b];
          sum_y_[a] += sum_y_[b];
        }
      }
      // Every component that changed at this level gets a node; the nodes it grew from become
      // its children.
      for (int t : touched) {
        const int root = Find(t);
        if (node_[root] >= 0) continue;
        Node node;
        node.level = level;
        node.area = size_[root];
        node.sum_x = sum_x_[root];
        node.sum_y = sum_y_[root];
        node_[root] = static_cast<int>(nodes_.size());
        nodes_.push_back(node);
      }
      for (const auto& [child, pixel] : orphans) {
        const int parent = node_[Find(pixel)];
        nodes_[child].parent = parent;
        Node& p = nodes_[parent];
        if (p.main_child < 0 || nodes_[p.main_child].area < nodes_[child].area) {
          p.main_child = child;
        }
      }
    }
  }

  const std::vector<Node>& nodes() const { return nodes_; }

 private:
  int Find(int p) {
    int root = p;
    while (parent_[root] != root) root = parent_[root];
    while (parent_[p] != root) {
      const int next = parent_[p];
      parent_[p] = root;
      p = next;
    }
    return root;
  }

  std::vector<int> parent_;
  std::vector<int64_t> size_;
  std::vector<int64_t> sum_x_;
  std::vector<int64_t> sum_y_;
  std::vector<int> node_;  // node of the component rooted here, -1 while it changes
  std::vector<Node> nodes_;
};

// Maximally stable regions of one polarity (dark regions of `gray`).
void DetectDarkRegions(const cv::Mat& gray, const MserDetectorOptions& options, Polarity polarity,
                       FeatureSet* features) {
  const ComponentTree tree(gray);
  const std::vector<Node>& nodes = tree.nodes();
  // Variation of every node: growth of its component over the next δ levels.
  std::vector<double> variation(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    int up = static_cast<int>(i);
    while (nodes[up].parent >= 0 &&
           nodes[nodes[up].parent].level <= nodes[i].level + options.delta) {
      up = nodes[up].parent;
    }
    variation[i] = static_cast<double>(nodes[up].area - nodes[i].area) / nodes[i].area;
  }
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Node& node = nodes[i];
    if (node.area < options.min_area || node.area > options.max_area) continue;
    if (variation[i] > options.max_variation) continue;
    if (node.parent < 0) continue;  // the whole image is not a region
    if (!(variation[i] < variation[node.parent])) continue;
    if (node.main_child >= 0 && !(variation[i] <= variation[node.main_child])) continue;
    Feature f;
    f.x = static_cast<float>(static_cast<double>(node.sum_x) / node.area);
    f.y = static_cast<float>(static_cast<double>(node.sum_y) / node.area);
    f.scale = static_cast<float>(std::sqrt(node.area / M_PI));
    f.response = static_cast<float>(1.0 / (1.0 + variation[i]));
    f.polarity = polarity;
    features->push_back(std::move(f));
  }
}

// Keeps, of features closer than `radius`, the strongest (input sorted strongest first).
FeatureSet SuppressNearDuplicates(const FeatureSet& sorted, double radius) {
  if (radius <= 0) return sorted;
  const double cell = radius;
  std::unordered_map<uint64_t, std::vector<int>> grid;
  auto key = [](int64_t cx, int64_t cy) { return GridCellKey(cx, cy); };
  FeatureSet kept;
  for (const Feature& f : sorted) {
    const int64_t cx = static_cast<int64_t>(std::floor(f.x / cell));
    const int64_t cy = static_cast<int64_t>(std::floor(f.y / cell));
    bool duplicate = false;
    for (int64_t dy = -1; dy <= 1 && !duplicate; ++dy) {
      for (int64_t dx = -1; dx <= 1 && !duplicate; ++dx) {
        const auto it = grid.find(key(cx + dx, cy + dy));
        if (it == grid.end()) continue;
        for (int index : it->second) {
          const double ddx = kept[index].x - f.x;
          const double ddy = kept[index].y - f.y;
          if (ddx * ddx + ddy * ddy < radius * radius) {
            duplicate = true;
            break;
          }
        }
      }
    }
    if (duplicate) continue;
    grid[key(cx, cy)].push_back(static_cast<int>(kept.size()));
    kept.push_back(f);
  }
  return kept;
}

}  // namespace

FeatureSet MserDetector::Detect(const cv::Mat& gray) const {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "mser: expected a non-empty 8-bit single-channel image");
  FeatureSet features;
  DetectDarkRegions(gray, options_, Polarity::kDark, &features);
  cv::Mat inverted;
  cv::bitwise_not(gray, inverted);
  DetectDarkRegions(inverted, options_, Polarity::kBright, &features);
  SortByResponse(&features);
  return SuppressNearDuplicates(features, options_.merge_radius);
}

}  // namespace comic::frontend
