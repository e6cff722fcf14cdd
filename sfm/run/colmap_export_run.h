// The run behind comic_export_colmap and comic.export_colmap: tracks features through a folder of
// frames or a video and writes them as a COLMAP 3.8 database (cameras, images, keypoints, raw and
// verified matches) for `colmap mapper`, with the exact mapper command the sequence needs. A
// video's frames are written as PNGs (COLMAP reads image files), staged so that they appear with
// the database or not at all. With the same options, `comic_sfm --colmap-db` writes the same
// database (the same tracker settings, pairing and export options).
//
//   ColmapExportRunOptions options;
//   options.frames = "examples/data/kitti06_000-011/image_l";
//   options.colmap.colmap_db = "kitti.db";
//   options.camera.intrinsics = "examples/data/kitti06_000-011/calib.txt";
//   ColmapExportRunResult result = RunColmapExport(options);  // result.mapper_command
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "frontend/detector_factory.h"
#include "frontend/matching/pairing.h"
#include "io/image/image_sequence.h"
#include "sfm/camera.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/run_options.h"
#include "sfm/run/tracker_settings.h"

namespace comic::sfm {

// `write_frames` value: images/ beside the database.
inline constexpr char kFramesBesideDatabase[] = "<DB's folder>/images";

// Named and defaulted as comic_export_colmap's flags.
struct ColmapExportRunOptions {
  std::string frames;               // FRAMES: a folder of images or a video file
  ColmapDatabaseOptions colmap;     // --colmap-db DB (required), --overwrite, --window, ...
  CameraChoice camera;              // --intrinsics, --camera-model (no ground truth here)
  std::string detector = "harris";  // --detector NAME
  // Each detector's own settings (Python's detector_options); comic's threads from `threads`.
  frontend::DetectorOptions detector_options;
  std::string matching = "auto";      // --matching
  std::string matcher = "auto";       // --matcher (ReconstructionRunOptions::matcher)
  TrackerSettings tracker;            // --max-features, --search-radius, ...
  io::ImageSequenceOptions sequence;  // --first, --last, --stride, --resize-height, --max-pixels
  int threads = 0;                    // --threads (0: one per core)
  std::string image_path;             // --image-path: COLMAP's --image_path (empty: the frames')
  std::string sparse;                 // --sparse: the mapper command's output (empty: DB's sparse/)
  // --write-frames: where a video's frames go (empty or kFramesBesideDatabase: images/ beside
  // the database).
  std::string write_frames;

  // Throws comic::Error(kInvalidArgument) naming the bad flag. Touches no file.
  void Check() const;
};

struct ColmapExportRunResult {
  size_t num_frames = 0;
  bool video = false;
  std::string frames_folder;  // where COLMAP finds the frames: FRAMES, or a video's written frames
  std::string image_path;     // COLMAP's --image_path
  std::string sparse;         // the mapper command's --output_path
  frontend::PairingChoice pairing;
  bool by_descriptors = false;  // matched by descriptors (--matcher), not tracked
  size_t num_tracks = 0;
  size_t num_observations = 0;
  std::optional<Camera> camera;  // known intrinsics (--intrinsics); none: COLMAP's guess
  CameraModelId guessed_model = CameraModelId::kSimpleRadial;  // the model of COLMAP's guess
  int pair_window = 0;
  ColmapExportSummary summary;
  std::string mapper_command;  // the `colmap mapper` command to run, paste-able
  // The frames were accepted with a problem to tell (entries of the folder skipped, a truncated
  // video used up to its break): ImageSequence::warning(); empty if none.
  std::string warning;
};

// Runs `options`. Throws comic::Error for bad options (kInvalidArgument, naming the flag) and for
// input or outputs it cannot use; the database and the frames are then left as they were.
ColmapExportRunResult RunColmapExport(const ColmapExportRunOptions& options,
                                      const RunCallbacks& callbacks = {});

// What comic_export_colmap prints after the run: frames, tracks, matching, camera, pairs,
// matches, the database and the command to run on it.
std::vector<std::string> ColmapExportReportLines(const ColmapExportRunOptions& options,
                                                 const ColmapExportRunResult& result);

}  // namespace comic::sfm
