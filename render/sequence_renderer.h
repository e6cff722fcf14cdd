// Renders a built scene frame by frame into an output folder:
//   images/NNNNNN.png      the frames (8-bit BGR; sensor effects applied)
//   depth/NNNNNN.png|pfm   z at each pixel centre (io/image/depth_map.h: 16-bit mm or float m)
//   ids/NNNNNN.png         object id at each pixel centre (16-bit; 0 = sky)
//   boundaries/NNNNNN.png  occlusion-boundary band (255), occlusion_boundary.h
//   masks/NNNNNN.png       foreground objects (255): comic_sfm / comic_track_eval --masks
//   poses.txt, calib.txt, colmap/   the true cameras (truth_files.h)
//   scene.json             the scene as drawn (scene_builder.h: BuiltScene::resolved) + options
// The same scene, seed and options give the same bytes in every file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "render/occlusion_boundary.h"
#include "render/rasterizer.h"
#include "render/scene_builder.h"
#include "render/sensor.h"

namespace comic::render {

struct SequenceRenderOptions {
  RasterOptions raster;
  SensorOptions sensor;
  BoundaryOptions boundary;
  std::string depth_format = "png";  // "png" (16-bit millimetres) or "pfm" (float metres)
  bool write_depth = true;
  bool write_ids = true;
  bool write_boundaries = true;
  bool write_masks = true;

  // Throws comic::Error(kInvalidArgument) naming the field.
  void Check() const;
};

struct SequenceRenderSummary {
  int num_frames = 0;
  // CPU time of this thread: rendering (rasterising, shading, sensor, boundaries and masks) and
  // encoding/writing the files.
  double render_cpu_s = 0.0;
  double write_cpu_s = 0.0;
};

// Called after each frame with (frames done, frames in all).
using RenderProgress = std::function<void(int, int)>;

// One frame: the 8-bit image and its truth (the view at the frame's time; with motion blur the
// colour averages sub-frames around it, on the frames sensor.blur_every picks).
struct RenderedFrame {
  cv::Mat image;  // CV_8UC3
  RenderedView view;
  Pose cam_from_world;
  Scene scene;  // the scene at the frame's time: moving objects where they are then
};
RenderedFrame RenderFrame(const BuiltScene& built, const Rasterizer& rasterizer, uint64_t seed,
                          const SensorOptions& sensor, int frame);

// The per-frame files of one frame: images/NAME.png always; the others when `options` asks for
// them (depth in options.depth_format). The subfolders must exist (PrepareOutputFolder).
struct FrameOutputs {
  cv::Mat image;       // CV_8UC3
  cv::Mat depth;       // CV_32F metres
  cv::Mat ids;         // CV_16UC1
  cv::Mat boundaries;  // CV_8UC1
  cv::Mat masks;       // CV_8UC1
};
void WriteFrameOutputs(const std::string& folder, int frame, const FrameOutputs& outputs,
                       const SequenceRenderOptions& options);
// Creates `folder` and the subfolders `options` writes into.
void PrepareOutputFolder(const std::string& folder, const SequenceRenderOptions& options);
// The options as scene.json records them.
nlohmann::json RenderOptionsToJson(const SequenceRenderOptions& options);
// "000042.png" (or another extension): the name of frame 42's files.
std::string FrameFileName(int frame, const std::string& extension);

// Renders every frame of `built` into `folder` (created if missing). Throws comic::Error for bad
// options (kInvalidArgument) or a failed write (kIo).
SequenceRenderSummary RenderSequence(const BuiltScene& built, uint64_t seed,
                                     const SequenceRenderOptions& options,
                                     const std::string& folder,
                                     const RenderProgress& progress = {});

// CPU time of the calling thread in seconds.
double ThreadCpuSeconds();

}  // namespace comic::render
