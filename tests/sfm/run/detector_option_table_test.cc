// DetectorOptionTable: every entry is a distinct flag and keyword with a meaning, its default is
// the default of every search that reads it, and it sets the search's field its name says.
#include "sfm/run/detector_option_table.h"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace comic::sfm {
namespace {

// The entry's field in `options` set to a value no default holds (true for a switch).
void SetOddValue(const DetectorOption& entry, DetectRunOptions& options) {
  std::visit(
      [&](auto field) {
        auto& value = field(options);
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, bool>) {
          value = !value;
        } else {
          value = static_cast<T>(value + 3);
        }
      },
      entry.field);
}

TEST(DetectorOptionTable, EveryEntryHasAFlagAKeywordAndAMeaning) {
  std::set<std::string> flags;
  std::set<std::string> keywords;
  for (const DetectorOption& entry : DetectorOptionTable()) {
    EXPECT_TRUE(std::regex_match(entry.flag, std::regex("[a-z][a-z0-9-]*"))) << entry.flag;
    EXPECT_TRUE(flags.insert(entry.flag).second) << "two entries for --" << entry.flag;
    EXPECT_TRUE(keywords.insert(entry.keyword).second) << "two entries for " << entry.keyword;
    std::string expected_keyword = entry.flag;
    for (char& c : expected_keyword) c = c == '-' ? '_' : c;
    EXPECT_EQ(entry.keyword, expected_keyword);
    EXPECT_FALSE(entry.help.empty()) << entry.flag;
    EXPECT_EQ(entry.metavar.empty(),
              std::holds_alternative<bool& (*)(DetectRunOptions&)>(entry.field))
        << entry.flag;
    EXPECT_TRUE(entry.AppliesTo("comic") || entry.AppliesTo("comic-paper")) << entry.flag;
    EXPECT_FALSE(entry.AppliesTo("harris")) << entry.flag;
  }
  EXPECT_EQ(flags.size(), 18u);
}

// Every field of each search's options, written out a second time on purpose: the table, the
// mapping (detect_run.cc) and this list would have to be wrong the same way for a flag to set
// another field. Compared as doubles: every field is a bool, an int or a double.
std::vector<double> Fields(const frontend::ComicDirectDetectorOptions& c) {
  return {c.scale,
          static_cast<double>(c.delta),
          static_cast<double>(c.half_length),
          c.min_cornerness,
          c.max_arm_rms,
          static_cast<double>(c.level_radius),
          static_cast<double>(c.bridge_levels),
          c.link_radius,
          static_cast<double>(c.level_step),
          static_cast<double>(c.max_level_gap),
          static_cast<double>(c.min_run_levels),
          c.consensus_fraction,
          c.presmoothing_sigma,
          c.merge_radius,
          c.min_stability,
          static_cast<double>(c.num_threads)};
}

std::vector<double> Fields(const frontend::ComicDetectorOptions& c) {
  return {c.scale,
          static_cast<double>(c.block_size),
          static_cast<double>(c.delta),
          static_cast<double>(c.half_length),
          static_cast<double>(c.max_iterations),
          c.convergence_tolerance,
          c.stop_tolerance,
          c.merge_radius,
          c.min_stability,
          static_cast<double>(c.num_threads),
          c.min_cornerness,
          static_cast<double>(c.coarse_initialisation),
          static_cast<double>(c.seed_neighbouring_corners),
          static_cast<double>(c.skip_duplicate_paths)};
}

// The searches' options made from a default DetectRunOptions are the searches' own defaults
// (the thread count aside: the run's default is every core): the table's defaults, its fields'
// initialisers, are the options structs'.
TEST(DetectorOptionTable, DefaultsAreTheSearchesDefaults) {
  DetectRunOptions run;
  run.threads = frontend::ComicDirectDetectorOptions().num_threads;
  const frontend::DetectorOptions made = run.ToDetectorOptions();
  EXPECT_EQ(Fields(made.comic), Fields(frontend::ComicDirectDetectorOptions()));
  EXPECT_EQ(Fields(made.comic_paper), Fields(frontend::ComicDetectorOptions()));
}

// Changing an entry changes the options of the searches it names, and only theirs: an entry that
// reached no search, or one it does not name, would be a flag that does nothing.
TEST(DetectorOptionTable, EachEntryReachesTheSearchesItNames) {
  const frontend::DetectorOptions defaults = DetectRunOptions().ToDetectorOptions();
  for (const DetectorOption& entry : DetectorOptionTable()) {
    DetectRunOptions options;
    SetOddValue(entry, options);
    const frontend::DetectorOptions made = options.ToDetectorOptions();
    EXPECT_EQ(Fields(made.comic) != Fields(defaults.comic), entry.AppliesTo("comic")) << entry.flag;
    EXPECT_EQ(Fields(made.comic_paper) != Fields(defaults.comic_paper),
              entry.AppliesTo("comic-paper"))
        << entry.flag;
  }
}

}  // namespace
}  // namespace comic::sfm
