// ProgressLine: the text of a progress update, one line per frame off a terminal, one line
// rewritten with '\r' on a terminal, nothing when quiet.
#include "apps/common/progress_line.h"

#include <gtest/gtest.h>

#include <sstream>

namespace {

using comic::apps::ProgressLine;

TEST(ProgressLine, FormatsElapsedTimeAndTheEstimateOfWhatRemains) {
  // 4 of 10 frames in 2 s: 0.5 s a frame, 6 frames left -> 3 s.
  EXPECT_EQ(ProgressLine::Format("[harris] tracking", 4, 10, 2.0),
            "[harris] tracking: frame 4/10, 2.0 s elapsed, about 3.0 s left");
  EXPECT_EQ(ProgressLine::Format("x", 10, 10, 5.25), "x: frame 10/10, 5.2 s elapsed");
  EXPECT_EQ(ProgressLine::Format("x", 3, 0, 1.0), "x: frame 3, 1.0 s elapsed");
}

TEST(ProgressLine, OneLinePerFrameOffATerminal) {
  std::ostringstream out;
  double now = 0.0;
  ProgressLine progress("p", false, &out, /*terminal=*/0, [&] { return now; });
  auto callback = progress.Callback();
  for (size_t i = 1; i <= 3; ++i) {
    now = static_cast<double>(i);
    callback(i, 3);
  }
  EXPECT_EQ(out.str(),
            "p: frame 1/3, 1.0 s elapsed, about 2.0 s left\n"
            "p: frame 2/3, 2.0 s elapsed, about 1.0 s left\n"
            "p: frame 3/3, 3.0 s elapsed\n");
}

TEST(ProgressLine, RewritesOneLineOnATerminalAndEndsItWhenDone) {
  std::ostringstream out;
  ProgressLine progress("p", false, &out, /*terminal=*/1, [] { return 1.0; });
  progress.Update(1, 2);
  progress.Update(2, 2);
  EXPECT_EQ(out.str(),
            "\rp: frame 1/2, 1.0 s elapsed, about 1.0 s left\33[K"
            "\rp: frame 2/2, 1.0 s elapsed\33[K\n");
}

TEST(ProgressLine, QuietPrintsNothing) {
  std::ostringstream out;
  ProgressLine progress("p", true, &out, 0, [] { return 1.0; });
  progress.Update(1, 2);
  progress.Update(2, 2);
  EXPECT_TRUE(out.str().empty());
}

}  // namespace
