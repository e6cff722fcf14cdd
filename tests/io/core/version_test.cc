// comic::Version() is the VERSION of the top-level CMakeLists.txt's project(), not a copy of it.
#include "io/core/version.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "tests/test_support.h"

namespace {

TEST(Version, IsTheProjectVersionOfTheTopLevelCMakeLists) {
  std::ifstream in(comic::test::SourceDir() + "/CMakeLists.txt");
  ASSERT_TRUE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  std::smatch match;
  const std::string cmake = text.str();
  ASSERT_TRUE(
      std::regex_search(cmake, match, std::regex(R"(project\(\s*\w+\s+VERSION\s+([0-9.]+))")));
  EXPECT_EQ(comic::Version(), match[1].str());
}

TEST(Version, IsMajorMinorPatch) {
  EXPECT_TRUE(std::regex_match(comic::Version(), std::regex(R"([0-9]+\.[0-9]+\.[0-9]+)")))
      << comic::Version();
}

}  // namespace
