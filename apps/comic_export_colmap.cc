// comic_export_colmap: tracks features through a folder of frames and writes a COLMAP 3.8
// database (cameras, images, keypoints, raw and verified matches) for `colmap mapper`, then
// prints the exact mapper command the sequence needs.
#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/common/arg_parser.h"
#include "apps/common/thread_count.h"
#include "frontend/detector_factory.h"
#include "frontend/matching/tracker.h"
#include "io/error.h"
#include "io/file_utils.h"
#include "io/ground_truth_cameras.h"
#include "io/image_sequence.h"
#include "io/interrupt_cleanup.h"
#include "io/pixel_budget.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/colmap/colmap_runner.h"

namespace {

namespace fs = std::filesystem;

// COLMAP's image names are paths relative to its --image_path: the path from `image_path` to the
// frames' folder (empty when they are the same), which must lie inside it.
std::string ImageNamePrefix(const std::string& frames, const std::string& image_path) {
  std::error_code ec;
  const fs::path relative =
      fs::relative(fs::weakly_canonical(frames, ec), fs::weakly_canonical(image_path, ec), ec);
  COMIC_CHECK(!ec && !relative.empty() && *relative.begin() != "..", kInvalidArgument,
              "--image-path " << image_path << " must be FRAMES or a folder above it");
  const std::string prefix = relative.generic_string();
  return prefix == "." ? "" : prefix + "/";
}

int Run(int argc, char** argv) {
  std::string frames;
  std::string output;
  bool overwrite = false;
  std::string intrinsics_path;
  std::string detector_name = "harris";
  std::string prediction = "coarse-to-fine";
  std::string image_path;
  std::string sparse_path;
  int colmap_threads = -1;
  int max_pixels = static_cast<int>(comic::io::kDefaultMaxPixels);
  comic::io::ImageSequenceOptions sequence_options;
  comic::frontend::TrackerOptions tracker_options;
  tracker_options.max_features = 1500;
  comic::sfm::ColmapExportOptions export_options;

  comic::apps::ArgParser parser(
      "comic_export_colmap", "FRAMES --output DB [options]",
      "Detects and tracks features through FRAMES (a folder of images) and writes them as a\n"
      "COLMAP 3.8 database: one camera, one image per frame with its features as keypoints, and\n"
      "for every pair of frames at most --window apart that share tracks the raw matches and the\n"
      "matches verified by two-view geometry (essential matrix with --intrinsics, fundamental\n"
      "matrix without). Then prints the `colmap mapper` command to run on it, with the options\n"
      "the sequence needs. The database is written completely or not at all.");
  parser.AddPositional("FRAMES", "folder of images (COLMAP needs the image files)", &frames);
  parser.AddOption("output", "DB", "the COLMAP database to write (required)", &output);
  parser.AddFlag("overwrite", "replace DB if it exists (otherwise an existing file is refused)",
                 &overwrite);
  parser.AddOption("intrinsics", "FILE",
                   "known intrinsics: 'fx fy cx cy', a 3x3 K, or a 3x4 P such as KITTI's "
                   "calib.txt (OpenCV pixel convention); without, COLMAP's SIMPLE_RADIAL guess",
                   &intrinsics_path);
  parser.AddOption("detector", "NAME", "feature detector: comic, harris, hessian, mser, fast",
                   &detector_name);
  parser.AddOption("max-features", "N", "strongest features kept per frame (0 = all)",
                   &tracker_options.max_features);
  parser.AddOption("prediction", "P", "tracker motion prediction: none, velocity, coarse-to-fine",
                   &prediction);
  parser.AddOption("radius", "PX", "tracker search radius around the prediction, pixels",
                   &tracker_options.matcher.radius);
  parser.AddOption("first", "I", "first frame index of FRAMES to use",
                   &sequence_options.first_frame);
  parser.AddOption("last", "I", "last frame index to use, inclusive (-1 = end)",
                   &sequence_options.last_frame);
  parser.AddOption("stride", "N", "use every N-th frame", &sequence_options.stride);
  parser.AddOption("window", "K", "pair frames at most K apart that share tracks",
                   &export_options.pair_window);
  parser.AddOption("max-error", "PX", "two-view RANSAC inlier threshold, pixels",
                   &export_options.two_view.max_error_px);
  parser.AddOption("min-inliers", "N", "fewer verified matches: the pair is DEGENERATE",
                   &export_options.two_view.min_num_inliers);
  parser.AddOption("threads", "N", "threads verifying pairs (0 = one per core; same output)",
                   &export_options.num_threads);
  parser.AddOption("image-path", "DIR",
                   "COLMAP's --image_path: FRAMES (default) or a folder above it; image names "
                   "are relative to it",
                   &image_path);
  parser.AddOption("sparse", "DIR",
                   "output folder in the printed mapper command (default: DB's folder/sparse)",
                   &sparse_path);
  parser.AddFlag("allow-truncated",
                 "accept a video whose frames stop decoding before its end: a warning line, "
                 "and the frames before the break are used (otherwise an error)",
                 &sequence_options.allow_truncated);
  parser.AddOption("max-pixels", "N",
                   "refuse frames with more pixels than this after resizing (about 200 bytes "
                   "each; see docs/robustness.md)",
                   &max_pixels);
  parser.AddOption("colmap-threads", "N",
                   "--Mapper.num_threads in the printed command (-1 = COLMAP's default)",
                   &colmap_threads);
  parser.AddEpilog(
      "Example (the bundled KITTI clip):\n"
      "  comic_export_colmap examples/data/kitti06_000-011/image_l --output kitti.db \\\n"
      "      --intrinsics examples/data/kitti06_000-011/calib.txt\n"
      "prints, among its report, the command to run, e.g.\n"
      "  mkdir -p sparse && colmap mapper --database_path kitti.db --image_path ... \\\n"
      "      --output_path sparse --Mapper.init_max_forward_motion 1 ...\n"
      "For forward motion COLMAP's default --Mapper.init_max_forward_motion 0.95 and\n"
      "--Mapper.init_min_tri_angle 16 reject every initial pair; the printed values let it start.\n"
      "Known intrinsics are held fixed (--Mapper.ba_refine_* 0).\n");
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;

  // Everything that can be checked before the work starts.
  COMIC_CHECK(!output.empty(), kInvalidArgument, "--output DB is required");
  comic::apps::CheckThreadCount("--threads", export_options.num_threads);
  comic::io::CheckMaxPixels(max_pixels);
  sequence_options.max_pixels = max_pixels;
  sequence_options.Check();
  export_options.Check();
  comic::frontend::DetectorOptions detector_options;
  detector_options.name = detector_name;
  detector_options.Check();
  tracker_options.prediction = comic::frontend::ParseMotionPrediction(prediction);
  tracker_options.Check();
  comic::sfm::ColmapMapperOptions mapper_check;
  mapper_check.num_threads = colmap_threads;
  mapper_check.Check();
  comic::io::CheckWritableFile(output, overwrite);
  COMIC_CHECK(comic::io::PathExists(frames), kNotFound, frames << ": no such file or folder");
  COMIC_CHECK(comic::io::IsDirectory(frames), kInvalidArgument,
              frames << ": not a folder (COLMAP needs the frames as image files in a folder)");
  if (image_path.empty()) image_path = frames;
  COMIC_CHECK(comic::io::IsDirectory(image_path), kNotFound,
              image_path << ": --image-path is not a folder");
  export_options.image_name_prefix = ImageNamePrefix(frames, image_path);
  if (sparse_path.empty())
    sparse_path = comic::io::JoinPaths(comic::io::ParentPath(output), "sparse");

  std::optional<Eigen::Matrix3d> k;
  if (!intrinsics_path.empty()) k = comic::io::ReadIntrinsicsFile(intrinsics_path);

  const auto sequence = comic::io::ImageSequence::Open(frames, sequence_options);
  COMIC_CHECK(sequence.NumFrames() >= 2, kInvalidArgument,
              frames << ": COLMAP export needs at least two frames, got " << sequence.NumFrames());
  std::optional<comic::sfm::Camera> camera;
  if (k) {
    comic::sfm::Camera known;
    known.width = sequence.FrameSize().width;
    known.height = sequence.FrameSize().height;
    known.fx = (*k)(0, 0);
    known.fy = (*k)(1, 1);
    known.cx = (*k)(0, 2);
    known.cy = (*k)(1, 2);
    known.Check();
    camera = known;
  }

  const auto detector = comic::frontend::MakeDetector(detector_options);
  const comic::frontend::TrackingResult tracking =
      comic::frontend::TrackSequence(sequence, *detector, tracker_options);
  const comic::frontend::FeatureTracks& tracks = tracking.tracks;
  const comic::sfm::ColmapExportSummary summary =
      comic::sfm::ExportTracksToColmapDatabase(tracks, camera, export_options, output, overwrite);

  comic::sfm::ColmapMapperOptions mapper_options =
      comic::sfm::RecommendedColmapMapperOptions(summary);
  mapper_options.num_threads = colmap_threads;
  size_t observations = 0;
  for (const auto& track : tracks.tracks) observations += track.Length();
  std::cout << "frames:     " << sequence.NumFrames() << " (" << frames << ")\n"
            << "tracks:     " << tracks.tracks.size() << " (" << detector_name << ", "
            << observations << " observations)\n"
            << "camera:     "
            << (camera ? "PINHOLE, known intrinsics (" + intrinsics_path + ")"
                       : std::string("SIMPLE_RADIAL, guessed (no --intrinsics)"))
            << "\n"
            << "pairs:      " << summary.num_matched_pairs << " within "
            << export_options.pair_window << " frames, " << summary.num_verified_pairs
            << " verified\n"
            << "matches:    " << summary.num_matches << " raw, " << summary.num_inlier_matches
            << " verified\n"
            << "wrote:      " << output << "\n"
            << "run COLMAP on it with:\n"
            << "  "
            << comic::sfm::ColmapMapperCommandLine(output, image_path, sparse_path, mapper_options)
            << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_export_colmap", [&] { return Run(argc, argv); });
}
