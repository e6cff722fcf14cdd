// What comic.distributed (python/comic/distributed.py) needs from the library: the frames of an
// input, to cut it into chunks, and the merging of the chunks' models (sfm/chunk_model_merging.h).
#pragma once

#include <pybind11/pybind11.h>

namespace comic::python {

// Adds _core.frame_names and _core.merge_chunk_models to `module`.
void BindDistributed(pybind11::module_& module);

}  // namespace comic::python
