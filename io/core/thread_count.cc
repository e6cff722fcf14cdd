#include "io/core/thread_count.h"

#include <algorithm>
#include <thread>

#include "io/core/error.h"

namespace comic::io {

int HardwareThreads() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

void CheckThreadCount(const std::string& flag, int threads) {
  const int hardware = HardwareThreads();
  COMIC_CHECK(threads >= 0 && threads <= hardware, kInvalidArgument,
              flag << " must be >= 0 and <= " << hardware << " (the hardware threads of this "
                   << "machine; 0 = all), got " << threads);
}

}  // namespace comic::io
