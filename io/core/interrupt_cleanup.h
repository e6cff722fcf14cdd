// Temporary outputs are removed when the run is interrupted (SIGINT, SIGTERM), so that Ctrl-C
// or a killed job never leaves a hidden temp file, a staging folder or an SQLite -journal behind
// (issue 19). Writers register their temporary paths for as long as they exist (ScopedTempPath);
// the apps' main installs the handler once.
//
// The registry is process-wide by necessity (a signal belongs to the process); it is the one
// piece of shared state in io/, guarded by a mutex, and holds nothing but paths.
#pragma once

#include <string>

namespace comic::io {

// Blocks SIGINT and SIGTERM in the calling thread, and so in every thread it starts later, and
// starts a thread that waits for them: on a signal it removes every registered path (files, or
// folders with their contents) and ends the process with that signal's default action (the shell
// sees 130 / 143). Call at the start of main, before any other thread exists. Idempotent.
// Child processes must unblock the signals (see sfm/colmap/colmap_runner.cc).
void InstallInterruptCleanup();

// Registers `path` (and `path`-journal, for SQLite) for removal on interruption while the object
// lives. The destructor only unregisters: removing or renaming the path is the owner's job.
class ScopedTempPath {
 public:
  explicit ScopedTempPath(std::string path);
  ~ScopedTempPath();
  ScopedTempPath(const ScopedTempPath&) = delete;
  ScopedTempPath& operator=(const ScopedTempPath&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Removes every registered path now (what the signal thread does); for tests.
void RemoveRegisteredTempPaths();

// Number of paths registered now; for tests.
int NumRegisteredTempPaths();

}  // namespace comic::io
