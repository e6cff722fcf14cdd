#include "python/distributed_binding.h"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "io/colmap/colmap_model_folder.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_sequence.h"
#include "io/report/html_page.h"
#include "sfm/chunk_model_merging.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/run/distributed_run_page.h"

namespace py = pybind11;

namespace comic::python {
namespace {

// A chunk's model read from its folder, each frame's name prefixed (clips of one run may name
// their frames alike; a prefix per clip keeps them apart).
sfm::Reconstruction ReadChunk(const std::string& path, const std::string& name_prefix) {
  sfm::Reconstruction chunk = sfm::FromColmapTextModel(io::ReadColmapModel(path));
  std::vector<sfm::image_t> ids;
  for (const auto& [id, image] : chunk.images()) ids.push_back(id);
  for (sfm::image_t id : ids) chunk.image(id).name = name_prefix + chunk.image(id).name;
  return chunk;
}

py::dict OutcomeToPython(const sfm::ChunkMergeOutcome& outcome) {
  py::dict result;
  result["model_index"] = outcome.model_index;
  result["started_model"] = outcome.started_model;
  result["num_shared_frames"] = outcome.num_shared_frames;
  result["num_point_pairs"] = outcome.num_point_pairs;
  result["num_inliers"] = outcome.num_inliers;
  result["scale"] = outcome.model_from_chunk.scale;
  result["reason"] = outcome.reason;
  return result;
}

// Merges the chunks' models (folders, in sequence order) and writes model k as COLMAP text into
// output/k. Returns {"chunks": [...], "models": [{"num_images", "num_points3D", "path"}],
// "adjustments": [{"final_rmse_px", ...}]}.
py::dict MergeChunkModels(const std::vector<std::string>& paths,
                          const std::vector<std::string>& name_prefixes, const std::string& output,
                          int global_ba_max_images) {
  COMIC_CHECK(name_prefixes.empty() || name_prefixes.size() == paths.size(), kInvalidArgument,
              "merge_chunk_models: " << name_prefixes.size() << " name prefixes for "
                                     << paths.size() << " chunks");
  std::vector<sfm::Reconstruction> chunks;
  for (size_t i = 0; i < paths.size(); ++i) {
    chunks.push_back(ReadChunk(paths[i], name_prefixes.empty() ? "" : name_prefixes[i]));
  }
  sfm::ChunkMergingOptions options;
  options.global_ba_max_images = global_ba_max_images;
  sfm::ChunkMergingResult merged;
  {
    py::gil_scoped_release release;
    merged = sfm::MergeChunkModels(chunks, options);
  }
  py::dict result;
  py::list outcomes, models, adjustments;
  for (const sfm::ChunkMergeOutcome& outcome : merged.chunks) {
    outcomes.append(OutcomeToPython(outcome));
  }
  for (size_t k = 0; k < merged.models.size(); ++k) {
    const std::string folder = io::JoinPaths(output, std::to_string(k));
    io::WriteColmapTextModel(sfm::ToColmapTextModel(merged.models[k]), folder);
    py::dict model;
    model["num_images"] = merged.models[k].NumRegisteredImages();
    model["num_points3D"] = merged.models[k].NumPoints3D();
    model["path"] = folder;
    models.append(model);
  }
  for (const sfm::BundleAdjustmentSummary& summary : merged.adjustments) {
    py::dict adjustment;
    adjustment["usable"] = summary.usable;
    adjustment["num_images"] = summary.num_images;
    adjustment["initial_rmse_px"] = summary.initial_rmse_px;
    adjustment["final_rmse_px"] = summary.final_rmse_px;
    adjustments.append(adjustment);
  }
  result["chunks"] = outcomes;
  result["models"] = models;
  result["adjustments"] = adjustments;
  return result;
}

}  // namespace

void BindDistributed(py::module_& module) {
  // The names of the frames comic_sfm would read from `path` (a folder, naturally sorted, or a
  // video's frame_%06d.png), in order: frame i is --first i.
  module.def(
      "frame_names",
      [](const std::string& path) { return io::ImageSequence::Open(path).FrameNames(); },
      py::arg("path"));
  // report.html of the run from its report.json's text (sfm/run/distributed_run_page.h), written
  // atomically as comic_sfm writes its page.
  module.def(
      "write_distributed_run_page",
      [](const std::string& path, const std::string& report_json) {
        nlohmann::json report;
        try {
          report = nlohmann::json::parse(report_json);
        } catch (const nlohmann::json::exception& e) {
          COMIC_CHECK(false, kInvalidArgument,
                      "write_distributed_run_page: report_json is not JSON: " << e.what());
        }
        io::WriteHtmlPage(path, sfm::DistributedRunPage(report));
      },
      py::arg("path"), py::arg("report_json"));
  module.def("merge_chunk_models", &MergeChunkModels, py::arg("paths"), py::arg("name_prefixes"),
             py::arg("output"), py::arg("global_ba_max_images"));
}

}  // namespace comic::python
