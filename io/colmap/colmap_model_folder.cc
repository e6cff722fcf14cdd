#include "io/colmap/colmap_model_folder.h"

#include <optional>

#include "io/colmap/colmap_binary_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::io {

namespace {

bool HoldsModel(const std::string& folder, const std::string& extension) {
  for (const char* name : {"cameras", "images", "points3D"}) {
    if (!PathExists(JoinPaths(folder, name + extension))) return false;
  }
  return true;
}

std::optional<ColmapModelLocation> ModelIn(const std::string& folder) {
  if (!IsDirectory(folder)) return std::nullopt;
  if (HoldsModel(folder, ".bin")) return ColmapModelLocation{folder, true};
  if (HoldsModel(folder, ".txt")) return ColmapModelLocation{folder, false};
  return std::nullopt;
}

}  // namespace

ColmapModelLocation FindColmapModel(const std::string& path) {
  COMIC_CHECK(PathExists(path), kNotFound, path << ": no such file or folder");
  COMIC_CHECK(IsDirectory(path), kInvalidArgument,
              path << ": not a folder (a model is a folder of cameras, images and points3D)");
  if (const auto here = ModelIn(path)) return *here;
  if (const auto first = ModelIn(JoinPaths(path, "sparse/0"))) return *first;
  throw Error(ErrorKind::kNotFound,
              path +
                  ": no COLMAP model (cameras, images and points3D as .bin or .txt) in it or "
                  "in its sparse/0/");
}

ColmapTextModel ReadColmapModel(const std::string& path) {
  const ColmapModelLocation location = FindColmapModel(path);
  return location.binary ? ReadColmapBinaryModel(location.folder)
                         : ReadColmapTextModel(location.folder);
}

}  // namespace comic::io
