// TrackerOptionTable: each entry is a distinct flag and keyword with a meaning and sets the field
// its name says, so that an entry pointing at the wrong field is caught here rather than by a user.
#include "sfm/run/tracker_option_table.h"

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <string>
#include <type_traits>
#include <variant>

#include "io/core/error.h"
#include "sfm/run/tracker_settings.h"

namespace comic::sfm {
namespace {

using Options = frontend::TrackerOptions;

TEST(TrackerOptionTable, NamesAreUniqueAndEveryEntryHasAMeaning) {
  std::set<std::string> flags;
  std::set<std::string> keywords;
  for (const TrackerOption& entry : TrackerOptionTable()) {
    EXPECT_TRUE(std::regex_match(entry.flag, std::regex("[a-z][a-z0-9-]*"))) << entry.flag;
    EXPECT_TRUE(flags.insert(entry.flag).second) << "two entries for --" << entry.flag;
    EXPECT_TRUE(keywords.insert(entry.keyword).second) << "two entries for " << entry.keyword;
    std::string expected_keyword = entry.flag;
    for (char& c : expected_keyword) c = c == '-' ? '_' : c;
    EXPECT_EQ(entry.keyword, expected_keyword);
    EXPECT_FALSE(entry.help.empty()) << entry.flag;
    // Only a bool may be a switch (no value name); a bool with a value name is given as 1 or 0.
    if (entry.metavar.empty()) {
      EXPECT_TRUE(std::holds_alternative<bool& (*)(Options&)>(entry.field)) << entry.flag;
    } else if (std::holds_alternative<bool& (*)(Options&)>(entry.field)) {
      EXPECT_EQ(entry.metavar, "BOOL") << entry.flag;
    }
  }
  EXPECT_EQ(flags.size(), 21u);
}

// The address of the field an entry sets, in `options` (a named entry: found by setting it).
const void* FieldAddress(const TrackerOption& entry, Options& options) {
  return std::visit(
      [&](auto field) -> const void* {
        if constexpr (std::is_same_v<decltype(field), TrackerOption::Named>) {
          return nullptr;
        } else {
          return &field(options);
        }
      },
      entry.field);
}

// Each entry's field, written out a second time on purpose: the table and this list would have
// to be wrong the same way for a flag to set another flag's field.
TEST(TrackerOptionTable, EachEntrySetsTheFieldOfItsName) {
  Options o;
  const std::map<std::string, const void*> expected = {
      {"max-features", &o.max_features},
      {"search-radius", &o.matcher.radius},
      {"unpredicted-radius", &o.unpredicted_radius},
      {"prediction", nullptr},
      {"coarse-radius", &o.coarse_radius},
      {"match-window", &o.match_window},
      {"track-conflicts", nullptr},
      {"verify-min-gap", &o.verify_min_gap},
      {"match-turned", &o.match_turned_180},
      {"max-cost", &o.matcher.max_cost},
      {"min-window-eigenvalue", &o.min_window_eigenvalue},
      {"align-patches", &o.align_patches},
      {"max-continued-frames", &o.continuation.max_continued_frames},
      {"max-alignment-residual", &o.continuation.max_residual},
      {"aligned-radius", &o.continuation.aligned_radius},
      {"min-alignment-correlation", &o.continuation.min_correlation},
      {"alignment-min-eigenvalue", &o.continuation.alignment.min_eigenvalue},
      {"bridge-frames", &o.continuation.bridge_frames},
      {"alignment-max-fb", &o.continuation.alignment.max_forward_backward_px},
      {"alignment-iterations", &o.continuation.alignment.max_iterations},
      {"alignment-levels", &o.continuation.alignment.levels},
  };
  for (const TrackerOption& entry : TrackerOptionTable()) {
    const auto it = expected.find(entry.flag);
    ASSERT_NE(it, expected.end()) << "--" << entry.flag << " is missing from this test's list";
    EXPECT_EQ(FieldAddress(entry, o), it->second) << "--" << entry.flag << " sets another field";
  }
  // The two named entries, by their effect.
  Options named;
  std::get<TrackerOption::Named>(FindTrackerOption("prediction").field).set(named, "none");
  EXPECT_EQ(named.prediction, frontend::MotionPrediction::kNone);
  std::get<TrackerOption::Named>(FindTrackerOption("track-conflicts").field).set(named, "drop");
  EXPECT_EQ(named.conflict_rule, frontend::TrackConflictRule::kDrop);
  EXPECT_EQ(std::get<TrackerOption::Named>(FindTrackerOption("prediction").field).get(named),
            "none");
}

// CopyTrackerOption copies its entry's field and nothing else.
TEST(TrackerOptionTable, CopyingAnEntryCopiesOnlyItsField) {
  Options from;
  from.matcher.radius = 33.0;
  from.max_features = 77;
  from.prediction = frontend::MotionPrediction::kCoarseToFine;
  Options to;
  CopyTrackerOption(FindTrackerOption("search-radius"), from, to);
  CopyTrackerOption(FindTrackerOption("prediction"), from, to);
  EXPECT_EQ(to.matcher.radius, 33.0);
  EXPECT_EQ(to.prediction, frontend::MotionPrediction::kCoarseToFine);
  EXPECT_EQ(to.max_features, Options().max_features);
  EXPECT_THROW(FindTrackerOption("psychic-radius"), Error);
}

// A named entry's value round-trips through its name for every default the runs start from.
TEST(TrackerOptionTable, NamedEntriesRoundTripTheirNames) {
  Options defaults = DefaultRunTrackerOptions();
  for (const TrackerOption& entry : TrackerOptionTable()) {
    const auto* named = std::get_if<TrackerOption::Named>(&entry.field);
    if (named == nullptr) continue;
    Options copy;
    named->set(copy, named->get(defaults));
    EXPECT_EQ(named->get(copy), named->get(defaults)) << entry.flag;
    EXPECT_THROW(named->set(copy, "psychic"), Error) << entry.flag;
  }
}

}  // namespace
}  // namespace comic::sfm
