// RunOptionTable: each entry is a distinct flag and keyword with a meaning, and sets the field its
// name says, so that an entry pointing at the wrong field is caught here rather than by a user.
#include "sfm/run/run_option_table.h"

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <string>
#include <type_traits>
#include <variant>

namespace comic::sfm {
namespace {

// The address of the field an entry sets, in `options`.
const void* FieldAddress(const RunOption& entry, ReconstructionRunOptions& options) {
  return std::visit([&](auto field) -> const void* { return &field(options); }, entry.field);
}

TEST(RunOptionTable, NamesAreUniqueAndEveryEntryHasAMeaning) {
  std::set<std::string> flags;
  std::set<std::string> keywords;
  for (const RunOption& entry : RunOptionTable()) {
    EXPECT_TRUE(std::regex_match(entry.flag, std::regex("[a-z][a-z0-9-]*"))) << entry.flag;
    EXPECT_TRUE(flags.insert(entry.flag).second) << "two entries for --" << entry.flag;
    EXPECT_TRUE(keywords.insert(entry.keyword).second) << "two entries for " << entry.keyword;
    std::string expected_keyword = entry.flag;
    for (char& c : expected_keyword) c = c == '-' ? '_' : c;
    EXPECT_EQ(entry.keyword, expected_keyword);
    EXPECT_FALSE(entry.help.empty()) << entry.flag;
    // A switch has no value name, every other option one.
    EXPECT_EQ(entry.metavar.empty(),
              std::holds_alternative<bool& (*)(ReconstructionRunOptions&)>(entry.field))
        << entry.flag;
  }
  EXPECT_FALSE(flags.empty());
}

// Each entry's field, written out a second time on purpose: the table and this list would have
// to be wrong the same way for a flag to set another flag's field.
TEST(RunOptionTable, EachEntrySetsTheFieldOfItsName) {
  ReconstructionRunOptions o;
  const std::map<std::string, const void*> expected = {
      {"compare", &o.compare},
      {"gt", &o.gt},
      {"gt-format", &o.gt_format},
      {"gt-partial", &o.gt_partial},
      {"model-format", &o.model_format},
      {"ply-format", &o.ply_format},
      {"no-retriangulate", &o.no_retriangulate},
      {"no-planar-pose-choice", &o.no_planar_pose_choice},
      {"two-view-tracks", &o.two_view_tracks},
      {"refine-focal", &o.refine_focal},
      {"refine-principal-point", &o.refine_principal_point},
      {"refine-distortion", &o.refine_distortion},
      {"fixed-intrinsics", &o.camera.fixed_intrinsics},
      {"ignore-gt-intrinsics", &o.camera.ignore_gt_intrinsics},
      {"local-ba-images", &o.local_ba_images},
      {"global-ba-growth", &o.global_ba_growth},
      {"global-ba-max-images", &o.global_ba_max_images},
      {"init-angle", &o.init_angle},
      {"init-max-gap", &o.init_max_gap},
      {"keyframes", &o.keyframes},
      {"loop-closure", &o.loop_closure},
      {"loop-closure-max-move", &o.loop_closure_max_move},
      {"max-working-size", &o.max_working_size},
      {"min-registered", &o.min_registered},
      {"cache", &o.cache},
      {"plot-plane", &o.plot_plane},
      {"undistort", &o.undistort},
      {"compare-colmap", &o.compare_colmap},
      {"compare-colmap-sift", &o.compare_colmap_sift},
  };
  std::set<std::string> seen;
  for (const RunOption& entry : RunOptionTable()) {
    const auto it = expected.find(entry.flag);
    ASSERT_NE(it, expected.end()) << "--" << entry.flag << " is missing from this test's list";
    EXPECT_EQ(FieldAddress(entry, o), it->second) << "--" << entry.flag << " sets another field";
    seen.insert(entry.flag);
  }
  EXPECT_EQ(seen.size(), expected.size()) << "an entry of this test's list left the table";
}

// Setting one entry through the table changes that entry's field and no other entry's.
TEST(RunOptionTable, SettingAnEntryChangesOnlyItsField) {
  const std::vector<RunOption> table = RunOptionTable();
  const ReconstructionRunOptions defaults;
  // Each field's value as text, to compare fields of different types in one loop.
  const auto value_of = [](const RunOption& entry, ReconstructionRunOptions options) {
    return std::visit(
        [&](auto field) -> std::string {
          const auto& value = field(options);
          if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::string>) {
            return "s:" + value;
          } else {
            return "n:" + std::to_string(value);
          }
        },
        entry.field);
  };
  for (const RunOption& changed : table) {
    ReconstructionRunOptions options;
    std::visit(
        [&](auto field) {
          auto& value = field(options);
          using T = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<T, bool>) {
            value = !value;
          } else if constexpr (std::is_same_v<T, std::string>) {
            value += "-changed";
          } else {
            value = value + 7;
          }
        },
        changed.field);
    for (const RunOption& entry : table) {
      const bool differs = value_of(entry, options) != value_of(entry, defaults);
      EXPECT_EQ(differs, entry.flag == changed.flag)
          << "setting --" << changed.flag << " through the table, --" << entry.flag;
    }
  }
}

}  // namespace
}  // namespace comic::sfm
