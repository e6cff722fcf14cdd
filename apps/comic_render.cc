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

// The command line, bound to the parser by AddFlags; Check() validates it.
struct Flags {
  void Check();

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
};

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("SCENE", "scene file (JSON; docs/rendering.md)", &flags.scene_file);
  parser.AddOption("photos", "LIST",
                   "comma-separated photographs (or folders of them) to cut textures from",
                   &flags.photos);
  parser.AddOption("seed", "N", "draws positions, sizes, textures, shake and noise", &flags.seed);
  comic::apps::AddMaxPixelsFlag(parser, &flags.max_pixels);
  parser.AddOption("frames", "N", "frames to render (0: the scene file's)",
                   &flags.build.num_frames);
  comic::apps::AddOutputFolderFlag(parser, &flags.out_dir);
  parser.AddOption("supersampling", "N", "samples per pixel along each axis (1-8)",
                   &flags.options.raster.supersampling);
  parser.AddOption("noise", "SIGMA", "read noise (grey levels)", &flags.options.sensor.read_noise);
  parser.AddOption("shot-noise", "K", "shot noise: variance per grey level",
                   &flags.options.sensor.shot_noise);
  parser.AddOption("exposure-drift", "A", "exposure gain wanders within exp(+-A)",
                   &flags.options.sensor.exposure_drift);
  parser.AddOption("exposure-period", "F", "frames between the exposure drift's knots",
                   &flags.options.sensor.exposure_period);
  parser.AddOption("shutter", "F",
                   "motion blur: shutter open for this fraction of the frame interval (0: none)",
                   &flags.options.sensor.shutter);
  parser.AddOption("blur-samples", "N", "sub-frames averaged for motion blur",
                   &flags.options.sensor.blur_samples);
  parser.AddOption("blur-every", "N",
                   "blur only every Nth frame (index % N == N-1), the others sharp (1: all)",
                   &flags.options.sensor.blur_every);
  parser.AddOption("depth-format", "F", "png (16-bit millimetres, saturates at 65.5 m) or pfm",
                   &flags.options.depth_format);
  parser.AddOption("occlusion-band", "PX",
                   "boundaries/: pixels within PX of a pixel touching a depth discontinuity",
                   &flags.options.boundary.band_px);
  parser.AddOption("occlusion-depth-ratio", "R",
                   "boundaries/: relative depth jump (each plane extended) that makes one",
                   &flags.options.boundary.depth_ratio);
  parser.AddOption("max-texture-size", "PX", "photographs are shrunk to this longer side",
                   &flags.build.max_texture_size);
  parser.AddFlag("frames-only",
                 "write the frames and the cameras only (no depth, ids, boundaries, masks)",
                 &flags.no_truth_images);
  parser.AddOption("stereo-pairs", "N",
                   "also write N rectified pairs (frames evenly spread) as Middlebury folders "
                   "stereo/NNNNNN/ for comic_stereo_eval --middlebury",
                   &flags.stereo_pairs);
  parser.AddOption("stereo-baseline", "M", "right camera this far to the left one's right",
                   &flags.stereo.baseline);
  parser.AddOption("nerf", "DIR",
                   "composite the views of a NeRF synthetic set (transforms_train.json, RGBA "
                   "views) over SCENE seen through the same cameras, instead of SCENE's path",
                   &flags.nerf);
  parser.AddOption("nerf-lift", "M", "the NeRF set's origin this far above the ground",
                   &flags.nerf_lift);
  comic::apps::AddQuietFlag(parser, &flags.quiet);
  parser.AddEpilog(
      "Example (a short drive textured with the bundled KITTI frames):\n"
      "  comic_render scenes/test_street.json --photos examples/data/kitti06_000-011/image_l \\\n"
      "      --frames 20 -o out/street\n"
      "  comic_sfm out/street/images --gt out/street/poses.txt --masks out/street/masks\n"
      "Same scene, photographs, seed and options: the same bytes. Timing (CPU seconds of the\n"
      "rendering thread) is printed at the end.");
}

void Flags::Check() {
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
}

// Renders the scene's frames (or, with --nerf, the NeRF set's views composited over the scene)
// into `folder`; `size` is set to the frames' size.
render::SequenceRenderSummary RenderFrames(const Flags& flags, const render::BuiltScene& built,
                                           const std::string& folder,
                                           comic::apps::ProgressLine& progress, cv::Size& size) {
  const auto update = [&](int done, int total) { progress.Update(done, total); };
  render::SequenceRenderSummary summary;
  size = cv::Size(built.lens.width, built.lens.height);
  if (!flags.nerf.empty()) {
    COMIC_CHECK(flags.stereo_pairs == 0, kInvalidArgument,
                "--stereo-pairs and --nerf exclude each other");
    const render::NerfSet set = render::ReadNerfSet(flags.nerf, "train", flags.nerf_lift);
    size = cv::Size(set.lens.width, set.lens.height);
    summary = render::RenderNerfComposite(set, built, static_cast<uint64_t>(flags.seed),
                                          flags.options, folder, flags.build.num_frames, update);
  } else {
    summary = render::RenderSequence(built, static_cast<uint64_t>(flags.seed), flags.options,
                                     folder, update);
  }
  return summary;
}

// --stereo-pairs rectified pairs as Middlebury folders stereo/NNNNNN/ in `folder`.
void WriteStereoPairs(const Flags& flags, const render::BuiltScene& built,
                      const std::string& folder) {
  const render::Rasterizer rasterizer(built.lens, flags.options.raster);
  for (int k = 0; k < flags.stereo_pairs; ++k) {
    // The middle frames of N equal parts of the sequence.
    const int frame = built.num_frames * (2 * k + 1) / (2 * flags.stereo_pairs);
    char name[32];
    std::snprintf(name, sizeof(name), "stereo/%06d", frame);
    render::WriteStereoPair(built, rasterizer, static_cast<uint64_t>(flags.seed),
                            flags.options.sensor, frame, flags.stereo, io::JoinPaths(folder, name));
  }
}

int Run(int argc, char** argv) {
  Flags flags;
  comic::apps::ArgParser parser(
      "comic_render", "SCENE.json --photos IMAGES [options]",
      "Renders a scene of textured planar pieces (ground, facades, boxes, poles, trees, fences,\n"
      "a distant backdrop) along its camera path, with textures cut from the photographs given,\n"
      "and writes the frames with their exact truth: images/, depth/, ids/, boundaries/, masks/,\n"
      "poses.txt + calib.txt (KITTI), colmap/ (the true cameras) and scene.json.");
  AddFlags(parser, flags);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  flags.Check();

  const render::BuiltScene built = render::BuildScene(
      flags.scene_file, ExpandPhotos(flags.photos), static_cast<uint64_t>(flags.seed), flags.build);
  CheckCameraPixels(flags.scene_file, built.lens, flags.max_pixels);
  io::StagedFolder out(flags.out_dir);
  comic::apps::ProgressLine progress("comic_render: " + built.name, flags.quiet);
  cv::Size size;
  const render::SequenceRenderSummary summary =
      RenderFrames(flags, built, out.path(), progress, size);
  if (flags.stereo_pairs > 0) WriteStereoPairs(flags, built, out.path());
  out.Commit();
  std::cout << "comic_render: " << summary.num_frames << " frames " << size.width << "x"
            << size.height << " of " << built.name << " (" << built.scene.pieces.size()
            << " pieces) in " << flags.out_dir << "; CPU " << summary.render_cpu_s
            << " s rendering (" << summary.num_frames / std::max(1e-9, summary.render_cpu_s)
            << " frames/s), " << summary.write_cpu_s << " s writing" << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_render", [&] { return Run(argc, argv); });
}
