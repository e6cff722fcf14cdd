#include "frontend/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace comic::frontend {
namespace {

TEST(ParallelFor, ResolvesThreadCountWithinBounds) {
  EXPECT_EQ(ResolveNumThreads(1, 10), 1);
  EXPECT_EQ(ResolveNumThreads(4, 10), 4);
  EXPECT_EQ(ResolveNumThreads(4, 2), 2);  // never more workers than items
  EXPECT_GE(ResolveNumThreads(0, 1000), 1);
  EXPECT_EQ(ResolveNumThreads(3, 0), 1);
}

TEST(ParallelFor, CallsEveryItemExactlyOnceWithValidWorkers) {
  for (int threads : {1, 2, 4, 0}) {
    const int items = 1000;
    std::vector<std::atomic<int>> calls(items);
    const int workers = ResolveNumThreads(threads, items);
    std::atomic<bool> bad_worker{false};
    ParallelFor(items, threads, [&](int item, int worker) {
      calls[item].fetch_add(1);
      if (worker < 0 || worker >= workers) bad_worker = true;
    });
    for (int i = 0; i < items; ++i) EXPECT_EQ(calls[i].load(), 1) << "item " << i;
    EXPECT_FALSE(bad_worker) << threads << " threads";
  }
}

TEST(ParallelFor, NoItemsCallsNothing) {
  bool called = false;
  ParallelFor(0, 4, [&](int, int) { called = true; });
  EXPECT_FALSE(called);
}

TEST(ParallelFor, RethrowsTheLowestFailingItemWhateverTheThreadCount) {
  for (int threads : {1, 2, 4}) {
    try {
      ParallelFor(200, threads, [](int item, int) {
        if (item == 37 || item == 150) throw std::runtime_error("item " + std::to_string(item));
      });
      FAIL() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "item 37") << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace comic::frontend
