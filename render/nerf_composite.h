// A NeRF synthetic set (Blender renders of an object with exact cameras and an alpha channel, e.g.
// ../shared/data/nerf_synthetic_lego) composited over a background scene seen through the same
// cameras: the paper's "object against a varying background" with a real renderer's object. Each
// view's background is rendered with the view's camera (the set's world set into the scene's,
// `lift` metres above the ground), and the view is laid over it by its alpha:
//   images/       the composite (sensor effects applied)
//   masks/        the object (alpha >= 0.5)
//   boundaries/   the object's silhouette band, and the background's own occlusion boundaries
//                 where the object does not hide them
//   depth/        the background's depth; unknown on the object (NaN in PFM, 0 in a PNG)
//   ids/          the background's object ids; the object gets the next id
//   poses.txt, calib.txt, colmap/, scene.json as render/sequence_renderer.h writes them
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/lens.h"
#include "render/pose.h"
#include "render/scene_builder.h"
#include "render/sequence_renderer.h"

namespace comic::render {

struct NerfView {
  std::string image_path;  // RGBA PNG
  Pose cam_from_world;     // in the scene's world
};

struct NerfSet {
  Lens lens;
  std::vector<NerfView> views;
};

// Reads `folder`/transforms_<split>.json (camera_angle_x; per frame file_path and the 4x4
// camera-to-world in Blender's axes: x right, y up, z backwards; world z up) into OpenCV cameras
// in the scene's world (y up), the set's origin at (0, lift, 0). The image size is the first
// view's. Throws comic::Error: kNotFound, kInvalidData naming the file.
NerfSet ReadNerfSet(const std::string& folder, const std::string& split, double lift);

// Composites every view of `set` (at most `max_views`; 0: all) over `background` into `folder`.
SequenceRenderSummary RenderNerfComposite(const NerfSet& set, const BuiltScene& background,
                                          uint64_t seed, const SequenceRenderOptions& options,
                                          const std::string& folder, int max_views = 0,
                                          const RenderProgress& progress = {});

}  // namespace comic::render
