// One vocabulary across the apps (apps/common/shared_flags.h): runs every app's --help, reads
// back each option's name, short name, one-line meaning and default, and fails when one name has
// two meanings (or two defaults, outside the list of defaults that differ on purpose), when a
// short name stands for two options, or when two spellings of one meaning from kSynonyms are in
// use. The apps are found as apps/*.cc, so a new app is checked without an edit here.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;

struct HelpOption {
  std::string short_name;  // "o" for -o, or ""
  std::string value_name;  // "DIR", or "" for a switch
  std::string meaning;     // the help text's first line, without "[default: ...]"
  std::string default_text;
};

// Spellings of one meaning: at most one of each group may appear in the apps' --help. The
// first is the name in use; the others are the old ones (some still accepted, hidden, for one
// release) or the usual alternatives.
const std::vector<std::vector<std::string>> kSynonyms = {
    {"output", "out", "output-dir", "output-path", "out-dir"},
    {"search-radius", "radius"},
    {"resize-height", "height", "working-height"},
    {"regions", "boxes"},
    {"boundary-band", "band"},
    {"max-features", "num-features"},
    {"threads", "num-threads", "jobs"},
    {"quiet", "silent"},
    {"colmap-db", "database", "database-path", "db"},
    {"disparity-scale", "scale-disparity"},
};

// Defaults that differ between apps on purpose: option -> why.
const std::map<std::string, std::string> kDefaultsDifferOnPurpose = {
    {"resize-height", "the evaluations and the benchmark work at the paper's 700 px (§5)"},
    {"detectors", "comic_sfm's empty list is every detector; comic_track_eval names its five"},
    {"target-precision", "comic_stereo_eval's 0 takes --precision-reference's precision"},
    {"output", "each app's default folder is named after it (out/sfm, stereo_eval, track_eval)"},
    {"max-features", "comic_detect shows every feature of its image; the trackers keep 2000"},
    {"detector", "comic_detect shows CoMIC (comic); the SfM apps default to harris"},
    {"boundary-band",
     "comic_render_eval's region is the exact occlusion boundary (4 px: where a corner "
     "detector's window meets it); the others' an annotated region (11 px: the patch straddles "
     "its edge)"},
};

std::vector<std::string> AppNames() {
  std::vector<std::string> names;
  for (const auto& entry :
       std::filesystem::directory_iterator(comic::test::SourceDir() + "/apps")) {
    if (entry.path().extension() == ".cc") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// The "Options:" block of a --help text.
std::map<std::string, HelpOption> ParseHelp(const std::string& help) {
  std::map<std::string, HelpOption> options;
  std::istringstream in(help);
  std::string line;
  bool in_options = false;
  const std::regex option_line(
      R"(^  (?:-([A-Za-z]), )?--([a-z0-9][a-z0-9-]*)(?: ([A-Z][A-Z0-9_]*))?(?:\s+(.*))?$)");
  while (std::getline(in, line)) {
    if (line == "Options:") {
      in_options = true;
      continue;
    }
    if (!in_options) continue;
    if (line.empty()) break;
    std::smatch match;
    if (!std::regex_match(line, match, option_line)) continue;  // a continuation line
    const std::string name = match[2];  // `match` points into `line`, read again below
    HelpOption option;
    option.short_name = match[1];
    option.value_name = match[3];
    std::string meaning = match[4];
    if (meaning.empty() && std::getline(in, line)) {
      meaning = line.substr(line.find_first_not_of(' '));  // a long name: meaning on its own line
    }
    const size_t bracket = meaning.rfind(" [default: ");
    if (bracket != std::string::npos && meaning.back() == ']') {
      option.default_text = meaning.substr(bracket + 11, meaning.size() - bracket - 12);
      meaning = meaning.substr(0, bracket);
    }
    option.meaning = meaning;
    options[name] = option;
  }
  return options;
}

TEST(OptionVocabulary, ParseHelpReadsNamesMeaningsAndDefaults) {
  const std::string help =
      "Usage: x\n\nOptions:\n"
      "  -h, --help                  show this help and exit\n"
      "  -o, --output DIR            output folder (created if needed) [default: out/sfm]\n"
      "  --convergence-tolerance-long PX\n"
      "                              a corner has settled [default: 0.1]\n"
      "  --json FILE                 write JSON,\n"
      "                              continued here\n"
      "\nExample: --not-an-option\n";
  const auto options = ParseHelp(help);
  ASSERT_EQ(options.size(), 4u);
  EXPECT_EQ(options.at("output").short_name, "o");
  EXPECT_EQ(options.at("output").value_name, "DIR");
  EXPECT_EQ(options.at("output").meaning, "output folder (created if needed)");
  EXPECT_EQ(options.at("output").default_text, "out/sfm");
  EXPECT_EQ(options.at("convergence-tolerance-long").meaning, "a corner has settled");
  EXPECT_EQ(options.at("convergence-tolerance-long").default_text, "0.1");
  EXPECT_EQ(options.at("json").meaning, "write JSON,");
  EXPECT_EQ(options.at("help").short_name, "h");
}

class AppHelps : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    for (const std::string& app : AppNames()) {
      const auto result = RunCommand(AppPath(app) + " --help");
      ASSERT_EQ(result.exit_code, 0) << app << "\n" << result.output;
      helps_[app] = ParseHelp(result.output);
      ASSERT_GE(helps_[app].size(), 3u) << app << ": no options read from\n" << result.output;
    }
  }
  static std::map<std::string, std::map<std::string, HelpOption>> helps_;
};
std::map<std::string, std::map<std::string, HelpOption>> AppHelps::helps_;

TEST_F(AppHelps, EveryAppIsChecked) {
  for (const char* app : {"comic_sfm", "comic_detect", "comic_stereo_eval", "comic_track_eval",
                          "comic_export_colmap", "comic_bench", "comic_inspect"}) {
    EXPECT_EQ(helps_.count(app), 1u) << app;
  }
}

TEST_F(AppHelps, OneNameHasOneMeaningOneValueNameAndOneDefault) {
  std::map<std::string, std::pair<std::string, HelpOption>> first_use;  // name -> (app, option)
  for (const auto& [app, options] : helps_) {
    for (const auto& [name, option] : options) {
      const auto [it, inserted] = first_use.insert({name, {app, option}});
      if (inserted) continue;
      const auto& [other_app, other] = it->second;
      EXPECT_EQ(option.meaning, other.meaning)
          << "--" << name << " means two things: in " << app << " and in " << other_app;
      EXPECT_EQ(option.value_name, other.value_name)
          << "--" << name << ": " << app << " vs " << other_app;
      EXPECT_EQ(option.short_name, other.short_name)
          << "--" << name << ": " << app << " vs " << other_app;
      if (kDefaultsDifferOnPurpose.count(name) == 0) {
        EXPECT_EQ(option.default_text, other.default_text)
            << "--" << name << " has two defaults: in " << app << " and in " << other_app;
      }
    }
  }
  // The vocabulary the issue asked for is in use.
  for (const char* name : {"output", "threads", "search-radius", "resize-height", "regions",
                           "boundary-band", "max-features", "version", "help"}) {
    EXPECT_EQ(first_use.count(name), 1u) << "--" << name << " is used by no app";
  }
}

TEST_F(AppHelps, OneShortNameStandsForOneOption) {
  std::map<std::string, std::string> long_of_short;
  for (const auto& [app, options] : helps_) {
    for (const auto& [name, option] : options) {
      if (option.short_name.empty()) continue;
      const auto [it, inserted] = long_of_short.insert({option.short_name, name});
      EXPECT_EQ(it->second, name) << "-" << option.short_name << " in " << app;
    }
  }
  EXPECT_EQ(long_of_short["o"], "output");
  EXPECT_EQ(long_of_short["q"], "quiet");
  EXPECT_EQ(long_of_short["h"], "help");
}

TEST_F(AppHelps, OneMeaningHasOneSpelling) {
  for (const std::vector<std::string>& group : kSynonyms) {
    std::map<std::string, std::string> used;  // spelling -> an app using it
    for (const auto& [app, options] : helps_) {
      for (const std::string& spelling : group) {
        if (options.count(spelling)) used[spelling] = app;
      }
    }
    EXPECT_LE(used.size(), 1u) << "two spellings of --" << group.front() << ": --"
                               << used.begin()->first << " (" << used.begin()->second << ") and --"
                               << used.rbegin()->first << " (" << used.rbegin()->second << ")";
    if (used.size() == 1) {
      EXPECT_EQ(used.begin()->first, group.front()) << "use --" << group.front();
    }
  }
}

}  // namespace
