// comic_render: renders a scene file (render/scene_builder.h) with textures cut from the given
// photographs into frames plus exact truth (render/sequence_renderer.h). Flags -> options ->
// BuildScene -> RenderSequence into a staged output folder.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "apps/common/arg_parser.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/list_flags.h"
#include "apps/common/progress_line.h"
#include "apps/common/shared_flags.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/pixel_budget.h"
#include "io/core/protected_inputs.h"
#include "io/core/staged_folder.h"
#include "io/image/image_io.h"
#include "render/nerf_composite.h"
#include "render/scene_builder.h"
#include "render/sequence_renderer.h"
#include "render/stereo_pair.h"

namespace {

namespace io = comic::io;
namespace render = comic::render;

// Pairs are spread over the frames, at most one per frame of the longest scene.
constexpr int kMaxStereoPairs = 100000;

// The camera's pixels per frame against --max-pixels, in the scene's words.
void CheckCameraPixels(const std::string& scene_file, const render::Lens& lens,
                       int64_t max_pixels) {
  const int64_t pixels = static_cast<int64_t>(lens.width) * lens.height;
  COMIC_CHECK(pixels <= max_pixels, kInvalidData,
              scene_file << ": \"camera\": " << lens.width << "x" << lens.height << " = " << pixels
                         << " pixels per frame exceeds the budget of " << max_pixels
                         << "; raise it with --max-pixels " << pixels);
}

// Each entry of --photos: an image file, or a folder whose images are all taken (sorted).
std::vector<std::string> ExpandPhotos(const std::string& list) {
  std::vector<std::string> photos;
  for (const std::string& entry : comic::apps::SplitList(list, "photos")) {
    if (!io::IsDirectory(entry)) {
      photos.push_back(entry);
      continue;
    }
    for (const std::string& name : io::ListFiles(entry)) {
      if (io::IsImageExtension(io::FileExtension(name)))
        photos.push_back(io::JoinPaths(entry, name));
    }
  }
  COMIC_CHECK(!photos.empty(), kInvalidArgument, "--photos: no images in '" << list << "'");
  return photos;
}

int Run(int argc, char** argv) {
  std::string scene_file;
  std::string photos;
  std::string out_dir = "render_out";
  int seed = 1;
  bool quiet = false;
  bool no_truth_images = false;
  int stereo_pairs = 0;
  int max_pixels = static_cast<int>(io::kDefaultMaxPixels);
  std::string nerf;
  double nerf_lift = 1.0;
  render::StereoPairOptions stereo;
  render::SceneBuildOptions build;
  render::SequenceRenderOptions options;
  comic::apps::ArgParser parser(
      "comic_render", "SCENE.json --photos IMAGES [options]",
      "Renders a scene of textured planar pieces (ground, facades, boxes, poles, trees, fences,\n"
      "a distant backdrop) along its camera path, with textures cut from the photographs given,\n"
      "and writes the frames with their exact truth: images/, depth/, ids/, boundaries/, masks/,\n"
      "poses.txt + calib.txt (KITTI), colmap/ (the true cameras) and scene.json.");
  parser.AddPositional("SCENE", "scene file (JSON; docs/rendering.md)", &scene_file);
  parser.AddOption("photos", "LIST",
                   "comma-separated photographs (or folders of them) to cut textures from",
                   &photos);
  parser.AddOption("seed", "N", "draws positions, sizes, textures, shake and noise", &seed);
  comic::apps::AddMaxPixelsFlag(parser, &max_pixels);
  parser.AddOption("frames", "N", "frames to render (0: the scene file's)", &build.num_frames);
  comic::apps::AddOutputFolderFlag(parser, &out_dir);
  parser.AddOption("supersampling", "N", "samples per pixel along each axis (1-8)",
                   &options.raster.supersampling);
  parser.AddOption("noise", "SIGMA", "read noise (grey levels)", &options.sensor.read_noise);
  parser.AddOption("shot-noise", "K", "shot noise: variance per grey level",
                   &options.sensor.shot_noise);
  parser.AddOption("exposure-drift", "A", "exposure gain wanders within exp(+-A)",
                   &options.sensor.exposure_drift);
  parser.AddOption("exposure-period", "F", "frames between the exposure drift's knots",
                   &options.sensor.exposure_period);
  parser.AddOption("shutter", "F",
                   "motion blur: shutter open for this fraction of the frame interval (0: none)",
                   &options.sensor.shutter);
  parser.AddOption("blur-samples", "N", "sub-frames averaged for motion blur",
                   &options.sensor.blur_samples);
  parser.AddOption("blur-every", "N",
                   "blur only every Nth frame (index % N == N-1), the others sharp (1: all)",
                   &options.sensor.blur_every);
  parser.AddOption("depth-format", "F", "png (16-bit millimetres, saturates at 65.5 m) or pfm",
                   &options.depth_format);
  parser.AddOption("occlusion-band", "PX",
                   "boundaries/: pixels within PX of a pixel touching a depth discontinuity",
                   &options.boundary.band_px);
  parser.AddOption("occlusion-depth-ratio", "R",
                   "boundaries/: relative depth jump (each plane extended) that makes one",
                   &options.boundary.depth_ratio);
  parser.AddOption("max-texture-size", "PX", "photographs are shrunk to this longer side",
                   &build.max_texture_size);
  parser.AddFlag("frames-only",
                 "write the frames and the cameras only (no depth, ids, boundaries, masks)",
                 &no_truth_images);
  parser.AddOption("stereo-pairs", "N",
                   "also write N rectified pairs (frames evenly spread) as Middlebury folders "
                   "stereo/NNNNNN/ for comic_stereo_eval --middlebury",
                   &stereo_pairs);
  parser.AddOption("stereo-baseline", "M", "right camera this far to the left one's right",
                   &stereo.baseline);
  parser.AddOption("nerf", "DIR",
                   "composite the views of a NeRF synthetic set (transforms_train.json, RGBA "
                   "views) over SCENE seen through the same cameras, instead of SCENE's path",
                   &nerf);
  parser.AddOption("nerf-lift", "M", "the NeRF set's origin this far above the ground", &nerf_lift);
  comic::apps::AddQuietFlag(parser, &quiet);
  parser.AddEpilog(
      "Example (a short drive textured with the bundled KITTI frames):\n"
      "  comic_render scenes/test_street.json --photos examples/data/kitti06_000-011/image_l \\\n"
      "      --frames 20 -o out/street\n"
      "  comic_sfm out/street/images --gt out/street/poses.txt --masks out/street/masks\n"
      "Same scene, photographs, seed and options: the same bytes. Timing (CPU seconds of the\n"
      "rendering thread) is printed at the end.");
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  COMIC_CHECK(seed >= 0, kInvalidArgument, "--seed must be >= 0, got " << seed);
  COMIC_CHECK(!photos.empty(), kInvalidArgument,
              "--photos is required: the photographs to cut textures from");
  if (no_truth_images) {
    options.write_depth = options.write_ids = options.write_boundaries = options.write_masks =
        false;
  }
  options.Check();
  build.Check();
  io::CheckMaxPixels(max_pixels);
  COMIC_CHECK(stereo_pairs >= 0 && stereo_pairs <= kMaxStereoPairs, kInvalidArgument,
              "--stereo-pairs must be in [0, " << kMaxStereoPairs << "], got " << stereo_pairs);
  stereo.boundary.depth_ratio = options.boundary.depth_ratio;
  stereo.Check();
  std::vector<io::NamedPath> inputs = {{"SCENE", scene_file}, {"--nerf", nerf}};
  for (const std::string& entry : comic::apps::SplitList(photos, "photos")) {
    inputs.push_back({"--photos", entry});
  }
  io::CheckOutputFolderAvoidsInputs({"--output", out_dir}, inputs);
  io::CheckCreatableFolder(out_dir);  // before the photographs are read

  const render::BuiltScene built =
      render::BuildScene(scene_file, ExpandPhotos(photos), static_cast<uint64_t>(seed), build);
  CheckCameraPixels(scene_file, built.lens, max_pixels);
  io::StagedFolder out(out_dir);
  comic::apps::ProgressLine progress("comic_render: " + built.name, quiet);
  const auto update = [&](int done, int total) { progress.Update(done, total); };
  render::SequenceRenderSummary summary;
  cv::Size size(built.lens.width, built.lens.height);
  if (!nerf.empty()) {
    COMIC_CHECK(stereo_pairs == 0, kInvalidArgument,
                "--stereo-pairs and --nerf exclude each other");
    const render::NerfSet set = render::ReadNerfSet(nerf, "train", nerf_lift);
    size = cv::Size(set.lens.width, set.lens.height);
    summary = render::RenderNerfComposite(set, built, static_cast<uint64_t>(seed), options,
                                          out.path(), build.num_frames, update);
  } else {
    summary =
        render::RenderSequence(built, static_cast<uint64_t>(seed), options, out.path(), update);
  }
  if (stereo_pairs > 0) {
    const render::Rasterizer rasterizer(built.lens, options.raster);
    for (int k = 0; k < stereo_pairs; ++k) {
      // The middle frames of N equal parts of the sequence.
      const int frame = built.num_frames * (2 * k + 1) / (2 * stereo_pairs);
      char name[32];
      std::snprintf(name, sizeof(name), "stereo/%06d", frame);
      render::WriteStereoPair(built, rasterizer, static_cast<uint64_t>(seed), options.sensor, frame,
                              stereo, io::JoinPaths(out.path(), name));
    }
  }
  out.Commit();
  std::cout << "comic_render: " << summary.num_frames << " frames " << size.width << "x"
            << size.height << " of " << built.name << " (" << built.scene.pieces.size()
            << " pieces) in " << out_dir << "; CPU " << summary.render_cpu_s << " s rendering ("
            << summary.num_frames / std::max(1e-9, summary.render_cpu_s) << " frames/s), "
            << summary.write_cpu_s << " s writing" << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_render", [&] { return Run(argc, argv); });
}
