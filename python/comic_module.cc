// The compiled half of the Python module `comic` (python/comic/__init__.py is the other half): the
// module definition. The functions are thin wrappers that turn numpy arrays and keyword dicts into
// the libraries' Options and types (array_conversions.h, keyword_options.h, detector_keywords.h,
// run_keywords.h), release the GIL around the heavy calls, and hand results back as plain numpy
// columns, which __init__.py packs into structured arrays. detect, reconstruct and export_colmap
// are doors onto the runs comic_detect, comic_sfm and comic_export_colmap call (sfm/run/), with
// their options named as the flags (--max-features -> max_features). comic::Error becomes
// ValueError (kInvalidArgument) or RuntimeError (every other kind), with the C++ message, which is
// the command line's.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <new>
#include <opencv2/core.hpp>
#include <string>

#include "frontend/detector_factory.h"
#include "frontend/feature.h"
#include "io/core/error.h"
#include "io/core/pixel_budget.h"
#include "io/core/printable_text.h"
#include "io/core/version.h"
#include "python/distributed_binding.h"
#include "python/export_binding.h"
#include "python/frontend_bindings.h"
#include "python/reconstruct_binding.h"
#include "sfm/option_vocabulary.h"

namespace py = pybind11;

namespace {

// Every C++ error is a Python exception with the command line's one line (RunMain's): the option
// named as the flag, printable, never an abort and never a raw multi-line library text.
void TranslateException(std::exception_ptr pointer) {
  try {
    if (pointer) std::rethrow_exception(pointer);
  } catch (const comic::Error& e) {
    const std::string message =
        comic::io::PrintableMessage(comic::sfm::WithUserOptionNames(e.what()));
    if (e.kind() == comic::ErrorKind::kInvalidArgument) {
      PyErr_SetString(PyExc_ValueError, message.c_str());
    } else {
      PyErr_SetString(PyExc_RuntimeError, message.c_str());
    }
  } catch (const cv::Exception& e) {
    PyErr_SetString(
        PyExc_RuntimeError,
        ("OpenCV: " + comic::io::PrintableOneLine(e.err) + " (" + e.func + ")").c_str());
  } catch (const std::bad_alloc&) {
    PyErr_SetString(PyExc_MemoryError, "out of memory");
  }
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "comic-sfm's compiled core; use the package `comic` (python/comic/__init__.py).";
  m.attr("__version__") = comic::Version();  // project(VERSION), through io/core/version.cc
  m.attr("detector_names") = comic::frontend::DetectorNames();
  m.attr("patch_size") = comic::frontend::kPatchSize;
  m.attr("default_max_pixels") = comic::io::kDefaultMaxPixels;
  py::register_exception_translator(&TranslateException);
  comic::python::BindFrontend(m);
  comic::python::BindReconstruct(m);
  comic::python::BindExportColmap(m);
  comic::python::BindDistributed(m);
}
