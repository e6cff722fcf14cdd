// Progress from C++ code running without the GIL to Python: the tracker's frame count to a
// callback, and a reconstruction run's events (sfm/run's RunCallbacks) to a callback and to the
// command line's lines on sys.stdout. Each callback takes the GIL for its call.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "frontend/matching/tracker.h"
#include "sfm/run/detector_run.h"

namespace comic::python {

namespace py = pybind11;

// `callback(done, total)` after each frame; none when `callback` is None. It captures a pointer
// to the caller's py::object (alive for the whole call), so that copying the std::function inside
// the libraries touches no Python reference count without the GIL.
frontend::TrackingProgress TrackingCallback(const py::object& callback);

// The run's progress for Python: `callback(event)` after each registered frame (a dict), and the
// command line's lines printed (sys.stdout) unless `quiet`; a truncated video's warning and an
// unusable --cache file's as a RuntimeWarning. `program` prefixes the printed notes.
sfm::RunCallbacks RunCallbacksFor(const py::object& callback, bool quiet,
                                  const std::string& program);

}  // namespace comic::python
