// The geometry pictures of report.html (sfm/run/run_page.h): the 3-D view of the models' points
// and cameras, the top view of the camera paths, and with ground truth the error of each camera
// along the path. With ground truth every model is drawn in the truth's world (Sim(3)-aligned,
// metric where the truth is); without, the largest model in its own frame and units.
#pragma once

#include <string>
#include <vector>

#include "io/report/page_charts.h"
#include "io/report/page_scene.h"
#include "sfm/rigid3d.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/run_inputs.h"

namespace comic::sfm {

// A model placed in the page's world.
struct PlacedModel {
  int index = 0;  // 0 = the largest (sparse/0)
  const Reconstruction* model = nullptr;
  // Into the truth's world with the orientations aligned (the 3-D view), and with the centres
  // aligned as the ATE measures them (the top view, whose grey segments are the ATE's errors).
  // Both the identity without ground truth.
  Sim3d world_from_model;
  Sim3d centers_from_model;
};

// The models drawn, and whether they are in the ground truth's world.
struct PlacedModels {
  std::vector<PlacedModel> models;
  bool aligned = false;
  std::string unit;  // "m", "ground-truth units" or "model units"
  std::string note;  // what is left out and why (may be empty)
};

PlacedModels PlaceModels(const DetectorRun& run, const RunInputs& inputs);

// Points (subsampled beyond max_points), camera frusta per model and, with ground truth, the true
// path and the true positions of the frames no model holds.
io::Scene RunScene(const PlacedModels& placed, const RunInputs& inputs, size_t max_points);

// The top view on the run's plot plane: the true path, each model's cameras, a grey segment from
// each camera to its true position, and the unregistered frames marked where they truly were.
io::TopView RunTopView(const PlacedModels& placed, const DetectorRun& run, const RunInputs& inputs);

// With an evaluation: the position and the rotation error of each camera along the frames, the
// unregistered frames as ticks. Empty without one.
std::vector<io::LineChart> RunErrorCharts(const DetectorRun& run, const RunInputs& inputs);

}  // namespace comic::sfm
