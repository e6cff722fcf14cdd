// Thread counts of options such as --threads, bounded: 0 means every hardware thread, and more than
// the machine has is refused (issue 19: --threads 100000 was accepted by six apps). Outputs do not
// depend on the value.
#pragma once

#include <string>

namespace comic::io {

// The machine's hardware threads (at least 1).
int HardwareThreads();

// Throws comic::Error(kInvalidArgument) naming `flag` unless 0 <= threads <= HardwareThreads().
void CheckThreadCount(const std::string& flag, int threads);

}  // namespace comic::io
