#include "frontend/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace comic::frontend {

int ResolveNumThreads(int requested, int num_items) {
  int threads = requested;
  if (threads <= 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(threads, 1);
  return std::max(1, std::min(threads, num_items));
}

void ParallelFor(int num_items, int num_threads, const std::function<void(int, int)>& body) {
  if (num_items <= 0) return;
  const int workers = ResolveNumThreads(num_threads, num_items);
  if (workers == 1) {
    for (int item = 0; item < num_items; ++item) body(item, 0);
    return;
  }
  std::atomic<int> next_item{0};
  std::mutex error_mutex;
  int failed_item = num_items;  // lowest failing item so far; guarded by error_mutex
  std::exception_ptr error;
  auto run = [&](int worker) {
    for (;;) {
      const int item = next_item.fetch_add(1);
      if (item >= num_items) return;
      {
        // Items above a known failure need not run: their errors could never be reported.
        std::lock_guard<std::mutex> lock(error_mutex);
        if (item > failed_item) return;
      }
      try {
        body(item, worker);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (item < failed_item) {
          failed_item = item;
          error = std::current_exception();
        }
      }
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(workers - 1);
  for (int worker = 1; worker < workers; ++worker) {
    // A thread the system refuses (std::system_error: too many threads) is not an abort: the
    // workers already started, and this one, take every item (issue 29: a joinable thread
    // destroyed while the exception unwound called std::terminate).
    try {
      threads.emplace_back(run, worker);
    } catch (const std::system_error&) {
      break;
    }
  }
  run(0);
  for (std::thread& thread : threads) thread.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace comic::frontend
