#include "sfm/run/run_options.h"

#include <cmath>

#include "io/core/error.h"
#include "io/core/thread_count.h"
#include "io/datasets/ground_truth_cameras.h"
#include "sfm/colmap/colmap_runner.h"
#include "sfm/run/run_outputs.h"

namespace comic::sfm {

void ColmapDatabaseOptions::Check() const {
  COMIC_CHECK(!overwrite || !colmap_db.empty(), kInvalidArgument, "--overwrite needs --colmap-db");
  COMIC_CHECK(colmap_threads == -1 || colmap_threads >= 1, kInvalidArgument,
              "--colmap-threads must be -1 or >= 1, got " << colmap_threads);
  // At most the machine's threads (absurd counts were accepted once; docs/robustness.md).
  COMIC_CHECK(colmap_threads <= io::HardwareThreads(), kInvalidArgument,
              "--colmap-threads must be at most the " << io::HardwareThreads()
                                                      << " hardware threads of this machine, got "
                                                      << colmap_threads);
  export_options.Check();
  ColmapMapperOptions mapper;
  mapper.num_threads = colmap_threads;
  mapper.Check();
}

std::vector<std::string> ReconstructionRunOptions::DetectorList() const {
  if (compare) {
    return detectors.empty() ? frontend::DetectorNames() : frontend::ParseDetectorList(detectors);
  }
  return {detector.empty() ? "harris" : detector};
}

void ReconstructionRunOptions::Check() const {
  // The detectors.
  if (compare) {
    COMIC_CHECK(detector.empty(), kInvalidArgument,
                "--detector and --compare exclude each other (use --detectors with --compare)");
  } else {
    COMIC_CHECK(detectors.empty(), kInvalidArgument, "--detectors needs --compare");
    try {
      frontend::CheckDetectorName(DetectorList().front());
    } catch (const Error& e) {
      throw Error(ErrorKind::kInvalidArgument, std::string("--detector: ") + e.what());
    }
  }
  DetectorList();  // --detectors parsed
  // The frames, the tracker and the mapper.
  io::CheckThreadCount("--threads", threads);
  io::CheckMaxPixels(sequence.max_pixels);
  sequence.Check();
  frontend::ParsePairing(matching);
  frontend::ParseFeatureMatcher(matcher);
  COMIC_CHECK(local_ba_images >= 2, kInvalidArgument,
              "--local-ba-images must be >= 2, got " << local_ba_images);
  COMIC_CHECK(global_ba_growth > 1.0, kInvalidArgument,
              "--global-ba-growth must be > 1, got " << global_ba_growth);
  COMIC_CHECK(global_ba_max_images == 0 || global_ba_max_images >= 2, kInvalidArgument,
              "--global-ba-max-images must be 0 (every frame) or >= 2 (a window holds at least 2 "
              "images), got "
                  << global_ba_max_images);
  COMIC_CHECK(loop_closure_max_move > 0.0, kInvalidArgument,
              "--loop-closure-max-move must be > 0 (a fraction of the path), got "
                  << loop_closure_max_move);
  COMIC_CHECK(init_angle > 0.0 && init_angle < 90.0, kInvalidArgument,
              "--init-angle must be in (0, 90) degrees, got " << init_angle);
  COMIC_CHECK(init_max_gap >= 0, kInvalidArgument,
              "--init-max-gap must be >= 0 (0: no limit), got " << init_max_gap);
  COMIC_CHECK(
      max_working_size == 0 || max_working_size >= 64, kInvalidArgument,
      "--max-working-size must be 0 (the input's size) or >= 64 pixels, got " << max_working_size);
  COMIC_CHECK(min_registered >= 0.0 && min_registered <= 1.0, kInvalidArgument,
              "--min-registered must be in [0, 1], got " << min_registered);
  MakeSequenceReconstructionOptions(*this, tracker.ToTrackerOptions(), false);
  camera.Check();
  // The outputs.
  COMIC_CHECK(
      model_format == "txt" || model_format == "bin" || model_format == "both", kInvalidArgument,
      "--model-format: unknown format '" << model_format << "' (expected txt, bin or both)");
  COMIC_CHECK(ply_format == "binary" || ply_format == "ascii", kInvalidArgument,
              "--ply-format: unknown format '" << ply_format << "' (expected binary or ascii)");
  colmap.Check();
  if (!colmap.colmap_db.empty() || compare_colmap) {
    COMIC_CHECK(!compare, kInvalidArgument,
                "--colmap-db and --compare-colmap work on one detector's run, not with --compare");
  }
  COMIC_CHECK(!compare_colmap || !output.empty(), kInvalidArgument,
              "--compare-colmap needs --output (COLMAP's files go to --output/colmap/)");
  COMIC_CHECK(!compare_colmap_sift || (!compare && !output.empty()), kInvalidArgument,
              "--compare-colmap-sift works on one detector's run (not --compare) and needs "
              "--output (COLMAP's files go to --output/colmap_sift/)");
  COMIC_CHECK(write_frames != kFramesInOutput || !output.empty(), kInvalidArgument,
              "--write-frames without a folder needs --output (the frames go to images/ in it)");
  // The evaluation.
  COMIC_CHECK(regions.empty() || masks.empty(), kInvalidArgument,
              "--regions and --masks exclude each other");
  COMIC_CHECK(boundary_band > 0, kInvalidArgument, "--boundary-band must be > 0");
  if (plot_plane != "auto") ParsePlotPlane(plot_plane);
  io::ParseGroundTruthFormat(gt_format);
  report_page.Check();
}

SequenceReconstructionOptions MakeSequenceReconstructionOptions(
    const ReconstructionRunOptions& run, const frontend::TrackerOptions& tracker,
    bool refine_intrinsics, const std::optional<frontend::ImageSetMatchingOptions>& image_set,
    bool video) {
  // Frames without an order: an image set matched by descriptors.
  const bool unordered = image_set.has_value() && !video;
  SequenceReconstructionOptions options;
  options.tracker = tracker;
  options.image_set = image_set;
  options.mapper.global_ba.refine_focal_length = run.refine_focal || refine_intrinsics;
  options.mapper.global_ba.refine_principal_point = run.refine_principal_point;
  options.mapper.global_ba.refine_extra_params = run.refine_distortion || refine_intrinsics;
  options.mapper.mapper.retriangulate_incomplete_tracks = !run.no_retriangulate;
  options.mapper.choose_planar_pose = !run.no_planar_pose_choice;
  // Two-view tracks are left out of video (frame-to-frame tracks are long; the two-frame ones
  // are the unchecked leftovers) but kept for image sets matched across several frames, where a
  // track of two views is often all a sparse ring has (docs/sfm.md "Two-view tracks and the
  // global loss"), and for image sets matched by descriptors.
  options.mapper.mapper.ignore_two_view_tracks =
      !run.two_view_tracks && tracker.match_window <= 1 && !unordered;
  options.mapper.local_ba_num_images = run.local_ba_images;
  options.mapper.global_ba_growth_ratio = run.global_ba_growth;
  options.mapper.global_ba_max_images = run.global_ba_max_images;
  options.mapper.mapper.init_tri_angle_deg = run.init_angle;
  options.mapper.mapper.init_max_frame_gap = run.init_max_gap;
  // An image set's frame order says nothing about which views are near: any two may start.
  if (unordered) options.mapper.mapper.init_max_frame_gap = 1 << 30;
  options.mapper.max_working_image_size = run.max_working_size;
  options.mapper.keyframes_only = run.keyframes && !unordered;
  options.mapper.close_loops = run.loop_closure && !unordered;
  // Guessed poses (interpolation between neighbours, rotation only) need frames close in time:
  // video only, whatever matched it. On an unordered set 36 of 63 "registered" frames were once
  // poses interpolated between neighbours in file order (issue 47).
  options.mapper.fill_pose_gaps = video;
  options.mapper.loop_closure.max_move_per_path = run.loop_closure_max_move;
  // `threads` is not passed to the bundle adjustments: Ceres sums the residual blocks of its
  // threads in a scheduling-dependent order (docs/sfm.md, determinism), and no output may depend
  // on the thread count. They stay on one thread; detection and the export use `threads`.
  options.Check();
  return options;
}

}  // namespace comic::sfm
