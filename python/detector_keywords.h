// The detectors' keywords: comic.detect's options and the detector_options of comic.track,
// comic.reconstruct and comic.export_colmap. CoMIC's two searches take one keyword per entry of
// the library's detector option table (sfm/run/detector_option_table.h), the flags of
// comic_detect; the baselines take their options' field names; every detector takes
// scale_levels.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "frontend/detector_factory.h"
#include "sfm/run/detect_run.h"

namespace comic::python {

namespace py = pybind11;

// Which door the keywords are for, which decides the keywords beyond the detector's own.
enum class DetectorDoor {
  kDetect,  // comic.detect: also threads= (default: every core, as comic_detect) and max_features=
  kTrack,   // comic.track's detector_options: also threads= (default: the detector's own)
  kRun,     // the runs' detector_options: the runs take their threads= themselves
};

// The detection run of `name` (one of comic.DETECTORS, or several joined by '+' when `options` is
// empty) with `options` applied, checked. Unknown keywords raise ValueError listing the valid ones.
sfm::DetectRunOptions DetectRunFromKeywords(const std::string& name, const py::dict& options,
                                            DetectorDoor door);

// DetectRunFromKeywords' detector options.
frontend::DetectorOptions MakeDetectorOptions(const std::string& name, const py::dict& options,
                                              DetectorDoor door);

// The table's entries for Python ({flag, keyword, metavar, help, default, detectors}): the
// docstring of detect() and the tests that every entry is a flag and a keyword.
py::list DetectorOptionEntries();

}  // namespace comic::python
