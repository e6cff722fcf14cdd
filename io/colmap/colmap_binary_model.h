// COLMAP's binary model format (cameras.bin, images.bin, points3D.bin), the layout COLMAP itself
// writes by default and that pycolmap, nerfstudio and the Gaussian-splatting tools read from
// sparse/0/. Same structs and conventions as the text model (io/colmap/colmap_text_model.h): COLMAP
// pixel convention, cam_from_world poses, ids from 1; doubles are stored exactly.
//
// Layout (COLMAP 3.8, src/base/reconstruction.cc), every number little-endian:
//   cameras.bin   uint64 count; per camera: uint32 camera_id, int32 model_id, uint64 width,
//                 uint64 height, double params[n(model)]
//   images.bin    uint64 count; per image: uint32 image_id, double qw qx qy qz, double tx ty tz,
//                 uint32 camera_id, name bytes + '\0', uint64 num_points2D,
//                 per point: double x, double y, uint64 point3D_id (2^64 - 1: none)
//   points3D.bin  uint64 count; per point: uint64 point3D_id, double x y z, uint8 r g b,
//                 double error, uint64 track_length, per element: uint32 image_id, point2D_idx
#pragma once

#include <iosfwd>
#include <string>

#include "io/colmap/colmap_text_model.h"

namespace comic::io {

// COLMAP's numeric id of a camera model name ("PINHOLE" -> 1) and its number of parameters;
// throws comic::Error(kInvalidArgument) for a name COLMAP does not know.
int ColmapCameraModelId(const std::string& model_name);
int ColmapCameraModelNumParams(const std::string& model_name);

// The three files' bytes, streamed (what WriteColmapBinaryModel writes). Check the model first;
// a camera whose parameter count does not match its model throws comic::Error(kInvalidData).
void WriteColmapCamerasBinary(const ColmapTextModel& model, std::ostream& out);
void WriteColmapImagesBinary(const ColmapTextModel& model, std::ostream& out);
void WriteColmapPoints3DBinary(const ColmapTextModel& model, std::ostream& out);

// The same as strings.
std::string ColmapCamerasBinary(const ColmapTextModel& model);
std::string ColmapImagesBinary(const ColmapTextModel& model);
std::string ColmapPoints3DBinary(const ColmapTextModel& model);

// Writes cameras.bin, images.bin and points3D.bin into `folder` (created if needed) after
// checking the model: streamed, and all three written before any replaces an old file
// (io::WriteFilesAtomically), so an error while writing leaves the old model whole.
void WriteColmapBinaryModel(const ColmapTextModel& model, const std::string& folder);

// Reads the three files from `folder`. Throws comic::Error naming the file: kNotFound for a
// missing file, kInvalidData for a truncated or malformed one (an unknown camera model, a count
// larger than the file can hold, bytes left over) or a model failing ColmapTextModel::Check().
ColmapTextModel ReadColmapBinaryModel(const std::string& folder);

}  // namespace comic::io
