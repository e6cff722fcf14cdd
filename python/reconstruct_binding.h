// comic.reconstruct (comic_sfm's run, sfm/run/reconstruction_run.h) and the Reconstruction it
// returns: every model in the input's pixels, its report, and writing its outputs with
// comic_sfm's own writer; also comic.Reconstruction(path), a model read from a folder.
#pragma once

#include <pybind11/pybind11.h>

namespace comic::python {

// Adds reconstruct, read_reconstruction, reconstruct_option_names, run_option_table and the class
// Reconstruction to `m`.
void BindReconstruct(pybind11::module_& m);

}  // namespace comic::python
