// The apps' names for io/core/thread_count.h (HardwareThreads, CheckThreadCount), which the
// library's runs (sfm/run/) check their thread counts with too.
#pragma once

#include "io/core/thread_count.h"

namespace comic::apps {

using io::CheckThreadCount;
using io::HardwareThreads;

}  // namespace comic::apps
