// ArgParser: options, short names, hidden aliases, `--`, --help and --version.
#include "apps/common/arg_parser.h"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "io/core/error.h"
#include "io/core/version.h"

namespace {

using comic::apps::ArgParser;

// Parses `args` (without the program name).
ArgParser::Result Parse(ArgParser& parser, std::vector<std::string> args) {
  args.insert(args.begin(), "prog");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  return parser.Parse(static_cast<int>(argv.size()), argv.data());
}

struct Bound {
  std::string input;
  std::string output = "out";
  int count = 3;
  double radius = 20.0;
  bool quiet = false;
};

ArgParser MakeParser(Bound* bound) {
  ArgParser parser("prog", "INPUT [options]", "A test program.");
  parser.AddPositional("INPUT", "the input", &bound->input, /*required=*/false);
  parser.AddOption("output", "DIR", "output folder", &bound->output);
  parser.AddShortName('o', "output");
  parser.AddDeprecatedAlias("out", "output");
  parser.AddOption("count", "N", "how many", &bound->count);
  parser.AddOption("search-radius-of-the-matcher", "PX", "a long name", &bound->radius);
  parser.AddFlag("quiet", "no progress messages", &bound->quiet);
  parser.AddShortName('q', "quiet");
  return parser;
}

TEST(ArgParser, BindsOptionsShortNamesAndDeprecatedAliases) {
  Bound bound;
  ArgParser parser = MakeParser(&bound);
  EXPECT_EQ(Parse(parser, {"in", "-o", "a", "-q", "--count=7"}), ArgParser::Result::kRun);
  EXPECT_EQ(bound.input, "in");
  EXPECT_EQ(bound.output, "a");
  EXPECT_TRUE(bound.quiet);
  EXPECT_EQ(bound.count, 7);
  EXPECT_TRUE(parser.WasSet("output"));
  EXPECT_FALSE(parser.WasSet("search-radius-of-the-matcher"));

  Bound old;
  ArgParser old_parser = MakeParser(&old);
  EXPECT_EQ(Parse(old_parser, {"--out", "b", "x"}), ArgParser::Result::kRun);
  EXPECT_EQ(old.output, "b");
  EXPECT_TRUE(old_parser.WasSet("output"));  // the alias sets the option it stands for
}

TEST(ArgParser, DoubleDashEndsTheOptions) {
  Bound bound;
  ArgParser parser = MakeParser(&bound);
  EXPECT_EQ(Parse(parser, {"--count", "2", "--", "--strange-name"}), ArgParser::Result::kRun);
  EXPECT_EQ(bound.input, "--strange-name");
  EXPECT_EQ(bound.count, 2);
  Bound dash;
  ArgParser dash_parser = MakeParser(&dash);
  EXPECT_EQ(Parse(dash_parser, {"--", "-o"}), ArgParser::Result::kRun);
  EXPECT_EQ(dash.input, "-o");
  EXPECT_EQ(dash.output, "out");
}

TEST(ArgParser, UnknownShortAndLongNamesAreUsageErrors) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"-x"}, {"--bogus"}, {"--output"}, {"--quiet=1"}}) {
    Bound bound;
    ArgParser parser = MakeParser(&bound);
    try {
      Parse(parser, args);
      ADD_FAILURE() << args.front() << " was accepted";
    } catch (const comic::Error& e) {
      EXPECT_EQ(e.kind(), comic::ErrorKind::kInvalidArgument) << e.what();
    }
  }
}

TEST(ArgParser, HelpShowsShortNamesHidesAliasesAndKeepsNameAndMeaningApart) {
  Bound bound;
  ArgParser parser = MakeParser(&bound);
  const std::string help = parser.Help();
  EXPECT_NE(help.find("  -o, --output DIR"), std::string::npos) << help;
  EXPECT_NE(help.find("  -q, --quiet"), std::string::npos) << help;
  EXPECT_NE(help.find("  -h, --help"), std::string::npos) << help;
  EXPECT_NE(help.find("  --version"), std::string::npos) << help;
  EXPECT_EQ(help.find("--out "), std::string::npos) << help;
  // A name as long as the column gets the meaning on the next line, in column 30.
  EXPECT_NE(
      help.find("  --search-radius-of-the-matcher PX\n" + std::string(30, ' ') + "a long name"),
      std::string::npos)
      << help;
}

TEST(ArgParser, VersionAndHelpStopBeforeTheWork) {
  Bound bound;
  ArgParser parser = MakeParser(&bound);
  testing::internal::CaptureStdout();
  EXPECT_EQ(Parse(parser, {"--version"}), ArgParser::Result::kHelpShown);
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "prog " + comic::Version() + "\n");
  Bound help_bound;
  ArgParser help_parser = MakeParser(&help_bound);
  testing::internal::CaptureStdout();
  EXPECT_EQ(Parse(help_parser, {"-h", "--count", "x"}), ArgParser::Result::kHelpShown);
  EXPECT_NE(testing::internal::GetCapturedStdout().find("Usage: prog INPUT"), std::string::npos);
  EXPECT_EQ(help_bound.count, 3);
}

TEST(ArgParser, RefusesAShortNameOrAliasTakenTwice) {
  Bound bound;
  ArgParser parser = MakeParser(&bound);
  EXPECT_THROW(parser.AddShortName('o', "count"), comic::Error);
  EXPECT_THROW(parser.AddDeprecatedAlias("out", "count"), comic::Error);
  EXPECT_THROW(parser.AddDeprecatedAlias("count", "output"), comic::Error);
  EXPECT_THROW(parser.AddDeprecatedAlias("cnt", "no-such-option"), comic::Error);
}

}  // namespace

// --write-frames[=DIR]: alone it takes the implicit value, with '=' the given one, and the next
// argument stays a positional (GNU getopt's optional arguments).
TEST(ArgParser, OptionalValueTakesTheImplicitValueOrTheAttachedOne) {
  for (const auto& [args, expected, input] :
       std::vector<std::tuple<std::vector<std::string>, std::string, std::string>>{
           {{"--frames", "clip.mp4"}, "<beside>", "clip.mp4"},
           {{"clip.mp4", "--frames=out/img"}, "out/img", "clip.mp4"},
           {{"clip.mp4"}, "", "clip.mp4"}}) {
    std::string input_value;
    std::string frames;
    ArgParser parser("prog", "INPUT [options]", "A test program.");
    parser.AddPositional("INPUT", "the input", &input_value);
    parser.AddOptionalValueOption("frames", "DIR", "write the frames", "<beside>", &frames);
    EXPECT_EQ(Parse(parser, args), ArgParser::Result::kRun);
    EXPECT_EQ(frames, expected);
    EXPECT_EQ(input_value, input);
    EXPECT_EQ(parser.WasSet("frames"), !expected.empty());
    EXPECT_NE(parser.Help().find("--frames[=DIR]"), std::string::npos) << parser.Help();
  }
  std::string input_value;
  std::string frames;
  ArgParser parser("prog", "INPUT [options]", "A test program.");
  parser.AddPositional("INPUT", "the input", &input_value);
  parser.AddOptionalValueOption("frames", "DIR", "write the frames", "<beside>", &frames);
  EXPECT_THROW(Parse(parser, {"in", "--frames="}), comic::Error);
}
