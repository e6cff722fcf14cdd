#include "python/export_binding.h"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "frontend/matching/pairing.h"
#include "python/detector_keywords.h"
#include "python/keyword_options.h"
#include "python/run_keywords.h"
#include "sfm/run/colmap_export_run.h"

namespace comic::python {
namespace {

// comic.export_colmap: comic_export_colmap's run (sfm/run/colmap_export_run.h).
py::dict ExportColmap(const std::string& frames, const std::string& colmap_db,
                      const py::dict& options, const py::dict& detector_options) {
  sfm::ColmapExportRunOptions run;
  run.frames = frames;
  run.colmap.colmap_db = colmap_db;
  bool quiet = true;
  ApplyOptions(options, ExportOptionTable(&run, &quiet), "export_colmap");
  run.Check();
  if (!detector_options.empty()) {
    run.detector_options = MakeDetectorOptions(run.detector, detector_options, DetectorDoor::kRun);
  }
  sfm::ColmapExportRunResult result;
  {
    py::gil_scoped_release release;
    result = sfm::RunColmapExport(run);
  }
  if (!quiet) {
    for (const std::string& line : sfm::ColmapExportReportLines(run, result)) py::print(line);
  }
  const sfm::ColmapExportSummary& summary = result.summary;
  py::dict out;
  out["num_images"] = summary.num_images;
  out["num_keypoints"] = summary.num_keypoints;
  out["num_matched_pairs"] = summary.num_matched_pairs;
  out["num_verified_pairs"] = summary.num_verified_pairs;
  out["num_matches"] = summary.num_matches;
  out["num_inlier_matches"] = summary.num_inlier_matches;
  out["known_intrinsics"] = summary.known_intrinsics;
  out["num_tracks"] = result.num_tracks;
  out["num_observations"] = result.num_observations;
  out["matching"] = frontend::PairingName(result.pairing.chosen);
  out["frames_folder"] = result.frames_folder;
  out["image_path"] = result.image_path;
  out["mapper_command"] = result.mapper_command;
  return out;
}

std::vector<std::string> ExportOptionNames() {
  sfm::ColmapExportRunOptions options;
  bool quiet = true;
  std::vector<std::string> names;
  for (const auto& entry : ExportOptionTable(&options, &quiet)) names.push_back(entry.first);
  return names;
}

}  // namespace

void BindExportColmap(py::module_& m) {
  m.def("export_colmap", &ExportColmap, py::arg("frames"), py::arg("colmap_db"), py::arg("options"),
        py::arg("detector_options"));
  m.def("export_colmap_option_names", &ExportOptionNames);
}

}  // namespace comic::python
