// Shared helpers for the tests: where the bundled example and the optional evaluation data live,
// temporary folders, and running the built apps.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace comic::test {

inline std::string SourceDir() { return COMIC_SOURCE_DIR; }

// The bundled example sequence (always present in a checkout).
inline std::string ExampleDir() { return SourceDir() + "/examples/data/kitti06_000-011"; }

// ../shared/data beside the repository, or "" where it is missing (a plain clone) or
// COMIC_TEST_WITHOUT_SHARED_DATA is set (the sanitizer run: the evaluation-data tests run whole
// reconstructions that the Release run already covers, at many times the cost under ASan).
inline std::string SharedDataDir() {
  const char* without = std::getenv("COMIC_TEST_WITHOUT_SHARED_DATA");
  if (without != nullptr && std::string(without) == "1") return "";
  const std::string dir = SourceDir() + "/../shared/data";
  std::error_code ec;
  return std::filesystem::is_directory(dir, ec) ? dir : "";
}

// Skips the current test cleanly when ../shared/data is absent.
#define COMIC_REQUIRE_SHARED_DATA()                                               \
  do {                                                                            \
    if (::comic::test::SharedDataDir().empty()) {                                 \
      GTEST_SKIP() << "../shared/data not present; evaluation-data test skipped"; \
    }                                                                             \
  } while (false)

// A fresh temporary folder, removed with everything in it when the object goes out of scope.
class ScopedTempDir {
 public:
  ScopedTempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "comic_test_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~ScopedTempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string File(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

// Path of a built app (apps/<name>.cc -> build/bin/<name>).
inline std::string AppPath(const std::string& name) {
  return std::string(COMIC_BINARY_DIR) + "/bin/" + name;
}

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr interleaved
};

// Runs a shell command, capturing stdout and stderr; exit_code is the process's exit status
// (or 128 + signal number if it was killed by a signal, so a crash never looks like success).
inline CommandResult RunCommand(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.output.append(buffer.data(), n);
  }
  const int status = ::pclose(pipe);
  if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.exit_code = 128 + WTERMSIG(status);
  }
  return result;
}

// Counts the lines of `text` (a trailing line without newline counts).
inline int CountLines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  if (!text.empty() && text.back() != '\n') ++lines;
  return lines;
}

}  // namespace comic::test
