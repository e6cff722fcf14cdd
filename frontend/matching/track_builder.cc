#include "frontend/matching/track_builder.h"

#include <algorithm>
#include <numeric>
#include <tuple>

#include "io/core/error.h"

namespace comic::frontend {

const char* TrackConflictRuleName(TrackConflictRule rule) {
  switch (rule) {
    case TrackConflictRule::kDrop:
      return "drop";
    case TrackConflictRule::kGreedy:
      return "greedy";
    case TrackConflictRule::kGreedyByCost:
      return "greedy-cost";
  }
  return "?";
}

TrackConflictRule ParseTrackConflictRule(const std::string& name) {
  for (TrackConflictRule rule :
       {TrackConflictRule::kDrop, TrackConflictRule::kGreedy, TrackConflictRule::kGreedyByCost}) {
    if (name == TrackConflictRuleName(rule)) return rule;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "unknown track conflict rule '" + name + "' (valid: drop, greedy, greedy-cost)");
}

namespace {

// Union-find over the nodes 0..n-1, union by size with path halving.
class DisjointSets {
 public:
  explicit DisjointSets(size_t n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int Find(int x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  // Joins the sets of roots a and b; returns the new root.
  int Unite(int a, int b) {
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return a;
  }

 private:
  std::vector<int> parent_;
  std::vector<int> size_;
};

// A match located in the node numbering, with the key kGreedy merges by.
struct NodeMatch {
  int gap;
  float cost;
  int frame1;
  int index1;
  int node1;
  int node2;
};

// (frame, feature) numbered as one node each: node = first_node[frame] + feature.
struct NodeNumbering {
  std::vector<int> first_node;     // num_frames + 1 entries
  std::vector<int> frame_of_node;  // one per node
  int NumNodes() const { return first_node.back(); }
};

NodeNumbering NumberNodes(const std::vector<FeatureSet>& features) {
  const int num_frames = static_cast<int>(features.size());
  NodeNumbering numbering;
  numbering.first_node.assign(num_frames + 1, 0);
  std::vector<int>& first_node = numbering.first_node;
  for (int f = 0; f < num_frames; ++f) {
    first_node[f + 1] = first_node[f] + static_cast<int>(features[f].size());
  }
  numbering.frame_of_node.resize(first_node[num_frames]);
  for (int f = 0; f < num_frames; ++f) {
    std::fill(numbering.frame_of_node.begin() + first_node[f],
              numbering.frame_of_node.begin() + first_node[f + 1], f);
  }
  return numbering;
}

// Every match as a NodeMatch; throws on a pair out of order or a match that is not one-to-one.
std::vector<NodeMatch> CollectMatches(const std::vector<FeatureSet>& features,
                                      const std::vector<FramePairMatches>& pairs,
                                      const std::vector<int>& first_node) {
  const int num_frames = static_cast<int>(features.size());
  std::vector<NodeMatch> matches;
  std::vector<char> used1, used2;
  for (const FramePairMatches& pair : pairs) {
    COMIC_CHECK(
        pair.frame1 >= 0 && pair.frame1 < pair.frame2 && pair.frame2 < num_frames, kInvalidArgument,
        "track building: frame pair (" << pair.frame1 << ", " << pair.frame2
                                       << ") is not increasing within " << num_frames << " frames");
    const int n1 = static_cast<int>(features[pair.frame1].size());
    const int n2 = static_cast<int>(features[pair.frame2].size());
    used1.assign(n1, 0);
    used2.assign(n2, 0);
    for (const PatchMatch& m : pair.matches) {
      COMIC_CHECK(m.index1 >= 0 && m.index1 < n1 && m.index2 >= 0 && m.index2 < n2,
                  kInvalidArgument,
                  "track building: match index out of range in frame pair (" << pair.frame1 << ", "
                                                                             << pair.frame2 << ")");
      COMIC_CHECK(!used1[m.index1] && !used2[m.index2], kInvalidArgument,
                  "track building: a feature is matched twice in frame pair ("
                      << pair.frame1 << ", " << pair.frame2 << ")");
      used1[m.index1] = used2[m.index2] = 1;
      matches.push_back({pair.Gap(), m.cost, pair.frame1, m.index1,
                         first_node[pair.frame1] + m.index1, first_node[pair.frame2] + m.index2});
    }
  }
  return matches;
}

// kGreedy, kGreedyByCost: joins along the matches in a fixed order, refusing a match whose two
// components share a frame. Returns the number refused.
int UniteGreedily(std::vector<NodeMatch>& matches, TrackConflictRule rule,
                  const std::vector<int>& frame_of_node, DisjointSets& sets) {
  // (gap, cost, frame1, index1) identifies a match (matching is one-to-one per pair), so the
  // order is total and the result independent of the input order.
  // kGreedyByCost: (cost, frame1, index1, gap), equally total.
  const bool by_cost = rule == TrackConflictRule::kGreedyByCost;
  std::sort(matches.begin(), matches.end(), [by_cost](const NodeMatch& x, const NodeMatch& y) {
    if (by_cost) {
      return std::tie(x.cost, x.frame1, x.index1, x.gap) <
             std::tie(y.cost, y.frame1, y.index1, y.gap);
    }
    return std::tie(x.gap, x.cost, x.frame1, x.index1) <
           std::tie(y.gap, y.cost, y.frame1, y.index1);
  });
  // Frames of each root's component, sorted; empty for a single node (its own frame).
  std::vector<std::vector<int>> frames_of_root(frame_of_node.size());
  auto frames_of = [&](int root) {
    return frames_of_root[root].empty() ? std::vector<int>{frame_of_node[root]}
                                        : frames_of_root[root];
  };
  int refused = 0;
  for (const NodeMatch& m : matches) {
    const int a = sets.Find(m.node1), b = sets.Find(m.node2);
    if (a == b) continue;
    const std::vector<int> frames_a = frames_of(a), frames_b = frames_of(b);
    std::vector<int> merged;
    merged.reserve(frames_a.size() + frames_b.size());
    std::merge(frames_a.begin(), frames_a.end(), frames_b.begin(), frames_b.end(),
               std::back_inserter(merged));
    if (std::adjacent_find(merged.begin(), merged.end()) != merged.end()) {
      ++refused;
      continue;
    }
    frames_of_root[a].clear();
    frames_of_root[b].clear();
    frames_of_root[sets.Unite(a, b)] = std::move(merged);
  }
  return refused;
}

// Components of two or more nodes, in node order: observations come out by increasing frame, and
// components by their first (frame, feature).
std::vector<Track> Components(const NodeNumbering& numbering, DisjointSets& sets) {
  const int num_nodes = numbering.NumNodes();
  std::vector<int> root_of_node(num_nodes), component_size(num_nodes, 0);
  for (int node = 0; node < num_nodes; ++node) {
    root_of_node[node] = sets.Find(node);
    ++component_size[root_of_node[node]];
  }
  std::vector<int> track_of_root(num_nodes, -1);
  std::vector<Track> components;
  for (int node = 0; node < num_nodes; ++node) {
    const int root = root_of_node[node];
    if (component_size[root] < 2) continue;
    if (track_of_root[root] < 0) {
      track_of_root[root] = static_cast<int>(components.size());
      components.emplace_back();
    }
    const int frame = numbering.frame_of_node[node];
    components[track_of_root[root]].observations.push_back(
        {frame, node - numbering.first_node[frame]});
  }
  return components;
}

}  // namespace

std::vector<Track> BuildTracks(const std::vector<FeatureSet>& features,
                               const std::vector<FramePairMatches>& pairs, TrackConflictRule rule,
                               TrackBuildSummary* summary) {
  const NodeNumbering numbering = NumberNodes(features);
  std::vector<NodeMatch> matches = CollectMatches(features, pairs, numbering.first_node);
  TrackBuildSummary local;
  local.num_matches = static_cast<int>(matches.size());

  DisjointSets sets(numbering.NumNodes());
  if (rule == TrackConflictRule::kDrop) {
    for (const NodeMatch& m : matches) {
      const int a = sets.Find(m.node1), b = sets.Find(m.node2);
      if (a != b) sets.Unite(a, b);
    }
  } else {
    local.num_refused_matches = UniteGreedily(matches, rule, numbering.frame_of_node, sets);
  }

  std::vector<Track> tracks;
  for (Track& component : Components(numbering, sets)) {
    const auto& obs = component.observations;
    const bool repeats_a_frame =
        std::adjacent_find(obs.begin(), obs.end(), [](const auto& x, const auto& y) {
          return x.frame == y.frame;
        }) != obs.end();
    if (repeats_a_frame) {  // only possible with kDrop
      ++local.num_conflicting_components;
      local.num_dropped_features += static_cast<int>(component.Length());
      continue;
    }
    tracks.push_back(std::move(component));
  }
  if (summary) *summary = local;
  return tracks;
}

}  // namespace comic::frontend
