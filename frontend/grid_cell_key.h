// The hash key of a 2-D grid cell (cx, cy), used by the grid-hashed neighbour searches of the
// detectors and the matcher. Cells left of or above the image are negative; the key packs the two
// 32-bit patterns in unsigned arithmetic, where a left shift of a negative value (undefined
// behaviour in C++17) cannot happen. The bits are those of the former signed formula
// (cx << 32) ^ (cy & 0xffffffff), so hash-map orders, and with them outputs, are unchanged.
#pragma once

#include <cstdint>

namespace comic::frontend {

inline uint64_t GridCellKey(int64_t cx, int64_t cy) {
  return (static_cast<uint64_t>(cx) << 32) ^ (static_cast<uint64_t>(cy) & 0xffffffffu);
}

}  // namespace comic::frontend
