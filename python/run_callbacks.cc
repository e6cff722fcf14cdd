#include "python/run_callbacks.h"

#include "sfm/run/run_messages.h"

namespace comic::python {

frontend::TrackingProgress TrackingCallback(const py::object& callback) {
  if (callback.is_none()) return {};
  const py::object* function = &callback;
  return [function](size_t done, size_t total) {
    py::gil_scoped_acquire gil;
    (*function)(done, total);
  };
}

sfm::RunCallbacks RunCallbacksFor(const py::object& callback, bool quiet,
                                  const std::string& program) {
  sfm::RunCallbacks callbacks;
  const py::object* function = &callback;
  callbacks.inputs_resolved = [quiet, program](const sfm::RunInputs& inputs) {
    py::gil_scoped_acquire gil;
    if (!inputs.sequence->warning().empty() &&
        PyErr_WarnEx(PyExc_RuntimeWarning, inputs.sequence->warning().c_str(), 1) != 0) {
      throw py::error_already_set();
    }
    if (quiet) return;
    for (const std::string& line : sfm::RunInputsLines(inputs, program)) py::print(line);
  };
  // A cache file that could not be used (recomputed and replaced), as the truncated video's.
  callbacks.warning = [](const std::string& message) {
    py::gil_scoped_acquire gil;
    if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw py::error_already_set();
  };
  // A choice the run made as it went (a second matcher tried), printed as the command line does.
  callbacks.note = [quiet, program](const std::string& message) {
    if (quiet) return;
    py::gil_scoped_acquire gil;
    py::print(program + ": " + message);
  };
  callbacks.frame_registered = [function, quiet](const std::string& detector,
                                                 const sfm::MapperProgress& p) {
    if (function->is_none() && quiet) return;
    py::gil_scoped_acquire gil;
    if (!quiet) py::print(sfm::FrameRegisteredLine(detector, p));
    if (function->is_none()) return;
    py::dict event;
    event["detector"] = detector;
    event["frame"] = p.frame;
    event["frame_name"] = p.frame_name;
    event["model"] = p.attempt;
    event["initial_pair"] = p.initial_pair;
    event["merged"] = p.merged;
    event["num_registered"] = p.num_registered;
    event["num_frames"] = p.num_frames;
    event["num_points3D"] = p.num_points3D;
    (*function)(event);
  };
  if (!quiet) {
    callbacks.detector_finished = [](const sfm::DetectorRun& run) {
      py::gil_scoped_acquire gil;
      py::print(sfm::DetectorSummaryLine(run));
    };
  }
  return callbacks;
}

}  // namespace comic::python
