#include "sfm/colmap/model_set_writer.h"

#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

std::vector<std::string> WriteModelSet(const IncrementalReconstruction& mapping,
                                       const std::string& folder,
                                       const ModelSetWriteOptions& options) {
  COMIC_CHECK(
      HasModel(mapping.status), kInvalidArgument,
      "write models: the run has no model (" << ReconstructionStatusName(mapping.status) << ")");
  std::vector<const Reconstruction*> models = {&mapping.reconstruction};
  for (const IncrementalModel& model : mapping.other_models)
    models.push_back(&model.reconstruction);
  std::vector<std::string> written;
  for (size_t k = 0; k < models.size(); ++k) {
    const Reconstruction resized =
        options.width > 0 && options.height > 0
            ? ResizedReconstruction(*models[k], options.width, options.height)
            : *models[k];
    const io::ColmapTextModel model = ToColmapTextModel(resized);
    const std::string sparse = "sparse/" + std::to_string(k);
    if (k == 0 && options.text) {
      io::WriteColmapTextModel(model, folder);
      written.insert(written.end(), {"cameras.txt", "images.txt", "points3D.txt"});
    }
    if (options.binary) {
      io::WriteColmapBinaryModel(model, io::JoinPaths(folder, sparse));
      for (const char* file : {"/cameras.bin", "/images.bin", "/points3D.bin"}) {
        written.push_back(sparse + file);
      }
    } else if (k > 0) {
      io::WriteColmapTextModel(model, io::JoinPaths(folder, sparse));
      for (const char* file : {"/cameras.txt", "/images.txt", "/points3D.txt"}) {
        written.push_back(sparse + file);
      }
    }
  }
  return written;
}

}  // namespace comic::sfm
