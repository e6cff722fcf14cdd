// The registration timeline of report.html (sfm/run/run_page.h): one cell per frame, in the
// colour of the model that holds it, with the frames no model holds and why. The page takes a
// list of models and a state per frame, so more models and more states (keyframes, poses found
// without PnP) are new rows of the same table, not a new picture.
#pragma once

#include <string>
#include <vector>

#include "io/report/page_charts.h"
#include "sfm/reconstruction.h"
#include "sfm/run/detector_run.h"

namespace comic::sfm {

// The models of a run, the largest first (sparse/0, sparse/1, ...); none for a failed run.
std::vector<const Reconstruction*> RunModels(const DetectorRun& run);

// The colour of model `index` (0 = the largest) on every picture of the page.
std::string ModelColor(int index);

// The page's words for model `index`: "model 1 (sparse/0)".
std::string ModelName(int index);

// The frames (image id - 1) registered in `model`, ascending.
std::vector<int> RegisteredFramesOf(const Reconstruction& model);

// One cell per frame of `frame_names`: registered in which model, or unregistered (with the
// mapper's reason where it gives one, the diagnosis for a failed run).
io::Timeline RunTimeline(const DetectorRun& run, const std::vector<std::string>& frame_names);

}  // namespace comic::sfm
