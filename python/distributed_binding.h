// What comic.distributed (python/comic/distributed.py) needs from the library: the frames of an
// input, to cut it into chunks, the merging of the chunks' models (sfm/chunk_model_merging.h) and
// the run's report.html (sfm/run/distributed_run_page.h).
#pragma once

#include <pybind11/pybind11.h>

namespace comic::python {

// Adds _core.frame_names, _core.merge_chunk_models and _core.write_distributed_run_page to
// `module`.
void BindDistributed(pybind11::module_& module);

}  // namespace comic::python
