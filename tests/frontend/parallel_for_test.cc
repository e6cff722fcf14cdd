#include "frontend/parallel_for.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
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

// Issue 29: `comic.detect(img, threads=10**6)` aborted the interpreter: the system refused a
// thread, and the threads already started were destroyed joinable while the exception unwound.
// Here a child process whose address space leaves room for a few thread stacks asks for 1000
// threads: every item must still run once, and the child must exit normally.
TEST(ParallelFor, ThreadsTheSystemRefusesAreNotAnAbort) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "an address-space limit starves AddressSanitizer's own allocator";
#endif
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    long pages = 0;
    std::FILE* statm = std::fopen("/proc/self/statm", "r");
    if (statm == nullptr || std::fscanf(statm, "%ld", &pages) != 1) ::_exit(2);
    std::fclose(statm);
    const rlim_t limit = static_cast<rlim_t>(pages) * ::sysconf(_SC_PAGESIZE) + (64 << 20);
    const struct rlimit address_space = {limit, limit};
    if (::setrlimit(RLIMIT_AS, &address_space) != 0) ::_exit(2);
    const int items = 1000;
    std::vector<std::atomic<int>> calls(items);
    ParallelFor(items, items, [&](int item, int) { calls[item].fetch_add(1); });
    for (int i = 0; i < items; ++i) {
      if (calls[i].load() != 1) ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace comic::frontend
