#include "python/reconstruct_binding.h"

#include <pybind11/stl.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_model_folder.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/protected_inputs.h"
#include "io/report/json_text.h"
#include "io/report/ply.h"
#include "python/detector_keywords.h"
#include "python/keyword_options.h"
#include "python/model_columns.h"
#include "python/run_callbacks.h"
#include "python/run_keywords.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/run/reconstruction_run.h"
#include "sfm/run/run_messages.h"
#include "sfm/run/run_option_table.h"
#include "sfm/run/run_outputs.h"
#include "sfm/run/tracker_option_table.h"
#include "sfm/run/tracker_settings.h"

namespace comic::python {
namespace {

// A reconstruction for Python: the COLMAP model and, for a run's, its report.json and status.
struct PyReconstruction {
  io::ColmapTextModel model;  // a run's largest model, in the input's pixels as comic_sfm writes it
  // A run's: every model (the largest first), in the input's pixels; and the run itself with its
  // options, kept so that writing it is comic_sfm's own writer on the same run (WriteOutputs).
  std::vector<io::ColmapTextModel> models;
  std::shared_ptr<const sfm::ReconstructionRunResult> run_result;
  size_t run_index = 0;
  sfm::ReconstructionRunOptions run_options;
  std::string status;       // ReconstructionStatusName; "" for a model read without a report
  std::string report_json;  // report.json's text ("" without one)
  std::string failure;      // a single detector's run without a model: the command line's error
  std::string path;         // where the model is on disk ("" for a run without --output)
};

// The `index`th run of `run_result`, its models in the input's pixels (as comic_sfm writes them).
PyReconstruction FromDetectorRun(
    const std::shared_ptr<const sfm::ReconstructionRunResult>& run_result, size_t index,
    const sfm::ReconstructionRunOptions& options, const std::string& path) {
  const sfm::DetectorRun& run = run_result->runs[index];
  PyReconstruction result;
  result.run_result = run_result;
  result.run_index = index;
  result.run_options = options;
  if (run.success()) {
    const sfm::ModelSetWriteOptions in_input_pixels = sfm::ModelWriteOptions(run, options);
    for (const sfm::Reconstruction* model : sfm::ModelsLargestFirst(run.run.mapping)) {
      result.models.push_back(sfm::ColmapModelForImages(*model, in_input_pixels));
    }
    result.model = result.models.front();
  }
  result.status = sfm::ReconstructionStatusName(run.run.mapping.status);
  result.report_json = io::JsonText(run.report_json, 2);
  result.path = run.success() ? path : "";
  return result;
}

// comic.reconstruct: comic_sfm's run (sfm/run/reconstruction_run.h). Returns {"runs": [one
// Reconstruction per detector], "failure", "comparison" (the --compare table), "lines" (what
// comic_sfm prints after the run)}.
py::dict Reconstruct(const std::string& frames, const py::dict& options,
                     const py::dict& detector_options, const py::object& callback) {
  sfm::ReconstructionRunOptions run;
  run.frames = frames;
  run.output.clear();  // nothing written unless output= is given
  bool quiet = true;
  ApplyOptions(options, ReconstructOptionTable(&run, &quiet), "reconstruct");
  run.Check();
  if (!detector_options.empty()) {
    COMIC_CHECK(!run.compare, kInvalidArgument,
                "detector_options are one detector's, not --compare's");
    const int scale_levels = run.detector_options.scale_space.num_levels;  // scale_levels=
    run.detector_options =
        MakeDetectorOptions(run.DetectorList().front(), detector_options, DetectorDoor::kRun);
    // detector_options' own scale_levels wins over the keyword's only when it is given.
    if (!detector_options.contains("scale_levels")) {
      run.detector_options.scale_space.num_levels = scale_levels;
    }
  }
  const sfm::RunCallbacks callbacks = RunCallbacksFor(callback, quiet, "comic.reconstruct");
  sfm::ReconstructionRunResult result;
  {
    py::gil_scoped_release release;
    result = sfm::RunReconstruction(run, callbacks);
  }
  const auto shared = std::make_shared<const sfm::ReconstructionRunResult>(std::move(result));
  py::list runs;
  for (size_t i = 0; i < shared->runs.size(); ++i) {
    const std::string& detector = shared->runs[i].detector;
    const std::string folder = run.output.empty() ? ""
                               : run.compare      ? io::JoinPaths(run.output, detector)
                                                  : run.output;
    PyReconstruction reconstruction = FromDetectorRun(shared, i, run, folder);
    if (!run.compare) reconstruction.failure = shared->failure;
    runs.append(py::cast(std::move(reconstruction)));
  }
  py::dict out;
  out["runs"] = runs;
  out["failure"] = shared->failure;
  out["comparison"] =
      shared->comparison ? py::object(py::str(shared->comparison->ToMarkdown())) : py::none();
  out["lines"] = sfm::RunOutcomeLines(*shared, run.output, "comic.reconstruct", quiet);
  return out;
}

// comic.Reconstruction(path): a model in a folder (io/colmap/colmap_model_folder.h), with the
// report.json beside it when comic_sfm wrote one.
PyReconstruction ReadReconstruction(const std::string& path) {
  PyReconstruction result;
  result.model = io::ReadColmapModel(path);
  result.models = {result.model};
  result.path = path;
  const std::string report = io::JoinPaths(path, "report.json");
  if (io::PathExists(report)) {
    result.report_json = io::ReadFileToString(report);
    const nlohmann::json json = nlohmann::json::parse(result.report_json, nullptr, false);
    COMIC_CHECK(!json.is_discarded() && json.is_object(), kInvalidData,
                report << ": not a JSON object");
    if (json.contains("status") && json["status"].is_string()) result.status = json["status"];
  }
  return result;
}

// Reconstructions.write: a run's outputs written by comic_sfm's writer (sfm/run/run_outputs.h) into
// `folder`, as `comic_sfm FRAMES --output folder --model-format ... --ply-format ...` writes them
// for one detector.
void WriteOutputs(const PyReconstruction& r, const std::string& folder,
                  const std::string& model_format, const std::string& ply_format) {
  COMIC_CHECK(r.run_result != nullptr, kInvalidArgument,
              "write: only a run's reconstruction (comic.reconstruct) writes a run's outputs");
  sfm::ReconstructionRunOptions options = r.run_options;
  options.output = folder;
  options.compare = false;
  options.model_format = model_format;
  options.ply_format = ply_format;
  io::ParsePlyFormat(ply_format);  // its message names the PLY formats
  options.Check();
  // As comic_sfm's --output: no written file may replace an input (a folder of frames written
  // into would receive trajectory.png and the reports).
  io::CheckOutputsAvoidInputs({{"write", folder}}, sfm::RunInputPaths(options));
  io::CheckWrittenPathsAvoidInputs(sfm::RunWrittenPaths(options), sfm::RunInputPaths(options));
  py::gil_scoped_release release;
  sfm::WriteDetectorOutputs(r.run_result->runs[r.run_index], options, r.run_result->inputs, folder);
}

// One model of a run's reconstruction (0: the largest), alone, with the run's report.
PyReconstruction ModelOf(const PyReconstruction& r, size_t index) {
  COMIC_CHECK(index < r.models.size(), kInvalidArgument,
              "model " << index << ": the reconstruction holds " << r.models.size() << " models");
  PyReconstruction model;
  model.model = r.models[index];
  model.models = {r.models[index]};
  model.status = r.status;
  model.report_json = r.report_json;
  model.failure = r.failure;
  model.path = r.path;
  return model;
}

// Writes `r`'s largest (or only) model as a PLY point cloud in `format` ("binary" or "ascii").
void WritePointCloud(const PyReconstruction& r, const std::string& path,
                     const std::string& format) {
  std::vector<io::PlyPoint> cloud;
  for (const io::ColmapPoint3D& point : r.model.points3D) cloud.push_back({point.xyz, point.rgb});
  io::WritePly(path, cloud, io::ParsePlyFormat(format));
}

// The library's table of plain run options (sfm/run/run_option_table.h), for the docstring of
// reconstruct() and the tests that every entry is a flag and a keyword.
py::list RunOptionEntries() {
  py::list entries;
  sfm::ReconstructionRunOptions defaults;
  for (const sfm::RunOption& entry : sfm::RunOptionTable()) {
    entries.append(OptionEntryDict(entry, defaults));
  }
  return entries;
}

// The library's tracker table (sfm/run/tracker_option_table.h) with the run's defaults, for the
// docstrings of reconstruct() and export_colmap() and the tests of every entry.
py::list TrackerOptionEntries() {
  py::list entries;
  frontend::TrackerOptions defaults = sfm::DefaultRunTrackerOptions();
  for (const sfm::TrackerOption& entry : sfm::TrackerOptionTable()) {
    py::dict d;
    d["flag"] = entry.flag;
    d["keyword"] = entry.keyword;
    d["metavar"] = entry.metavar;
    d["help"] = entry.help;
    d["default"] = std::visit(
        [&](auto field) -> py::object {
          if constexpr (std::is_same_v<decltype(field), sfm::TrackerOption::Named>) {
            return py::cast(field.get(defaults));
          } else {
            return py::cast(field(defaults));
          }
        },
        entry.field);
    entries.append(d);
  }
  return entries;
}

std::vector<std::string> ReconstructOptionNames() {
  sfm::ReconstructionRunOptions options;
  bool quiet = true;
  std::vector<std::string> names;
  for (const auto& entry : ReconstructOptionTable(&options, &quiet)) names.push_back(entry.first);
  return names;
}

}  // namespace

void BindReconstruct(py::module_& m) {
  m.def("reconstruct", &Reconstruct, py::arg("frames"), py::arg("options"),
        py::arg("detector_options"), py::arg("callback"));
  m.def("read_reconstruction", &ReadReconstruction, py::arg("path"));
  m.def("reconstruct_option_names", &ReconstructOptionNames);
  m.def("run_option_table", &RunOptionEntries);
  m.def("tracker_option_table", &TrackerOptionEntries);
  py::class_<PyReconstruction>(m, "Reconstruction")
      .def_readonly("status", &PyReconstruction::status)
      .def_readonly("report_json", &PyReconstruction::report_json)
      .def_readonly("failure", &PyReconstruction::failure)
      .def_readonly("path", &PyReconstruction::path)
      .def("columns", [](const PyReconstruction& r) { return ModelToColumns(r.model); })
      .def("num_models", [](const PyReconstruction& r) { return r.models.size(); })
      .def("has_run", [](const PyReconstruction& r) { return r.run_result != nullptr; })
      .def("model", &ModelOf, py::arg("index"))
      .def("write_outputs", &WriteOutputs, py::arg("folder"), py::arg("model_format"),
           py::arg("ply_format"))
      .def("write_text",
           [](const PyReconstruction& r, const std::string& folder) {
             io::WriteColmapTextModel(r.model, folder);
           })
      .def("write_binary",
           [](const PyReconstruction& r, const std::string& folder) {
             io::WriteColmapBinaryModel(r.model, folder);
           })
      .def("write_ply", &WritePointCloud);
}

}  // namespace comic::python
