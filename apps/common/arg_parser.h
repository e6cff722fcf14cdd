// A small command-line parser shared by the apps: positional arguments, `--name value` /
// `--name=value` options bound to variables (their initial values are the documented defaults),
// boolean switches, one-letter short names (`-o DIR`, `-q`), hidden aliases for old spellings,
// `--` ending the options, a generated --help and --version (comic::Version(), io/core/version.h).
// Flags are parsed here and nowhere below apps/; the names shared by several apps are defined
// once in apps/common/shared_flags.h.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace comic::apps {

class ArgParser {
 public:
  // `usage` is the synopsis after the program name, `description` a paragraph for --help.
  ArgParser(std::string program, std::string usage, std::string description);

  void AddPositional(const std::string& name, const std::string& help, std::string* value,
                     bool required = true);
  // A switch: present -> true.
  void AddFlag(const std::string& name, const std::string& help, bool* value);
  void AddOption(const std::string& name, const std::string& value_name, const std::string& help,
                 std::string* value);
  void AddOption(const std::string& name, const std::string& value_name, const std::string& help,
                 int* value);
  void AddOption(const std::string& name, const std::string& value_name, const std::string& help,
                 double* value);
  // An option whose value may be left out: `--name` alone sets `implicit_value`, `--name=VALUE`
  // sets VALUE (GNU getopt's optional arguments: `--name VALUE` would be ambiguous with a
  // positional, so the value must be attached with '='). Shown in --help as `--name[=VALUE]`.
  void AddOptionalValueOption(const std::string& name, const std::string& value_name,
                              const std::string& help, const std::string& implicit_value,
                              std::string* value);
  // `-<letter>` as a short name of the option `name` (added before); shown in --help.
  void AddShortName(char letter, const std::string& name);
  // `--<alias>` as an old spelling of the option `name` (added before): accepted, not shown in
  // --help (kept for one release so that scripts keep working; docs/apps.md lists them).
  void AddDeprecatedAlias(const std::string& alias, const std::string& name);
  // Free text appended to --help (examples, notes on outputs).
  void AddEpilog(const std::string& text);

  // kHelpShown: -h/--help or --version was printed to stdout; the app exits 0 without work.
  enum class Result { kRun, kHelpShown };
  // Parses argv. Prints help to stdout and returns kHelpShown for -h/--help, likewise the version
  // for --version. Arguments after `--` are positionals even when they start with '-'. Throws
  // comic::Error(kInvalidArgument) with a one-line message for unknown options, missing values,
  // malformed numbers and missing positionals.
  Result Parse(int argc, char** argv);
  // True if the option `name` (without dashes; not an alias) was given on the command line.
  bool WasSet(const std::string& name) const;

  std::string Help() const;
  const std::string& program() const { return program_; }

 private:
  struct Option {
    std::string name;
    std::string value_name;  // empty for switches
    std::string help;
    std::string default_text;
    std::function<void(const std::string&)> assign;
    bool seen = false;
    char short_name = '\0';
    bool value_optional = false;  // AddOptionalValueOption: the value may be left out
    std::string implicit_value{};
  };
  struct Alias {
    std::string alias;
    std::string name;
  };
  struct Positional {
    std::string name;
    std::string help;
    std::string* value;
    bool required;
  };
  Option* FindOption(const std::string& name);
  // The option called `name`, or the one `name` is an alias of; nullptr if none.
  Option* FindOptionOrAlias(const std::string& name);

  std::string program_;
  std::string usage_;
  std::string description_;
  std::string epilog_;
  std::vector<Option> options_;
  std::vector<Positional> positionals_;
  std::vector<Alias> aliases_;
};

// Runs an app body, mapping failures to one line on stderr and an exit code: comic::Error of
// kind kInvalidArgument -> 2 (usage), other comic::Error and any std::exception -> 1. Never lets
// an exception escape main().
int RunMain(const std::string& program, const std::function<int()>& body);

// The command as typed, for reports: `program` and argv[1..] joined by spaces.
std::string CommandLine(const std::string& program, int argc, char** argv);

// "PROGRAM: warning: TEXT" on stderr as one printable line (io/core/printable_text.h); nothing
// for an empty text.
void PrintWarning(const std::string& program, const std::string& text);

}  // namespace comic::apps
