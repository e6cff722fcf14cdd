// A small deterministic parallel loop over independent work items, used by the CoMIC detector to
// spread blocks and corners over threads. Determinism comes from the callers' contract: an item's
// result may depend only on the item (never on which worker ran it or in which order), and results
// are stored per item index and merged afterwards in index order. No global state is touched
// (no OpenCV thread pool, no cv::setNumThreads).
//
//   std::vector<Result> results(num_blocks);
//   ParallelFor(num_blocks, num_threads, [&](int block, int worker) {
//     results[block] = Process(block, &scratch[worker]);  // scratch: one per worker, reused
//   });
#pragma once

#include <functional>

namespace comic::frontend {

// Number of workers ParallelFor will use for `requested` threads (0 = all hardware threads)
// and `num_items` items: at least 1, at most num_items.
int ResolveNumThreads(int requested, int num_items);

// Calls body(item, worker) exactly once for every item in [0, num_items), on
// ResolveNumThreads(num_threads, num_items) workers (worker in [0, that number)). Items are
// handed out dynamically, so the order of calls is unspecified. If bodies throw, the exception of
// the lowest-numbered failing item is rethrown after all workers have stopped (later items may be
// skipped), so the error reported does not depend on the thread count either.
void ParallelFor(int num_items, int num_threads, const std::function<void(int, int)>& body);

}  // namespace comic::frontend
