#include "apps/common/thread_count.h"

#include "frontend/parallel_for.h"

namespace comic::apps {

// The library's bound (frontend/parallel_for.h), which the Python module holds to as well.
int HardwareThreads() { return frontend::HardwareThreads(); }

void CheckThreadCount(const std::string& flag, int threads) {
  frontend::CheckThreadCount(flag, threads);
}

}  // namespace comic::apps
