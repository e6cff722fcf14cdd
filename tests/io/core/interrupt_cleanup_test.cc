#include "io/core/interrupt_cleanup.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

TEST(InterruptCleanup, RegistersForTheLifetimeOfTheGuard) {
  const int before = NumRegisteredTempPaths();
  {
    const ScopedTempPath a("/tmp/a");
    const ScopedTempPath b("/tmp/a");  // the same path twice is counted twice
    EXPECT_EQ(NumRegisteredTempPaths(), before + 2);
  }
  EXPECT_EQ(NumRegisteredTempPaths(), before);
}

TEST(InterruptCleanup, RemovesRegisteredFilesFoldersAndJournals) {
  test::ScopedTempDir dir;
  WriteFileAtomically(dir.File("x.tmp.db"), "x");
  WriteFileAtomically(dir.File("x.tmp.db-journal"), "j");
  EnsureWritableDirectory(dir.File("staging/sub"));
  WriteFileAtomically(dir.File("staging/sub/f"), "f");
  WriteFileAtomically(dir.File("kept"), "k");
  {
    const ScopedTempPath file(dir.File("x.tmp.db"));
    const ScopedTempPath folder(dir.File("staging"));
    RemoveRegisteredTempPaths();
  }
  EXPECT_FALSE(PathExists(dir.File("x.tmp.db")));
  EXPECT_FALSE(PathExists(dir.File("x.tmp.db-journal")));
  EXPECT_FALSE(PathExists(dir.File("staging")));
  EXPECT_TRUE(PathExists(dir.File("kept")));
}

// The real thing in a child process: SIGTERM while a temp file is registered removes it, and the
// process ends by that signal.
TEST(InterruptCleanup, SigtermRemovesTheTempFilesAndEndsTheProcess) {
  test::ScopedTempDir dir;
  const std::string temp = dir.File(".out.tmp123.json");
  const std::string ready = dir.File("ready");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    InstallInterruptCleanup();
    const ScopedTempPath registered(temp);
    WriteFileAtomically(temp, "half");
    WriteFileAtomically(ready, "1");
    for (int i = 0; i < 1000; ++i) ::usleep(10000);  // 10 s at most
    ::_exit(0);
  }
  for (int i = 0; i < 500 && !PathExists(ready); ++i) ::usleep(10000);
  ASSERT_TRUE(PathExists(temp));
  ::kill(child, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status));
  if (WIFSIGNALED(status)) {
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
  }
  EXPECT_FALSE(PathExists(temp));
}

}  // namespace
}  // namespace comic::io
