// comic_export_colmap: tracks features through a folder of frames or a video and writes a COLMAP
// 3.8 database (cameras, images, keypoints, raw and verified matches) for `colmap mapper`, then
// prints the exact mapper command the sequence needs. A video's frames are written as PNGs
// (--write-frames), since COLMAP reads image files.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/common/arg_parser.h"
#include "apps/common/camera_intrinsics.h"
#include "apps/common/colmap_db_flags.h"
#include "apps/common/frame_range_flags.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/matching_flags.h"
#include "apps/common/progress_line.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "apps/common/tracker_flags.h"
#include "frontend/detector_factory.h"
#include "frontend/matching/combined_tracking.h"
#include "frontend/matching/image_set_matching.h"
#include "frontend/matching/pairing.h"
#include "frontend/matching/tracker.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/pixel_budget.h"
#include "io/core/staged_folder.h"
#include "io/image/frame_export.h"
#include "io/image/image_sequence.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/colmap/colmap_runner.h"

namespace {

namespace fs = std::filesystem;

// --write-frames without a folder: images/ beside the database.
const char kFramesBesideDatabase[] = "<DB's folder>/images";

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
  std::string intrinsics_path;
  std::string camera_model;
  std::string detector_name = "harris";
  std::string image_path;
  std::string sparse_path;
  int threads = 0;
  bool quiet = false;
  std::string write_frames;
  int max_pixels = static_cast<int>(comic::io::kDefaultMaxPixels);
  comic::io::ImageSequenceOptions sequence_options;
  std::string matching = "auto";            // comic_sfm's --matching
  std::string matcher = "auto";             // comic_sfm's --matcher
  comic::apps::TrackerFlags tracker_flags;  // comic_sfm's defaults: the same tracks as it builds
  comic::apps::ColmapDbFlags colmap;

  comic::apps::ArgParser parser(
      "comic_export_colmap", "FRAMES --colmap-db DB [options]",
      "Detects and tracks features through FRAMES (a folder of images or a video) and writes\n"
      "them as a COLMAP 3.8 database: one camera, one image per frame with its features as\n"
      "keypoints and descriptors, and for every pair of frames at most --window apart that share\n"
      "tracks the raw\n"
      "matches and the matches verified by two-view geometry (essential matrix with --intrinsics, "
      "fundamental\n"
      "matrix without). Then prints the `colmap mapper` command to run on it, with the options\n"
      "the sequence needs. The database is written completely or not at all. With the same\n"
      "options `comic_sfm FRAMES --colmap-db DB` writes the same database. A video's frames are\n"
      "written as PNGs (--write-frames) and are COLMAP's --image_path.");
  parser.AddPositional("FRAMES",
                       "folder of images, or video file (its frames are written as images, see "
                       "--write-frames)",
                       &frames);
  comic::apps::AddColmapDbFlags(parser, &colmap);
  parser.AddDeprecatedAlias("output", "colmap-db");
  comic::apps::AddIntrinsicsFlag(parser, &intrinsics_path);
  comic::apps::AddCameraModelFlag(parser, &camera_model);
  comic::apps::AddDetectorFlag(parser, &detector_name);
  comic::apps::AddMatchingFlag(parser, &matching);
  comic::apps::AddMatcherFlag(parser, &matcher);
  comic::apps::AddTrackerFlags(parser, &tracker_flags);
  parser.AddDeprecatedAlias("radius", "search-radius");
  comic::apps::AddFrameRangeFlags(parser, &sequence_options);
  comic::apps::AddThreadsFlag(parser, &threads);
  parser.AddOption("image-path", "DIR",
                   "COLMAP's --image_path: FRAMES (default) or a folder above it; image names "
                   "are relative to it",
                   &image_path);
  parser.AddOption("sparse", "DIR",
                   "output folder in the printed mapper command (default: DB's folder/sparse)",
                   &sparse_path);
  comic::apps::AddMaxPixelsFlag(parser, &max_pixels);
  comic::apps::AddResizeHeightFlag(parser, &sequence_options.resize_height);
  parser.AddOptionalValueOption(
      "write-frames", "DIR",
      "video input: write each frame once as DIR/frame_000000.png ..., the names the database "
      "uses, and use DIR as COLMAP's --image_path (default, and alone: images/ beside DB)",
      kFramesBesideDatabase, &write_frames);
  comic::apps::AddQuietFlag(parser, &quiet);
  parser.AddEpilog(
      "Without --intrinsics the camera is COLMAP's SIMPLE_RADIAL guess (or --camera-model's).\n"
      "Example (the bundled KITTI clip):\n"
      "  comic_export_colmap examples/data/kitti06_000-011/image_l --colmap-db kitti.db \\\n"
      "      --intrinsics examples/data/kitti06_000-011/calib.txt\n"
      "prints, among its report, the command to run, e.g.\n"
      "  mkdir -p sparse && colmap mapper --database_path kitti.db --image_path ... \\\n"
      "      --output_path sparse --Mapper.init_max_forward_motion 1 ...\n"
      "For forward motion COLMAP's default --Mapper.init_max_forward_motion 0.95 and\n"
      "--Mapper.init_min_tri_angle 16 reject every initial pair; the printed values let it start.\n"
      "Known intrinsics are held fixed (--Mapper.ba_refine_* 0).\n");
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;

  // Everything that can be checked before the work starts.
  const std::string& output = colmap.database;
  COMIC_CHECK(!output.empty(), kInvalidArgument, "--colmap-db DB is required");
  comic::apps::CheckThreadCount("--threads", threads);
  comic::io::CheckMaxPixels(max_pixels);
  sequence_options.max_pixels = max_pixels;
  sequence_options.Check();
  comic::sfm::ColmapExportOptions export_options = colmap.export_options;
  export_options.num_threads = threads;
  comic::apps::CheckColmapDbFlags(colmap);
  std::optional<comic::sfm::CameraModelId> model;
  if (!camera_model.empty()) model = comic::apps::ParseCameraModelFlag(camera_model);
  if (model) export_options.default_camera_model = *model;
  comic::frontend::DetectorOptions detector_options;
  detector_options.name = detector_name;
  detector_options.comic.num_threads = threads;
  detector_options.comic_paper.num_threads = threads;
  detector_options.Check();
  comic::frontend::ParsePairing(matching);
  comic::frontend::ParseFeatureMatcher(matcher);
  comic::apps::ToTrackerOptions(tracker_flags);  // validated before any work
  comic::io::CheckWritableFile(output, colmap.overwrite);
  COMIC_CHECK(comic::io::PathExists(frames), kNotFound, frames << ": no such file or folder");
  const bool video = !comic::io::IsDirectory(frames);
  COMIC_CHECK(video || write_frames.empty(), kInvalidArgument,
              "--write-frames: " << frames
                                 << " is a folder of images already (COLMAP reads them there); "
                                    "--write-frames is for a video");
  // A folder's images are COLMAP's as stored; a video's frames are written as the tracker saw
  // them (resized too).
  COMIC_CHECK(video || sequence_options.resize_height == 0, kInvalidArgument,
              "--resize-height needs a video FRAMES (COLMAP reads a folder's image files at "
              "their stored size)");
  // Where COLMAP will find the frames: FRAMES itself, or the folder a video's frames go to.
  std::string frames_folder = frames;
  if (video) {
    frames_folder = write_frames.empty() || write_frames == kFramesBesideDatabase
                        ? comic::io::JoinPaths(comic::io::ParentPath(output), "images")
                        : write_frames;
    comic::io::CheckCreatableFolder(frames_folder);
  }
  if (image_path.empty()) image_path = frames_folder;
  COMIC_CHECK(comic::io::IsDirectory(image_path) || image_path == frames_folder, kNotFound,
              image_path << ": --image-path is not a folder");
  export_options.image_name_prefix = ImageNamePrefix(frames_folder, image_path);
  if (sparse_path.empty())
    sparse_path = comic::io::JoinPaths(comic::io::ParentPath(output), "sparse");

  const auto sequence = comic::io::ImageSequence::Open(frames, sequence_options);
  COMIC_CHECK(sequence.IsVideo() == video, kInvalidArgument,
              frames << ": a single image, not a folder of images or a video (COLMAP export "
                        "needs at least two frames)");
  COMIC_CHECK(sequence.NumFrames() >= 2, kInvalidArgument,
              frames << ": COLMAP export needs at least two frames, got " << sequence.NumFrames());
  std::optional<comic::sfm::Camera> camera;
  if (!intrinsics_path.empty()) {
    camera = comic::apps::LoadCameraIntrinsics(intrinsics_path, sequence.SourceFrameSize(),
                                               sequence.FrameSize(), model);
  }

  const comic::frontend::PairingChoice pairing =
      comic::apps::ChooseRunPairing(matching, parser, sequence);
  const comic::frontend::TrackerOptions tracker_options = comic::apps::TrackerOptionsForRun(
      parser, tracker_flags, pairing, static_cast<int>(sequence.NumFrames()));
  const auto detector = comic::frontend::MakeDetector(detector_options);
  // Staged: the frames appear with the database or not at all.
  std::unique_ptr<comic::io::StagedFolder> frames_out;
  if (video) frames_out = std::make_unique<comic::io::StagedFolder>(frames_folder);
  // An image set is matched by descriptors, a video tracked (--matcher); either way every feature
  // gets a descriptor, so that COLMAP's matchers can extend the database.
  const std::optional<comic::frontend::ImageSetMatchingOptions> image_set =
      comic::apps::ImageSetMatchingForRun(matcher, pairing, tracker_options, threads);
  if (image_set && !parser.WasSet("window")) {
    export_options.pair_window = std::max(1, static_cast<int>(sequence.NumFrames()) - 1);
  }
  comic::apps::ProgressLine tracking_progress(
      "comic_export_colmap: [" + detector_name + "] " +
          (image_set ? "description (frames), then matching (pairs)" : "detection and tracking"),
      quiet);
  comic::frontend::FeatureTracks tracks =
      image_set ? comic::frontend::MatchImageSet(sequence, *detector, *image_set,
                                                 tracking_progress.Callback())
                      .tracks
                : comic::frontend::TrackSequenceWithDetector(sequence, *detector, tracker_options,
                                                             tracking_progress.Callback())
                      .tracks;
  if (!tracks.HasDescriptors()) {
    comic::apps::ProgressLine progress("comic_export_colmap: describing the tracked features",
                                       quiet);
    comic::frontend::DescribeTrackedFeatures(sequence, &tracks, threads, std::nullopt,
                                             progress.Callback());
  }
  if (frames_out) {
    comic::apps::ProgressLine progress("comic_export_colmap: writing frames", quiet);
    comic::io::WriteSequenceFrames(sequence, frames_out->path(), progress.Callback());
  }
  const comic::sfm::ColmapExportSummary summary = comic::sfm::ExportTracksToColmapDatabase(
      tracks, camera, export_options, output, colmap.overwrite);
  if (frames_out) frames_out->Commit();

  comic::sfm::ColmapMapperOptions mapper_options =
      comic::sfm::RecommendedColmapMapperOptions(summary);
  mapper_options.num_threads = colmap.colmap_threads;
  size_t observations = 0;
  for (const auto& track : tracks.tracks) observations += track.Length();
  std::cout << "frames:     " << sequence.NumFrames() << " (" << frames
            << (video ? ", written as PNG to " + frames_folder : std::string()) << ")\n"
            << "tracks:     " << tracks.tracks.size() << " (" << detector_name << ", "
            << observations << " observations)\n"
            << "matching:   " << comic::frontend::PairingName(pairing.chosen) << " ("
            << (pairing.requested.mode == comic::frontend::PairingMode::kAuto ? "auto: " : "")
            << pairing.reason << ")" << (image_set ? ", by SIFT descriptors" : "") << "\n"
            << "camera:     "
            << (camera ? camera->Describe() + ", known intrinsics (" + intrinsics_path + ")"
                       : comic::sfm::CameraModelName(export_options.default_camera_model) +
                             ", guessed (no --intrinsics)")
            << "\n"
            << "pairs:      " << summary.num_matched_pairs << " within "
            << export_options.pair_window << " frames, " << summary.num_verified_pairs
            << " verified\n"
            << "matches:    " << summary.num_matches << " raw, " << summary.num_inlier_matches
            << " verified\n"
            << "descriptors: " << summary.num_descriptors
            << " (128-D uint8 RootSIFT; COLMAP's matchers can add pairs)\n"
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
