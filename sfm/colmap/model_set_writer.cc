#include "sfm/colmap/model_set_writer.h"

#include <optional>

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

std::vector<std::string> ModelSetFiles(const IncrementalReconstruction& mapping,
                                       const ModelSetWriteOptions& options) {
  std::vector<std::string> files;
  if (!HasModel(mapping.status)) return files;
  for (size_t k = 0; k <= mapping.other_models.size(); ++k) {
    const std::string sparse = "sparse/" + std::to_string(k);
    if (k == 0 && options.text)
      files.insert(files.end(), {"cameras.txt", "images.txt", "points3D.txt"});
    if (options.binary || k > 0) {
      const std::string extension = options.binary ? ".bin" : ".txt";
      for (const char* name : {"/cameras", "/images", "/points3D"}) {
        files.push_back(sparse + name + extension);
      }
    }
  }
  return files;
}

std::vector<const Reconstruction*> ModelsLargestFirst(const IncrementalReconstruction& mapping) {
  COMIC_CHECK(
      HasModel(mapping.status), kInvalidArgument,
      "write models: the run has no model (" << ReconstructionStatusName(mapping.status) << ")");
  std::vector<const Reconstruction*> models = {&mapping.reconstruction};
  for (const IncrementalModel& model : mapping.other_models)
    models.push_back(&model.reconstruction);
  return models;
}

io::ColmapTextModel ColmapModelForImages(const Reconstruction& model,
                                         const ModelSetWriteOptions& options) {
  // Copied only to be resized: a 5000-frame model is hundreds of MB.
  std::optional<Reconstruction> resized;
  if (options.width > 0 && options.height > 0) {
    resized = ResizedReconstruction(model, options.width, options.height);
  }
  return ToColmapTextModel(resized ? *resized : model);
}

std::vector<std::string> WriteModelSet(const IncrementalReconstruction& mapping,
                                       const std::string& folder,
                                       const ModelSetWriteOptions& options) {
  const std::vector<const Reconstruction*> models = ModelsLargestFirst(mapping);
  for (size_t k = 0; k < models.size(); ++k) {
    const io::ColmapTextModel model = ColmapModelForImages(*models[k], options);
    const std::string sparse = io::JoinPaths(folder, "sparse/" + std::to_string(k));
    if (k == 0 && options.text) io::WriteColmapTextModel(model, folder);
    if (options.binary) {
      io::WriteColmapBinaryModel(model, sparse);
    } else if (k > 0) {
      io::WriteColmapTextModel(model, sparse);
    }
  }
  return ModelSetFiles(mapping, options);
}

}  // namespace comic::sfm
