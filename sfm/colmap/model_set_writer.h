// Writing every model of a run (issue 30): COLMAP's layout, sparse/0 the largest, sparse/1, ...
// as COLMAP's mapper numbers its models, and the largest also as a text model at the top of the
// folder (cameras.txt, images.txt, points3D.txt), where comic_sfm has always put it.
//
//   ModelSetWriteOptions options;                   // text at the top, binary in sparse/<k>/
//   options.width = 3072; options.height = 2048;    // the input's pixels
//   const std::vector<std::string> written = WriteModelSet(run.mapping, "out", options);
#pragma once

#include <string>
#include <vector>

#include "io/colmap/colmap_text_model.h"
#include "sfm/incremental_pipeline.h"

namespace comic::sfm {

struct ModelSetWriteOptions {
  // The largest model as text at the top of the folder.
  bool text = true;
  // Every model as binary in sparse/<k>/; when off, the models other than the largest go to
  // sparse/<k>/ as text.
  bool binary = true;
  // The models are written for images of this size (their cameras and 2-D points scaled; 0: as
  // they are).
  int width = 0;
  int height = 0;
};

// Every model of `mapping` (HasModel(mapping.status) must hold), in the order written: the largest,
// then the others largest first.
std::vector<const Reconstruction*> ModelsLargestFirst(const IncrementalReconstruction& mapping);

// `model` as a COLMAP model for images of options.width x options.height (as written; 0: as it
// is), what WriteModelSet writes for it and what the Python module hands out.
io::ColmapTextModel ColmapModelForImages(const Reconstruction& model,
                                         const ModelSetWriteOptions& options);

// The files WriteModelSet writes for `mapping`, relative to the folder, in its order.
std::vector<std::string> ModelSetFiles(const IncrementalReconstruction& mapping,
                                       const ModelSetWriteOptions& options);

// Writes the models of `mapping` (HasModel(mapping.status) must hold) into `folder` and returns
// the files written, relative to it (ModelSetFiles). Throws comic::Error(kIo) when a file cannot
// be written.
std::vector<std::string> WriteModelSet(const IncrementalReconstruction& mapping,
                                       const std::string& folder,
                                       const ModelSetWriteOptions& options);

}  // namespace comic::sfm
