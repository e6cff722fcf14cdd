// GridCellKey: well-defined for negative cells (issue 19: the former signed `cx << 32` was
// undefined behaviour for cx < 0), the same bits as the former formula for non-negative cells,
// and distinct for the neighbouring cells a 3x3 grid search visits.
#include "frontend/grid_cell_key.h"

#include <gtest/gtest.h>

#include <set>

namespace comic::frontend {
namespace {

TEST(GridCellKey, NonNegativeCellsKeepTheFormerBits) {
  EXPECT_EQ(GridCellKey(0, 0), 0u);
  EXPECT_EQ(GridCellKey(1, 0), uint64_t{1} << 32);
  EXPECT_EQ(GridCellKey(3, 7), (uint64_t{3} << 32) | 7u);
  EXPECT_EQ(GridCellKey(123456, 654321), (uint64_t{123456} << 32) ^ uint64_t{654321});
}

TEST(GridCellKey, NegativeCellsAreTwosComplementPatterns) {
  EXPECT_EQ(GridCellKey(-1, -1), ~uint64_t{0});
  EXPECT_EQ(GridCellKey(-1, 0), uint64_t{0xffffffff} << 32);
  EXPECT_EQ(GridCellKey(0, -1), uint64_t{0xffffffff});
  EXPECT_EQ(GridCellKey(-2, 5), (uint64_t{0xfffffffe} << 32) | 5u);
}

TEST(GridCellKey, NeighbourhoodsAroundTheOriginAreDistinct) {
  std::set<uint64_t> keys;
  for (int64_t cy = -3; cy <= 3; ++cy) {
    for (int64_t cx = -3; cx <= 3; ++cx) keys.insert(GridCellKey(cx, cy));
  }
  EXPECT_EQ(keys.size(), 49u);
}

}  // namespace
}  // namespace comic::frontend
