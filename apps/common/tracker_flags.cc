#include "apps/common/tracker_flags.h"

#include <type_traits>
#include <variant>

#include "io/core/error.h"
#include "sfm/run/tracker_option_table.h"

namespace comic::apps {
namespace {

using Options = frontend::TrackerOptions;
using sfm::TrackerOption;

// Writes flag `entry`'s value as parsed into `to`'s field.
void ApplyFlag(const TrackerOption& entry, const TrackerFlags& flags, Options& to) {
  Options parsed = flags.options;  // the accessors take their struct by reference
  std::visit(
      [&](auto field) {
        using Field = decltype(field);
        if constexpr (std::is_same_v<Field, TrackerOption::Named>) {
          field.set(to, flags.names.at(entry.flag));
        } else if constexpr (std::is_same_v<Field, bool& (*)(Options&)>) {
          if (entry.metavar.empty()) {
            field(to) = field(parsed);
            return;
          }
          const int value = flags.numbered.at(entry.flag);
          COMIC_CHECK(value == 0 || value == 1, kInvalidArgument,
                      "--" << entry.flag << " must be 1 or 0, got " << value);
          field(to) = value == 1;
        } else {
          field(to) = field(parsed);
        }
      },
      entry.field);
}

}  // namespace

TrackerFlags::TrackerFlags() : options(sfm::DefaultRunTrackerOptions()) {
  for (const TrackerOption& entry : sfm::TrackerOptionTable()) {
    if (const auto* named = std::get_if<TrackerOption::Named>(&entry.field)) {
      names[entry.flag] = named->get(options);
    } else if (const auto* field = std::get_if<bool& (*)(Options&)>(&entry.field)) {
      if (!entry.metavar.empty()) numbered[entry.flag] = (*field)(options) ? 1 : 0;
    }
  }
}

void AddTrackerFlags(ArgParser& parser, TrackerFlags* flags) {
  for (const TrackerOption& entry : sfm::TrackerOptionTable()) {
    std::visit(
        [&](auto field) {
          using Field = decltype(field);
          if constexpr (std::is_same_v<Field, TrackerOption::Named>) {
            parser.AddOption(entry.flag, entry.metavar, entry.help, &flags->names[entry.flag]);
          } else if constexpr (std::is_same_v<Field, bool& (*)(Options&)>) {
            if (entry.metavar.empty()) {
              parser.AddFlag(entry.flag, entry.help, &field(flags->options));
            } else {
              parser.AddOption(entry.flag, entry.metavar, entry.help, &flags->numbered[entry.flag]);
            }
          } else {
            parser.AddOption(entry.flag, entry.metavar, entry.help, &field(flags->options));
          }
        },
        entry.field);
  }
}

frontend::TrackerOptions ToTrackerOptions(const TrackerFlags& flags) {
  Options options = flags.options;
  for (const TrackerOption& entry : sfm::TrackerOptionTable()) ApplyFlag(entry, flags, options);
  options.Check();
  return options;
}

sfm::TrackerSettings ToTrackerSettings(const TrackerFlags& flags, const ArgParser& parser) {
  sfm::TrackerSettings settings;
  for (const TrackerOption& entry : sfm::TrackerOptionTable()) {
    if (!parser.WasSet(entry.flag)) continue;
    ApplyFlag(entry, flags, settings.values);
    settings.MarkGiven(entry.flag);
  }
  return settings;
}

}  // namespace comic::apps
