// The options of a reconstruction run, named and defaulted as comic_sfm's flags (the field for
// --init-max-gap is init_max_gap; Python's keyword is the same), so that the command line and
// the Python module fill one struct and call one function (sfm/run/reconstruction_run.h).
// Check() validates without touching the file system; its messages name the flags.
#pragma once

#include <optional>
#include <string>

#include "frontend/detector_factory.h"
#include "frontend/evaluation/track_evaluation.h"
#include "io/core/pixel_budget.h"
#include "io/image/image_sequence.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/run/camera_resolution.h"
#include "sfm/run/run_page_options.h"
#include "sfm/run/tracker_settings.h"
#include "sfm/sequence_reconstruction.h"

namespace comic::sfm {

// `write_frames` value: images/ in --output, beside the model (COLMAP's layout).
inline constexpr char kFramesInOutput[] = "<--output>/images";

// A COLMAP database of the run's tracks (sfm/colmap/colmap_export.h), the same from
// `comic_sfm --colmap-db` and comic_export_colmap.
struct ColmapDatabaseOptions {
  std::string colmap_db;               // --colmap-db DB (empty: none)
  bool overwrite = false;              // --overwrite: replace an existing database
  ColmapExportOptions export_options;  // --window, --max-error, --min-inliers
  int colmap_threads = -1;             // --colmap-threads (-1: COLMAP's default)

  // Throws comic::Error(kInvalidArgument) naming the bad flag (the export options, the thread
  // count, --overwrite without --colmap-db).
  void Check() const;
};

struct ReconstructionRunOptions {
  // ---- what to reconstruct
  std::string frames;     // FRAMES: a folder of images or a video file
  std::string detector;   // --detector NAME (empty: harris); with --compare it must stay empty
  bool compare = false;   // --compare: one run per detector of `detectors`, and one table
  std::string detectors;  // --detectors LIST (comma-separated; empty: all)
  // Each detector's own settings (not flags: the CLI keeps the defaults; Python's
  // detector_options). `name` is set per run; comic's threads come from `threads`.
  frontend::DetectorOptions detector_options;
  // --resize-height, --first, --last, --stride, --allow-truncated, --max-pixels.
  io::ImageSequenceOptions sequence;
  // --max-working-size N: frames whose larger side exceeds N pixels are tracked and mapped at N
  // (the tracker's and the mapper's pixel thresholds are tuned at ~700 px; COLMAP caps its SIFT
  // at 3200) and the models are written in the input's pixels (sfm/working_resolution.h). 0: the
  // input's size. --resize-height, when given, decides instead.
  int max_working_size = IncrementalPipelineOptions().max_working_image_size;

  // ---- the camera and the truth
  CameraChoice camera;             // --intrinsics, --camera-model, --fixed-intrinsics, ...
  std::string gt;                  // --gt PATH: ground-truth cameras
  std::string gt_format = "auto";  // --gt-format auto|kitti|...|nerf|tum|euroc
  bool gt_partial = false;         // --gt-partial

  // ---- tracking
  std::string matching = "auto";  // --matching auto|sequential|exhaustive|window:K
  // --matcher auto|descriptors|patches (frontend::FeatureMatcher). auto: a video by descriptors,
  // every pair verified, each frame with the next 10 and those 2^k after it (COLMAP's sequential
  // matcher); an image set by the patch tracker's image-set set-up. docs/matching.md measures the
  // choice: car1 11 -> 238 of 252 frames, the bag clip's first 25 frames none -> 25.
  std::string matcher = "auto";
  TrackerSettings tracker;  // --max-features, --search-radius, ...

  // ---- mapping
  bool refine_focal = false;  // on anyway for a self-calibrated camera
  bool refine_principal_point = false;
  bool refine_distortion = false;  // on anyway for a self-calibrated camera
  bool no_retriangulate = false;
  // --no-planar-pose-choice: a near-planar initial pair keeps the essential matrix's pose
  // (IncrementalPipelineOptions::choose_planar_pose off).
  bool no_planar_pose_choice = false;
  bool two_view_tracks = false;
  int local_ba_images = IncrementalPipelineOptions().local_ba_num_images;
  double global_ba_growth = 1.5;
  // --global-ba-max-images N: the adjustments as a model grows hold at most N of its newest
  // (key)frames variable, and the final one runs in windows of N
  // (IncrementalPipelineOptions::global_ba_max_images; 0: all).
  int global_ba_max_images = 0;
  double init_angle = 4.0;  // degrees
  // A video's initial-pair gap (0: no limit, the gap grows as far as the tracks reach); see
  // `matcher`.
  int init_max_gap = 0;
  // --keyframes: only keyframes add points and enter bundle adjustments; the other frames are
  // posed against the map (IncrementalPipelineOptions::keyframes_only). Video only: an image
  // set's order says nothing about which frames are close.
  bool keyframes = false;
  // --loop-closure: revisited places found by appearance, verified and closed at the end of each
  // model's growth (IncrementalPipelineOptions::close_loops). Video only, as --keyframes.
  bool loop_closure = false;
  // --loop-closure-max-move F: a verified loop is closed only if it moves the query's camera by
  // at most F of the path between its two frames (LoopClosureOptions::max_move_per_path).
  double loop_closure_max_move = LoopClosureOptions().max_move_per_path;
  int threads = 0;  // detection and the export (0: one per core); never the bundle adjustments
  // --cache DIR: each detector's detections, descriptors and tracks are kept in
  // DIR/tracks-<detector>-<key>.bin and reused by a re-run with the same frames, detector and
  // tracker options (sfm/run/track_cache.h); other mapper options do not change the key. Empty:
  // no cache. Not inside an input folder nor inside --output (replaced by each run).
  std::string cache;

  // ---- evaluation, and moving objects left out
  // --masks DIR: one mask per source frame (DAVIS annotations). Every feature a mask covers, or
  // lies within 2 px of, is removed before tracking or matching (frontend/feature_masks.h), and
  // the points get boundary and interior statistics.
  std::string masks;
  // Which mask pixels remove features: true, non-zero (DAVIS: the moving object); false, zero
  // (COLMAP's ImageReader.mask_path convention). The statistics take non-zero as the object
  // either way.
  bool mask_drops_nonzero = true;
  std::string regions;  // --regions FILE
  // --boundary-band PX: the band of the track evaluation (region_labels.h), one default for both.
  double boundary_band = frontend::TrackEvaluationOptions().boundary_band;
  std::string plot_plane = "auto";

  // ---- outputs
  // --output DIR. Empty: nothing is written (a library call that only wants the models; the
  // command line's default is out/sfm).
  std::string output;
  std::string model_format = "both";  // txt, bin or both
  std::string ply_format = "binary";  // binary or ascii
  ColmapDatabaseOptions colmap;       // --colmap-db and its flags
  bool compare_colmap = false;        // --compare-colmap
  // --compare-colmap-sift: COLMAP's own pipeline (SIFT, matcher, mapper; its defaults, one thread
  // unless --colmap-threads) on the same frames, in --output/colmap_sift/, and the table
  // colmap_sift_compare.md (sfm/colmap/colmap_pipeline.h).
  bool compare_colmap_sift = false;
  // --min-registered F: a run whose largest model holds fewer than this fraction of the frames is
  // a failure (exit 1), its models written all the same. 0.5: below half the frames the largest
  // model is not a reconstruction of the clip but of a part of it (which part is a matter of where
  // tracking held), and a script that takes exit 0 for "the clip is reconstructed" would be wrong;
  // between half and 95 % the run is `partial` but the model is the clip's main part.
  double min_registered = 0.5;
  // --undistort: the largest model's images undistorted with PINHOLE cameras in dense/, the
  // layout of COLMAP's image_undistorter (sfm/run/undistorted_output.h), for dense MVS.
  bool undistort = false;
  // --write-frames: where a video's frames are written as PNGs (empty: not written, unless
  // --colmap-db needs them; kFramesInOutput: images/ in --output).
  std::string write_frames;
  // report.html: points in the 3-D view, frames shown, where three.js is (not flags: the
  // defaults; Python's report_page).
  RunPageOptions report_page;

  // Throws comic::Error(kInvalidArgument) naming the bad flag. Touches no file.
  void Check() const;
  // The detectors run, in order: `detector` (harris by default), or the --compare list.
  std::vector<std::string> DetectorList() const;
};

// The SfM options of one run: the mapping flags, the tracker options resolved for the frames, and
// the self-calibration rule (a camera no calibration gave has its focal length and distortion
// refined unless --fixed-intrinsics; camera_resolution.h), and the descriptor matching of an
// image set (`image_set`, RunInputs). `video`: the frames are in time order (a video, or a
// folder of its frames), whatever matched them: the mapper may then lean on that order (the
// initial pair near in time, keyframes, loop closure, poses through gaps); an unordered image
// set matched by descriptors gets none of it, and no image set (exhaustive pairing, patches or
// descriptors) gets poses through gaps (issue 47). Check()ed.
SequenceReconstructionOptions MakeSequenceReconstructionOptions(
    const ReconstructionRunOptions& options, const frontend::TrackerOptions& tracker,
    bool refine_intrinsics,
    const std::optional<frontend::ImageSetMatchingOptions>& image_set = std::nullopt,
    bool video = false);

}  // namespace comic::sfm
