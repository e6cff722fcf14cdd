// Every app prints the one project version (io/core/version.h, from the top-level CMakeLists.txt's
// project(VERSION)) for --version, exits 0 and does no work.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/core/version.h"
#include "tests/test_support.h"

namespace {

TEST(AppVersion, EveryAppPrintsTheProjectVersion) {
  int apps = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(comic::test::SourceDir() + "/apps")) {
    if (entry.path().extension() != ".cc") continue;
    const std::string app = entry.path().stem().string();
    // Before a required argument and with options after it: --version wins, nothing runs.
    const auto result =
        comic::test::RunCommand(comic::test::AppPath(app) + " --version --bogus-after");
    EXPECT_EQ(result.exit_code, 0) << app << "\n" << result.output;
    EXPECT_EQ(result.output, app + " " + comic::Version() + "\n") << app;
    ++apps;
  }
  EXPECT_GE(apps, 7);
}

}  // namespace
