// A COLMAP model wherever it is in a folder, text or binary, as pycolmap.Reconstruction(path)
// reads one: the folder itself when it holds a model (binary preferred when it holds both, as
// COLMAP's Reconstruction::Read), else its sparse/0/ (comic_sfm's binary model, COLMAP's first
// model) — so comic_sfm's --output, a COLMAP sparse/0 and a converted text model all open.
#pragma once

#include <string>

#include "io/colmap/colmap_text_model.h"

namespace comic::io {

struct ColmapModelLocation {
  std::string folder;   // holding cameras, images and points3D
  bool binary = false;  // .bin files (else .txt)
};

// Where the model in `path` is. Throws comic::Error: kNotFound naming `path` when neither it nor
// its sparse/0/ holds a model's three files.
ColmapModelLocation FindColmapModel(const std::string& path);

// The model FindColmapModel finds, read. Throws as FindColmapModel, ReadColmapTextModel and
// ReadColmapBinaryModel do.
ColmapTextModel ReadColmapModel(const std::string& path);

}  // namespace comic::io
