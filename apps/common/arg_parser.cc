#include "apps/common/arg_parser.h"

#include <cerrno>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <new>
#include <opencv2/core.hpp>
#include <sstream>

#include "io/core/error.h"
#include "io/core/library_messages.h"
#include "io/core/printable_text.h"
#include "io/core/version.h"
#include "sfm/option_vocabulary.h"

namespace comic::apps {

ArgParser::ArgParser(std::string program, std::string usage, std::string description)
    : program_(std::move(program)), usage_(std::move(usage)), description_(std::move(description)) {
  AddFlag("help", "show this help and exit", nullptr);
  AddShortName('h', "help");
  AddFlag("version", "print the version and exit", nullptr);
}

void ArgParser::AddPositional(const std::string& name, const std::string& help, std::string* value,
                              bool required) {
  positionals_.push_back({name, help, value, required});
}

void ArgParser::AddFlag(const std::string& name, const std::string& help, bool* value) {
  options_.push_back({name, "", help, "", [value](const std::string&) {
                        if (value) *value = true;
                      }});
}

void ArgParser::AddOption(const std::string& name, const std::string& value_name,
                          const std::string& help, std::string* value) {
  options_.push_back({name, value_name, help, value->empty() ? "" : *value,
                      [value](const std::string& text) { *value = text; }});
}

void ArgParser::AddOption(const std::string& name, const std::string& value_name,
                          const std::string& help, int* value) {
  options_.push_back(
      {name, value_name, help, std::to_string(*value), [name, value](const std::string& text) {
         errno = 0;
         char* end = nullptr;
         const long parsed = std::strtol(text.c_str(), &end, 10);
         COMIC_CHECK(!text.empty() && *end == '\0' && errno == 0 && parsed >= INT32_MIN &&
                         parsed <= INT32_MAX,
                     kInvalidArgument,
                     "--" << name << ": expected an integer, got '" << text << "'");
         *value = static_cast<int>(parsed);
       }});
}

void ArgParser::AddOption(const std::string& name, const std::string& value_name,
                          const std::string& help, double* value) {
  std::ostringstream default_text;
  default_text << *value;
  options_.push_back(
      {name, value_name, help, default_text.str(), [name, value](const std::string& text) {
         errno = 0;
         char* end = nullptr;
         const double parsed = std::strtod(text.c_str(), &end);
         COMIC_CHECK(!text.empty() && *end == '\0' && errno == 0, kInvalidArgument,
                     "--" << name << ": expected a number, got '" << text << "'");
         *value = parsed;
       }});
}

void ArgParser::AddOptionalValueOption(const std::string& name, const std::string& value_name,
                                       const std::string& help, const std::string& implicit_value,
                                       std::string* value) {
  Option option{name, value_name, help, "", [value](const std::string& text) { *value = text; }};
  option.value_optional = true;
  option.implicit_value = implicit_value;
  options_.push_back(std::move(option));
}

void ArgParser::AddShortName(char letter, const std::string& name) {
  Option* option = FindOption(name);
  COMIC_CHECK(option != nullptr, kInvalidArgument, "AddShortName: no option --" << name);
  for (const Option& other : options_) {
    COMIC_CHECK(other.short_name != letter, kInvalidArgument,
                "AddShortName: -" << letter << " is already --" << other.name);
  }
  option->short_name = letter;
}

void ArgParser::AddDeprecatedAlias(const std::string& alias, const std::string& name) {
  COMIC_CHECK(FindOption(name) != nullptr, kInvalidArgument,
              "AddDeprecatedAlias: no option --" << name);
  COMIC_CHECK(FindOptionOrAlias(alias) == nullptr, kInvalidArgument,
              "AddDeprecatedAlias: --" << alias << " is already an option");
  aliases_.push_back({alias, name});
}

void ArgParser::AddEpilog(const std::string& text) { epilog_ += text; }

ArgParser::Option* ArgParser::FindOption(const std::string& name) {
  for (Option& option : options_) {
    if (option.name == name) return &option;
  }
  return nullptr;
}

ArgParser::Option* ArgParser::FindOptionOrAlias(const std::string& name) {
  if (Option* option = FindOption(name)) return option;
  for (const Alias& alias : aliases_) {
    if (alias.alias == name) return FindOption(alias.name);
  }
  return nullptr;
}

bool ArgParser::WasSet(const std::string& name) const {
  for (const Option& option : options_) {
    if (option.name == name) return option.seen;
  }
  return false;
}

ArgParser::Result ArgParser::Parse(int argc, char** argv) {
  size_t next_positional = 0;
  bool options_ended = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (!options_ended && arg == "--") {
      options_ended = true;
      continue;
    }
    Option* option = nullptr;
    std::string name;
    std::string value;
    bool has_inline_value = false;
    if (!options_ended && arg.size() > 2 && arg.compare(0, 2, "--") == 0) {
      name = arg.substr(2);
      const size_t eq = name.find('=');
      if (eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        has_inline_value = true;
      }
      option = FindOptionOrAlias(name);
      COMIC_CHECK(option != nullptr, kInvalidArgument,
                  "unknown option --" << name << " (see " << program_ << " --help)");
    } else if (!options_ended && arg.size() == 2 && arg[0] == '-' && arg[1] != '-') {
      for (Option& candidate : options_) {
        if (candidate.short_name == arg[1]) option = &candidate;
      }
      COMIC_CHECK(option != nullptr, kInvalidArgument,
                  "unknown option " << arg << " (see " << program_ << " --help)");
      name = option->name;
    }
    if (option == nullptr) {
      COMIC_CHECK(next_positional < positionals_.size(), kInvalidArgument,
                  "unexpected argument '" << arg << "' (see " << program_ << " --help)");
      *positionals_[next_positional++].value = arg;
      continue;
    }
    if (option->name == "help") {
      std::cout << Help();
      return Result::kHelpShown;
    }
    if (option->name == "version") {
      std::cout << program_ << " " << Version() << "\n";
      return Result::kHelpShown;
    }
    if (option->value_name.empty()) {
      COMIC_CHECK(!has_inline_value, kInvalidArgument, "--" << name << " takes no value");
    } else if (option->value_optional) {
      if (!has_inline_value) value = option->implicit_value;
      COMIC_CHECK(!value.empty(), kInvalidArgument,
                  "--" << name << "= needs a value (" << option->value_name << ")");
    } else if (!has_inline_value) {
      COMIC_CHECK(i + 1 < argc, kInvalidArgument,
                  "--" << name << " needs a value (" << option->value_name << ")");
      value = argv[++i];
    }
    option->assign(value);
    option->seen = true;
  }
  for (size_t p = next_positional; p < positionals_.size(); ++p) {
    COMIC_CHECK(!positionals_[p].required, kInvalidArgument,
                "missing argument " << positionals_[p].name << " (see " << program_ << " --help)");
  }
  return Result::kRun;
}

std::string ArgParser::Help() const {
  std::ostringstream out;
  out << "Usage: " << program_ << " " << usage_ << "\n\n" << description_ << "\n";
  if (!positionals_.empty()) {
    out << "\nArguments:\n";
    for (const Positional& p : positionals_) {
      out << "  " << std::left << std::setw(28) << p.name << p.help
          << (p.required ? "" : " (optional)") << "\n";
    }
  }
  out << "\nOptions:\n";
  for (const Option& option : options_) {
    std::string left = "--" + option.name;
    if (option.short_name != '\0') left = std::string("-") + option.short_name + ", " + left;
    if (option.value_optional) {
      left += "[=" + option.value_name + "]";
    } else if (!option.value_name.empty()) {
      left += " " + option.value_name;
    }
    // The meaning starts in column 30; a longer name gets a line of its own so that name and
    // meaning stay apart (tests/apps/option_vocabulary_test.cc reads them back).
    if (left.size() >= 28) left += "\n" + std::string(30, ' ');
    out << "  " << std::left << std::setw(28) << left << option.help;
    if (!option.default_text.empty()) out << " [default: " << option.default_text << "]";
    out << "\n";
  }
  if (!epilog_.empty()) out << "\n" << epilog_;
  return out.str();
}

void PrintWarning(const std::string& program, const std::string& text) {
  if (text.empty()) return;
  std::cerr << program << ": warning: " << io::PrintableMessage(text) << std::endl;
}

namespace {

// What a user can do about it: every app's work grows with the pixels and the frames.
int PrintOutOfMemory(const std::string& program) {
  std::cerr << program
            << ": error: out of memory; free memory or work smaller (--max-pixels, "
               "--resize-height, fewer frames)\n";
  return 1;
}

}  // namespace

int RunMain(const std::string& program, const std::function<int()>& body) {
  // One line, ours: OpenCV's own log stays quiet, and every message is made one printable line
  // (a file's binary garbage quoted in a parse error is escaped, never echoed raw).
  io::SilenceLibraryLogging();
  try {
    return body();
  } catch (const Error& e) {
    // Options by the flags' names, not the library fields' (sfm/option_vocabulary.h).
    std::cerr << program << ": error: " << io::PrintableMessage(sfm::WithUserOptionNames(e.what()))
              << "\n";
    return e.kind() == ErrorKind::kInvalidArgument ? 2 : 1;
  } catch (const cv::Exception& e) {
    // OpenCV's allocator reports running out of memory as its own exception, not bad_alloc.
    if (e.code == cv::Error::StsNoMem) return PrintOutOfMemory(program);
    std::cerr << program << ": error: OpenCV: " << io::PrintableOneLine(e.err) << " (" << e.func
              << ")\n";
    return 1;
  } catch (const std::bad_alloc&) {
    return PrintOutOfMemory(program);
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << io::PrintableMessage(e.what()) << "\n";
    return 1;
  }
}

std::string CommandLine(const std::string& program, int argc, char** argv) {
  std::string command = program;
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  return command;
}

}  // namespace comic::apps
