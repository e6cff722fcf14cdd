// The plain options of a reconstruction run, each written once: its flag, its Python keyword,
// its value name, its meaning and the field of ReconstructionRunOptions it sets. comic_sfm adds
// a flag per entry and comic.reconstruct a keyword per entry, so the two doors cannot drift; the
// default is the field's initialiser (a default-constructed ReconstructionRunOptions), never
// written here. The options that need more than a field (whether they were given, a negation, an
// optional value, a flag shared with other apps) are added by each door itself.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "sfm/run/run_options.h"

namespace comic::sfm {

struct RunOption {
  // The field an entry sets, by its type; a captureless lambda converts to each.
  using Field =
      std::variant<bool& (*)(ReconstructionRunOptions&), int& (*)(ReconstructionRunOptions&),
                   double& (*)(ReconstructionRunOptions&),
                   std::string& (*)(ReconstructionRunOptions&)>;

  std::string flag;     // the long flag without its dashes: "init-max-gap"
  std::string keyword;  // the Python keyword: the flag with '-' -> '_'
  std::string metavar;  // the value's name in --help ("N", "DIR"); empty for a switch
  std::string help;     // the meaning, as --help prints it
  Field field;
  // report.json's options hold the field as given, under the keyword; the other entries are
  // reported as the run resolved them, under names older than this table (run_report.cc).
  bool reported_as_given = false;
};

// Every plain option, in the order --help lists them.
std::vector<RunOption> RunOptionTable();

}  // namespace comic::sfm
