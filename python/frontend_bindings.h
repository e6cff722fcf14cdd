// The front end's functions of the module: imread, detect (comic_detect's run,
// sfm/run/detect_run.h), match and track, each turning numpy arrays and keywords into the
// libraries' types and releasing the GIL around the work.
#pragma once

#include <pybind11/pybind11.h>

namespace comic::python {

// Adds imread, detect, match, track and detector_option_table to `m`.
void BindFrontend(pybind11::module_& m);

}  // namespace comic::python
