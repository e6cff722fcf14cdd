// The tracker's options (paper §4: frame-to-frame SSD patch matching within a radius, with the
// motion prediction real driving video needs), each written once: its flag, its Python keyword,
// its value name, its meaning and the field of frontend::TrackerOptions it sets. comic_sfm and
// comic_export_colmap add a flag per entry, comic.reconstruct, comic.export_colmap and
// comic.track a keyword per entry, and report.json echoes each entry under its keyword, so the
// doors cannot drift. The default is the field's value in DefaultRunTrackerOptions() (video
// SfM's tracker), never written here.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "frontend/matching/tracker.h"

namespace comic::sfm {

struct TrackerOption {
  using Options = frontend::TrackerOptions;
  // A field named by a word (--prediction velocity): read and written as its name; `set` throws
  // comic::Error(kInvalidArgument) for an unknown name.
  struct Named {
    std::string (*get)(const Options&);
    void (*set)(Options&, const std::string&);
  };
  // The field an entry sets, by its type; a captureless lambda converts to each.
  using Field = std::variant<bool& (*)(Options&), int& (*)(Options&), double& (*)(Options&), Named>;

  std::string flag;     // the long flag without its dashes: "search-radius"
  std::string keyword;  // the Python keyword: the flag with '-' -> '_'
  // The value's name in --help ("PX"); empty for a switch. A bool field with a value name is
  // given as 1 or 0 on the command line (a default-on switch: --align-patches 0).
  std::string metavar;
  std::string help;  // the meaning, as --help prints it
  Field field;
};

// Every tracker option, in the order --help lists them.
std::vector<TrackerOption> TrackerOptionTable();

// The entry of `flag`; throws comic::Error(kInvalidArgument) for a flag the table lacks.
TrackerOption FindTrackerOption(const std::string& flag);

// Sets `entry`'s field of `to` to its value in `from`.
void CopyTrackerOption(const TrackerOption& entry, const frontend::TrackerOptions& from,
                       frontend::TrackerOptions& to);

}  // namespace comic::sfm
