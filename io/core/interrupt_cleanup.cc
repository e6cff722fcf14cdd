#include "io/core/interrupt_cleanup.h"

#include <pthread.h>
#include <signal.h>

#include <filesystem>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

namespace comic::io {
namespace {

namespace fs = std::filesystem;

struct TempPathRegistry {
  std::mutex mutex;
  std::multiset<std::string> paths;
  bool installed = false;
};

TempPathRegistry& Registry() {
  static TempPathRegistry registry;  // see the header: a signal belongs to the process
  return registry;
}

void RemoveAllLocked(TempPathRegistry& registry) {
  for (const std::string& path : registry.paths) {
    std::error_code ec;
    // A writer may add a file while the folder is being removed: try again a few times.
    for (int attempt = 0; attempt < 3 && fs::exists(fs::symlink_status(path, ec)); ++attempt) {
      fs::remove_all(path, ec);
    }
    fs::remove(path + "-journal", ec);
  }
}

sigset_t InterruptSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  return signals;
}

// A thread that waits for SIGINT or SIGTERM, removes every registered temp path and dies of the
// signal as the process would have.
void StartInterruptWatcher(const sigset_t& signals) {
  std::thread([signals] {
    int signal_number = 0;
    if (sigwait(&signals, &signal_number) != 0) return;
    TempPathRegistry& registry = Registry();
    // Holding the lock until the end: no writer registers (or renames into place) meanwhile.
    registry.mutex.lock();
    RemoveAllLocked(registry);
    ::signal(signal_number, SIG_DFL);
    pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
    ::raise(signal_number);
  }).detach();
}

}  // namespace

void InstallInterruptCleanup() {
  TempPathRegistry& registry = Registry();
  {
    const std::lock_guard<std::mutex> lock(registry.mutex);
    if (registry.installed) return;
    registry.installed = true;
  }
  const sigset_t signals = InterruptSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  // Out of memory or threads, the system refuses the watcher (std::system_error, before RunMain
  // could turn it into our line): the run goes on without the cleanup, interruptible as usual,
  // and meets the shortage again where its one line says what to do.
  try {
    StartInterruptWatcher(signals);
  } catch (const std::system_error&) {
    pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
  }
}

ScopedTempPath::ScopedTempPath(std::string path) : path_(std::move(path)) {
  TempPathRegistry& registry = Registry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  registry.paths.insert(path_);
}

ScopedTempPath::~ScopedTempPath() {
  TempPathRegistry& registry = Registry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  const auto it = registry.paths.find(path_);
  if (it != registry.paths.end()) registry.paths.erase(it);
}

void RemoveRegisteredTempPaths() {
  TempPathRegistry& registry = Registry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  RemoveAllLocked(registry);
}

int NumRegisteredTempPaths() {
  TempPathRegistry& registry = Registry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  return static_cast<int>(registry.paths.size());
}

}  // namespace comic::io
