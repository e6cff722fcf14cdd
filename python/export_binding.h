// comic.export_colmap: comic_export_colmap's run (sfm/run/colmap_export_run.h), its options
// named as that app's flags, its summary as a dict.
#pragma once

#include <pybind11/pybind11.h>

namespace comic::python {

// Adds export_colmap and export_colmap_option_names to `m`.
void BindExportColmap(pybind11::module_& m);

}  // namespace comic::python
