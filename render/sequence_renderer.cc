#include "render/sequence_renderer.h"

#include <cstdio>
#include <ctime>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/depth_map.h"
#include "render/random.h"
#include "render/truth_files.h"

namespace comic::render {
namespace {

enum SequenceStream : uint64_t { kSensorSeed = 2 };

}  // namespace

std::string FrameFileName(int frame, const std::string& extension) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06d.%s", frame, extension.c_str());
  return name;
}

nlohmann::json RenderOptionsToJson(const SequenceRenderOptions& o) {
  return {{"supersampling", o.raster.supersampling},
          {"near_plane", o.raster.near_plane},
          {"read_noise", o.sensor.read_noise},
          {"shot_noise", o.sensor.shot_noise},
          {"exposure_drift", o.sensor.exposure_drift},
          {"exposure_period", o.sensor.exposure_period},
          {"shutter", o.sensor.shutter},
          {"blur_samples", o.sensor.blur_samples},
          {"blur_every", o.sensor.blur_every},
          {"boundary_depth_ratio", o.boundary.depth_ratio},
          {"boundary_band_px", o.boundary.band_px},
          {"depth_format", o.depth_format}};
}

void PrepareOutputFolder(const std::string& folder, const SequenceRenderOptions& options) {
  io::EnsureWritableDirectory(folder);
  std::vector<std::string> subfolders = {"images"};
  if (options.write_depth) subfolders.push_back("depth");
  if (options.write_ids) subfolders.push_back("ids");
  if (options.write_boundaries) subfolders.push_back("boundaries");
  if (options.write_masks) subfolders.push_back("masks");
  for (const std::string& sub : subfolders) io::EnsureWritableDirectory(io::JoinPaths(folder, sub));
}

void WriteFrameOutputs(const std::string& folder, int frame, const FrameOutputs& outputs,
                       const SequenceRenderOptions& options) {
  const std::string png = FrameFileName(frame, "png");
  io::WriteImageAtomically(io::JoinPaths(folder, "images/" + png), outputs.image);
  if (options.write_depth) {
    io::WriteDepthMap(io::JoinPaths(folder, "depth/" + FrameFileName(frame, options.depth_format)),
                      outputs.depth);
  }
  if (options.write_ids) io::WriteImageAtomically(io::JoinPaths(folder, "ids/" + png), outputs.ids);
  if (options.write_boundaries) {
    io::WriteImageAtomically(io::JoinPaths(folder, "boundaries/" + png), outputs.boundaries);
  }
  if (options.write_masks) {
    io::WriteImageAtomically(io::JoinPaths(folder, "masks/" + png), outputs.masks);
  }
}

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

void SequenceRenderOptions::Check() const {
  raster.Check();
  sensor.Check();
  boundary.Check();
  COMIC_CHECK(depth_format == "png" || depth_format == "pfm", kInvalidArgument,
              "depth format must be png (16-bit millimetres) or pfm (float metres), got '"
                  << depth_format << "'");
}

RenderedFrame RenderFrame(const BuiltScene& built, const Rasterizer& rasterizer, uint64_t seed,
                          const SensorOptions& sensor, int frame) {
  RenderedFrame out;
  out.cam_from_world = built.path.At(frame);
  out.scene = built.scene.At(frame);
  out.view = rasterizer.Render(out.scene, out.cam_from_world);
  cv::Mat color = out.view.color;
  const double shutter = sensor.ShutterOf(frame);
  if (shutter > 0.0) {
    // Sub-frames spread over the open shutter, centred on the frame's time; the camera and the
    // moving objects both where they are at each.
    color = cv::Mat::zeros(color.size(), color.type());
    for (int k = 0; k < sensor.blur_samples; ++k) {
      const double time =
          frame + shutter * (static_cast<double>(k) / (sensor.blur_samples - 1) - 0.5);
      color += rasterizer.RenderColor(built.scene.At(time), built.path.At(time));
    }
    color /= static_cast<double>(sensor.blur_samples);
  }
  out.image = ExposeFrame(color, sensor, MixSeed(seed, kSensorSeed), frame);
  return out;
}

SequenceRenderSummary RenderSequence(const BuiltScene& built, uint64_t seed,
                                     const SequenceRenderOptions& options,
                                     const std::string& folder, const RenderProgress& progress) {
  options.Check();
  const Rasterizer rasterizer(built.lens, options.raster);
  PrepareOutputFolder(folder, options);
  SequenceRenderSummary summary;
  std::vector<Pose> poses;
  std::vector<std::string> names;
  for (int frame = 0; frame < built.num_frames; ++frame) {
    const double start = ThreadCpuSeconds();
    const RenderedFrame rendered = RenderFrame(built, rasterizer, seed, options.sensor, frame);
    FrameOutputs outputs;
    outputs.image = rendered.image;
    outputs.depth = rendered.view.depth;
    if (options.write_boundaries) {
      outputs.boundaries = OcclusionBoundaryMask(rendered.scene, rendered.cam_from_world,
                                                 rasterizer, rendered.view, options.boundary);
    }
    if (options.write_masks) outputs.masks = ForegroundMask(rendered.scene, rendered.view);
    if (options.write_ids) outputs.ids = ObjectIds(rendered.scene, rendered.view);
    const double rendered_at = ThreadCpuSeconds();
    summary.render_cpu_s += rendered_at - start;
    WriteFrameOutputs(folder, frame, outputs, options);
    summary.write_cpu_s += ThreadCpuSeconds() - rendered_at;
    poses.push_back(rendered.cam_from_world);
    names.push_back(FrameFileName(frame, "png"));
    ++summary.num_frames;
    if (progress) progress(summary.num_frames, built.num_frames);
  }
  WriteTrueCameras(folder, built.lens, poses, names);
  nlohmann::json scene = built.resolved;
  scene["render_options"] = RenderOptionsToJson(options);
  scene["camera"] = {{"model", built.lens.ColmapModelName()},
                     {"width", built.lens.width},
                     {"height", built.lens.height},
                     {"params_opencv_convention",
                      {built.lens.fx, built.lens.fy, built.lens.cx, built.lens.cy, built.lens.k1,
                       built.lens.k2, built.lens.p1, built.lens.p2}}};
  io::WriteFileAtomically(io::JoinPaths(folder, "scene.json"), scene.dump(1) + "\n");
  return summary;
}

}  // namespace comic::render
