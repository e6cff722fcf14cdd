// SplitList / ParseNumberList: the comma-separated values of --detectors, --sweep, --counts...
#include "apps/common/list_flags.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "io/core/error.h"

namespace {

using comic::apps::ParseNumberList;
using comic::apps::SplitList;

std::string MessageOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const comic::Error& e) {
    EXPECT_EQ(e.kind(), comic::ErrorKind::kInvalidArgument);
    return e.what();
  }
  return "(no error)";
}

TEST(SplitList, SplitsAtCommas) {
  EXPECT_EQ(SplitList("comic,harris,fast", "detectors"),
            (std::vector<std::string>{"comic", "harris", "fast"}));
  EXPECT_EQ(SplitList("one", "detectors"), (std::vector<std::string>{"one"}));
}

TEST(SplitList, RefusesEmptyListsAndEntriesNamingTheFlag) {
  EXPECT_EQ(MessageOf([] { SplitList("", "detectors"); }), "--detectors: the list is empty");
  EXPECT_EQ(MessageOf([] { SplitList("a,,b", "methods"); }), "--methods: empty entry in 'a,,b'");
  EXPECT_EQ(MessageOf([] { SplitList("a,", "methods"); }), "--methods: empty entry in 'a,'");
  EXPECT_EQ(MessageOf([] { SplitList(",a", "methods"); }), "--methods: empty entry in ',a'");
}

TEST(ParseNumberList, ParsesNumbersAndInfinity) {
  const std::vector<double> values = ParseNumberList("100,2.5,-1,inf", "sweep");
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[0], 100.0);
  EXPECT_EQ(values[1], 2.5);
  EXPECT_EQ(values[2], -1.0);
  EXPECT_TRUE(std::isinf(values[3]) && values[3] > 0);
}

TEST(ParseNumberList, RefusesPartialNumbers) {
  EXPECT_EQ(MessageOf([] { ParseNumberList("100,x", "sweep"); }),
            "--sweep: expected a number or inf, got 'x'");
  EXPECT_EQ(MessageOf([] { ParseNumberList("10px", "counts"); }),
            "--counts: expected a number or inf, got '10px'");
}

}  // namespace
