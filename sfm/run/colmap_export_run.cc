#include "sfm/run/colmap_export_run.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <sstream>

#include "frontend/matching/combined_tracking.h"
#include "frontend/matching/image_set_matching.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/protected_inputs.h"
#include "io/core/staged_folder.h"
#include "io/core/thread_count.h"
#include "io/image/frame_export.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/colmap/colmap_runner.h"

namespace comic::sfm {

namespace {

// COLMAP's image names are paths relative to its --image_path: the path from `image_path` to the
// frames' folder (empty when they are the same), which must lie inside it.
std::string ImageNamePrefix(const std::string& frames, const std::string& image_path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path relative =
      fs::relative(fs::weakly_canonical(frames, ec), fs::weakly_canonical(image_path, ec), ec);
  COMIC_CHECK(!ec && !relative.empty() && *relative.begin() != "..", kInvalidArgument,
              "--image-path " << image_path << " must be FRAMES or a folder above it");
  const std::string prefix = relative.generic_string();
  return prefix == "." ? "" : prefix + "/";
}

// The database and a video's written frames, against every input.
void CheckExportWritesNoInput(const ColmapExportRunOptions& options,
                              const ColmapExportRunResult& placed) {
  const bool beside = options.write_frames.empty() || options.write_frames == kFramesBesideDatabase;
  io::CheckWrittenPathsAvoidInputs(
      {{"--colmap-db", options.colmap.colmap_db},
       {beside ? "--colmap-db" : "--write-frames", placed.video ? placed.frames_folder : ""}},
      {{"FRAMES", options.frames}, {"--intrinsics", options.camera.intrinsics}});
}

// Where things go, from the options and the file system, before any work: the frames' folder
// for COLMAP, --image-path, --sparse. Throws comic::Error naming the flag or the file.
void PlaceOutputs(const ColmapExportRunOptions& options, ColmapExportRunResult* result) {
  const std::string& database = options.colmap.colmap_db;
  // Inputs are sacred (issue 29: `--colmap-db frames/000000.png --overwrite` replaced a frame).
  io::CheckOutputsAvoidInputs(
      {{"--colmap-db", database},
       {"--write-frames",
        options.write_frames == kFramesBesideDatabase ? "" : options.write_frames}},
      {{"FRAMES", options.frames}, {"--intrinsics", options.camera.intrinsics}});
  CheckColmapDatabaseOutput(database, options.colmap.overwrite);
  COMIC_CHECK(io::PathExists(options.frames), kNotFound,
              options.frames << ": no such file or folder");
  result->video = !io::IsDirectory(options.frames);
  COMIC_CHECK(result->video || options.write_frames.empty(), kInvalidArgument,
              "--write-frames: " << options.frames
                                 << " is a folder of images already (COLMAP reads them there); "
                                    "--write-frames is for a video");
  // A folder's images are COLMAP's as stored; a video's frames are written as the tracker saw
  // them (resized too).
  COMIC_CHECK(result->video || options.sequence.resize_height == 0, kInvalidArgument,
              "--resize-height needs a video FRAMES (COLMAP reads a folder's image files at "
              "their stored size)");
  result->frames_folder = options.frames;
  if (result->video) {
    result->frames_folder =
        options.write_frames.empty() || options.write_frames == kFramesBesideDatabase
            ? io::JoinPaths(io::ParentPath(database), "images")
            : options.write_frames;
    io::CheckCreatableFolder(result->frames_folder);
  }
  result->image_path = options.image_path.empty() ? result->frames_folder : options.image_path;
  COMIC_CHECK(io::IsDirectory(result->image_path) || result->image_path == result->frames_folder,
              kNotFound, result->image_path << ": --image-path is not a folder");
  result->sparse = options.sparse.empty() ? ColmapMapperOutputBeside(database) : options.sparse;
  CheckExportWritesNoInput(options, *result);
}

io::ImageSequence OpenFrames(const ColmapExportRunOptions& options, bool video) {
  io::ImageSequence sequence = io::ImageSequence::Open(options.frames, options.sequence);
  COMIC_CHECK(sequence.IsVideo() == video, kInvalidArgument,
              options.frames << ": a single image, not a folder of images or a video (COLMAP "
                                "export needs at least two frames)");
  COMIC_CHECK(
      sequence.NumFrames() >= 2, kInvalidArgument,
      options.frames << ": COLMAP export needs at least two frames, got " << sequence.NumFrames());
  return sequence;
}

// The tracks of the frames, a descriptor for every feature (so that COLMAP's matchers can add
// pairs): an image set matched by descriptors (`image_set`), or tracked, then described.
frontend::FeatureTracks Track(const ColmapExportRunOptions& options,
                              const io::ImageSequence& sequence,
                              const frontend::TrackerOptions& tracker,
                              const std::optional<frontend::ImageSetMatchingOptions>& image_set,
                              const RunCallbacks& callbacks) {
  frontend::DetectorOptions detector_options = options.detector_options;
  detector_options.name = options.detector;
  detector_options.comic.num_threads = options.threads;
  detector_options.comic_paper.num_threads = options.threads;
  const auto detector = frontend::MakeDetector(detector_options);
  if (callbacks.stage_started) callbacks.stage_started(RunStage::kTracking, options.detector);
  if (image_set) {
    return frontend::MatchImageSet(
               sequence, *detector, *image_set,
               frontend::ProgressInFrames(callbacks.frame_done, sequence.NumFrames()))
        .tracks;
  }
  frontend::FeatureTracks tracks =
      frontend::TrackSequenceWithDetector(sequence, *detector, tracker, callbacks.frame_done)
          .tracks;
  frontend::DescribeTrackedFeatures(sequence, &tracks, options.threads, std::nullopt,
                                    callbacks.frame_done);
  return tracks;
}

}  // namespace

void ColmapExportRunOptions::Check() const {
  COMIC_CHECK(!colmap.colmap_db.empty(), kInvalidArgument, "--colmap-db DB is required");
  io::CheckThreadCount("--threads", threads);
  io::CheckMaxPixels(sequence.max_pixels);
  sequence.Check();
  colmap.Check();
  camera.Check();
  frontend::DetectorOptions detector_check = detector_options;
  detector_check.name = detector;
  try {
    detector_check.Check();
  } catch (const Error& e) {
    throw Error(ErrorKind::kInvalidArgument, std::string("--detector: ") + e.what());
  }
  frontend::ParsePairing(matching);
  frontend::ParseFeatureMatcher(matcher);
  tracker.ToTrackerOptions();
}

ColmapExportRunResult RunColmapExport(const ColmapExportRunOptions& options,
                                      const RunCallbacks& callbacks) {
  options.Check();
  ColmapExportRunResult result;
  PlaceOutputs(options, &result);
  ColmapExportOptions export_options = options.colmap.export_options;
  export_options.num_threads = options.threads;
  if (!options.camera.camera_model.empty()) {
    export_options.default_camera_model = ParseCameraModel(options.camera.camera_model);
  }
  export_options.image_name_prefix = ImageNamePrefix(result.frames_folder, result.image_path);
  const io::ImageSequence sequence = OpenFrames(options, result.video);
  result.num_frames = sequence.NumFrames();
  result.warning = sequence.warning();
  if (!options.camera.intrinsics.empty()) {
    result.camera = ResolveCamera(options.camera, sequence.SourceFrameSize(), sequence.FrameSize(),
                                  std::nullopt)
                        .camera;
  }
  result.pairing = ChooseRunPairing(options.matching, options.tracker, sequence);
  const frontend::TrackerOptions tracker =
      TrackerOptionsForRun(options.tracker, result.pairing, static_cast<int>(result.num_frames));
  const std::optional<frontend::ImageSetMatchingOptions> image_set =
      ImageSetMatchingForRun(options.matcher, result.pairing, tracker, options.threads);
  result.by_descriptors = image_set.has_value();
  // An image set matched by descriptors: its pairs are any two frames that share tracks.
  if (image_set) {
    export_options.pair_window = std::max(1, static_cast<int>(result.num_frames) - 1);
  }
  // Staged: the frames appear with the database or not at all.
  std::unique_ptr<io::StagedFolder> frames_out;
  if (result.video) frames_out = std::make_unique<io::StagedFolder>(result.frames_folder);
  const frontend::FeatureTracks tracks = Track(options, sequence, tracker, image_set, callbacks);
  if (frames_out) {
    if (callbacks.stage_started) callbacks.stage_started(RunStage::kWritingFrames, "");
    // A failure (a full disk) names the user's folder, not the staging one.
    frames_out->NamingTarget(
        [&] { io::WriteSequenceFrames(sequence, frames_out->path(), callbacks.frame_done); });
  }
  result.summary = ExportTracksToColmapDatabase(tracks, result.camera, export_options,
                                                options.colmap.colmap_db, options.colmap.overwrite);
  if (frames_out) frames_out->Commit();

  result.num_tracks = tracks.tracks.size();
  for (const auto& track : tracks.tracks) result.num_observations += track.Length();
  result.guessed_model = export_options.default_camera_model;
  result.pair_window = export_options.pair_window;
  ColmapMapperOptions mapper = RecommendedColmapMapperOptions(result.summary);
  mapper.num_threads = options.colmap.colmap_threads;
  result.mapper_command =
      ColmapMapperCommandLine(options.colmap.colmap_db, result.image_path, result.sparse, mapper);
  return result;
}

std::vector<std::string> ColmapExportReportLines(const ColmapExportRunOptions& options,
                                                 const ColmapExportRunResult& result) {
  const ColmapExportSummary& summary = result.summary;
  const frontend::PairingChoice& pairing = result.pairing;
  std::ostringstream frames, tracks, matching, camera, pairs, matches;
  frames << "frames:     " << result.num_frames << " (" << options.frames
         << (result.video ? ", written as PNG to " + result.frames_folder : std::string()) << ")";
  tracks << "tracks:     " << result.num_tracks << " (" << options.detector << ", "
         << result.num_observations << " observations)";
  matching << "matching:   " << frontend::PairingName(pairing.chosen) << " ("
           << (pairing.requested.mode == frontend::PairingMode::kAuto ? "auto: " : "")
           << pairing.reason << ")" << (result.by_descriptors ? ", by SIFT descriptors" : "");
  camera << "camera:     "
         << (result.camera ? result.camera->Describe() + ", known intrinsics (" +
                                 options.camera.intrinsics + ")"
                           : CameraModelName(result.guessed_model) + ", guessed (no --intrinsics)");
  pairs << "pairs:      " << summary.num_matched_pairs << " within " << result.pair_window
        << " frames, " << summary.num_verified_pairs << " verified";
  matches << "matches:    " << summary.num_matches << " raw, " << summary.num_inlier_matches
          << " verified";
  return {frames.str(),
          tracks.str(),
          matching.str(),
          camera.str(),
          pairs.str(),
          matches.str(),
          "descriptors: " + std::to_string(summary.num_descriptors) +
              " (128-D uint8 RootSIFT; COLMAP's matchers can add pairs)",
          "wrote:      " + options.colmap.colmap_db,
          "run COLMAP on it with:",
          "  " + result.mapper_command};
}

}  // namespace comic::sfm
