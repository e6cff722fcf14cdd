// The options of CoMIC's two searches, each written once: its flag, its Python keyword, its value
// name, its meaning, the searches it applies to and the field of DetectRunOptions it sets.
// comic_detect adds a flag per entry and comic.detect (and the detector_options of the other
// Python runs) a keyword per entry, with its docstring made from the table, so the doors cannot
// drift. The default is the field's initialiser (a default-constructed DetectRunOptions, itself
// the search's own default), never written here.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "sfm/run/detect_run.h"

namespace comic::sfm {

struct DetectorOption {
  // The field an entry sets, by its type; a captureless lambda converts to each.
  using Field = std::variant<bool& (*)(DetectRunOptions&), int& (*)(DetectRunOptions&),
                             double& (*)(DetectRunOptions&)>;
  // Which of CoMIC's searches reads the field.
  enum class Searches { kBoth, kDirect, kPaper };

  std::string flag;     // the long flag without its dashes: "half-length"
  std::string keyword;  // the Python keyword: the flag with '-' -> '_'
  std::string metavar;  // the value's name in --help ("PX"); empty for a switch
  std::string help;     // the meaning, as --help prints it
  Searches searches = Searches::kBoth;
  Field field;

  // Whether the search `detector` ("comic" or "comic-paper") reads this entry's field.
  bool AppliesTo(const std::string& detector) const;
};

// Every option of the two searches, in the order --help lists them.
std::vector<DetectorOption> DetectorOptionTable();

}  // namespace comic::sfm
