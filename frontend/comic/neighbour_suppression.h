// Greedy suppression of neighbours: candidates in a given order (strongest first) are kept unless
// a kept one of the same group lies within `radius` (distance <= radius: seeds on the pixel grid
// exactly one radius apart are neighbours). The kept candidates are hashed on a grid of cells at
// least `radius` wide, so each candidate is compared with those in its 3 x 3 cells only.
//
//   corners = SuppressNeighbours(std::move(corners), 2.0,
//                                [](const Corner& c) { return c.position; });
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <unordered_map>
#include <utility>
#include <vector>

#include "frontend/grid_cell_key.h"

namespace comic::frontend {

// `items` without those within `radius` of an earlier kept item for which same_group(kept, item)
// holds, in their order. radius <= 0 keeps every item. `position(item)` gives a cv::Point2f.
template <class T, class Position, class SameGroup>
std::vector<T> SuppressNeighbours(std::vector<T> items, double radius, Position position,
                                  SameGroup same_group) {
  if (radius <= 0) return items;
  // At least a pixel wide: a tiny radius would make cell indices too large for int64_t.
  const double cell = std::max(radius, 1.0);
  std::unordered_map<uint64_t, std::vector<int>> grid;
  std::vector<T> kept;
  kept.reserve(items.size());
  for (T& item : items) {
    const cv::Point2f p = position(item);
    const int64_t cx = static_cast<int64_t>(std::floor(p.x / cell));
    const int64_t cy = static_cast<int64_t>(std::floor(p.y / cell));
    bool suppressed = false;
    for (int64_t dy = -1; dy <= 1 && !suppressed; ++dy) {
      for (int64_t dx = -1; dx <= 1 && !suppressed; ++dx) {
        const auto it = grid.find(GridCellKey(cx + dx, cy + dy));
        if (it == grid.end()) continue;
        for (int index : it->second) {
          const cv::Point2f q = position(kept[index]);
          if (std::hypot(p.x - q.x, p.y - q.y) <= radius && same_group(kept[index], item)) {
            suppressed = true;
            break;
          }
        }
      }
    }
    if (suppressed) continue;
    grid[GridCellKey(cx, cy)].push_back(static_cast<int>(kept.size()));
    kept.push_back(std::move(item));
  }
  return kept;
}

// Every pair may suppress each other.
template <class T, class Position>
std::vector<T> SuppressNeighbours(std::vector<T> items, double radius, Position position) {
  return SuppressNeighbours(std::move(items), radius, position,
                            [](const T&, const T&) { return true; });
}

}  // namespace comic::frontend
