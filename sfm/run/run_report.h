// report.json of a detector's run: the run report (sfm/evaluation/sfm_report.h) with the options
// of the run, the camera (prior, final, whether the focal length could be refined), the track
// building, the diagnosis of a failure, the rotation-only path and the files written.
#pragma once

#include <nlohmann/json.hpp>

#include "sfm/run/detector_run.h"
#include "sfm/run/run_inputs.h"
#include "sfm/run/run_options.h"

namespace comic::sfm {

// The options of the run as report.json's "options" (and compare.json's) hold them.
nlohmann::json RunOptionsToJson(const ReconstructionRunOptions& options, const RunInputs& inputs);

// report.json's "camera": the prior, the camera of the model (refined or not), and whether the
// motion let the focal length be refined.
nlohmann::json CameraReportJson(const SequenceReconstruction& run, const RunInputs& inputs);

// The whole report.json of `run`; "outputs" lists the files written into the run's folder
// (DetectorOutputFiles) when `writes_outputs`.
nlohmann::json DetectorReportJson(const DetectorRun& run, const ReconstructionRunOptions& options,
                                  const RunInputs& inputs, bool writes_outputs);

}  // namespace comic::sfm
