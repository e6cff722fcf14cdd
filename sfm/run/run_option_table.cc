#include "sfm/run/run_option_table.h"

#include <algorithm>
#include <iterator>
#include <utility>

namespace comic::sfm {
namespace {

using Options = ReconstructionRunOptions;

// The keyword is the flag's name with underscores, as every keyword of comic.reconstruct.
RunOption Entry(std::string flag, std::string metavar, std::string help, RunOption::Field field) {
  std::string keyword = flag;
  std::replace(keyword.begin(), keyword.end(), '-', '_');
  return {std::move(flag), std::move(keyword), std::move(metavar), std::move(help), field};
}

RunOption Switch(std::string flag, std::string help, bool& (*field)(Options&)) {
  return Entry(std::move(flag), "", std::move(help), field);
}

RunOption Reported(RunOption entry) {
  entry.reported_as_given = true;
  return entry;
}

// What is compared and written, and which tracks become points.
std::vector<RunOption> InputOutputAndTrackOptions() {
  return {
      Switch("compare",
             "run every detector of --detectors on the same frames; writes --output/<detector>/ "
             "and the table compare.md, compare.csv, compare.json",
             [](Options& o) -> bool& { return o.compare; }),
      Entry("gt", "PATH",
            "ground-truth cameras: KITTI poses.txt (calib.txt beside it gives the "
            "intrinsics; matched by frame index), Middlebury *_par.txt, a folder of "
            "Strecha *.camera files, a COLMAP model (folder of cameras/images .bin or "
            ".txt) or a NeRF transforms.json (matched by image name), a TUM trajectory "
            "or EuRoC's groundtruth data.csv (matched by time stamp when the frames are "
            "named by theirs, else by frame index)",
            [](Options& o) -> std::string& { return o.gt; }),
      Entry("gt-format", "F",
            "format of --gt: auto, kitti, middlebury, strecha, colmap, nerf, tum or euroc",
            [](Options& o) -> std::string& { return o.gt_format; }),
      Switch("gt-partial",
             "accept --gt that covers only some frames and evaluate on those (otherwise "
             "an error)",
             [](Options& o) -> bool& { return o.gt_partial; }),
      Entry("model-format", "F",
            "COLMAP model written: txt (cameras.txt ... in --output), bin (cameras.bin ... "
            "in --output/sparse/0/) or both",
            [](Options& o) -> std::string& { return o.model_format; }),
      Entry("ply-format", "F",
            "points.ply as binary (little-endian, float xyz, uchar rgb) or ascii (exact "
            "doubles)",
            [](Options& o) -> std::string& { return o.ply_format; }),
      Switch("no-retriangulate",
             "do not triangulate a track again from all its registered views when its point "
             "misses some of them (on by default: the new point must explain more views within "
             "2 px)",
             [](Options& o) -> bool& { return o.no_retriangulate; }),
      Switch("no-planar-pose-choice",
             "start a near-planar initial pair from the essential matrix's pose, without "
             "asking the other frames which of the plane's two poses they side with (on by "
             "default; docs/sfm.md)",
             [](Options& o) -> bool& { return o.no_planar_pose_choice; }),
      Switch("two-view-tracks",
             "also triangulate tracks seen in only two frames in a video (image sets matched "
             "across several frames always keep them; video leaves them out by default, as "
             "COLMAP: such a point has no third view to check it)",
             [](Options& o) -> bool& { return o.two_view_tracks; }),
  };
}

// The camera, the bundle adjustments and the initial pair.
std::vector<RunOption> CameraAndAdjustmentOptions() {
  return {
      Reported(
          Switch("refine-focal",
                 "refine the focal length in the global bundle adjustments (on by default without "
                 "a calibration; kept where the motion leaves it unobservable)",
                 [](Options& o) -> bool& { return o.refine_focal; })),
      Reported(Switch("refine-principal-point",
                      "refine the principal point in the global bundle adjustments",
                      [](Options& o) -> bool& { return o.refine_principal_point; })),
      Reported(
          Switch("refine-distortion",
                 "refine the camera model's distortion in the global bundle adjustments (on by "
                 "default without a calibration)",
                 [](Options& o) -> bool& { return o.refine_distortion; })),
      Reported(
          Switch("fixed-intrinsics",
                 "without a calibration, keep the default camera fixed instead of refining its "
                 "focal length and distortion",
                 [](Options& o) -> bool& { return o.camera.fixed_intrinsics; })),
      Reported(
          Switch("ignore-gt-intrinsics",
                 "use --gt for evaluation only, not as the camera's intrinsics (self-calibration "
                 "measured against the truth)",
                 [](Options& o) -> bool& { return o.camera.ignore_gt_intrinsics; })),
      Reported(Entry("local-ba-images", "N", "images in each local bundle adjustment",
                     [](Options& o) -> int& { return o.local_ba_images; })),
      Reported(Entry("global-ba-growth", "R",
                     "adjust the whole model whenever it has grown by this factor (and at the end)",
                     [](Options& o) -> double& { return o.global_ba_growth; })),
      Reported(Entry("global-ba-max-images", "N",
                     "long video: those adjustments hold only the N newest (key)frames variable, "
                     "the older ones seeing their points constant, and the final one adjusts the "
                     "model in overlapping windows of N (0: every frame, one adjustment)",
                     [](Options& o) -> int& { return o.global_ba_max_images; })),
  };
}

// Long video, the cache, and what is written for other tools.
std::vector<RunOption> VideoAndHandOffOptions() {
  return {
      Entry("init-angle", "DEG",
            "initial pair: a point's triangulation angle that counts fully towards the "
            "pair's parallax score",
            [](Options& o) -> double& { return o.init_angle; }),
      Entry("init-max-gap", "N",
            "initial pair: frames at most this far apart (0: no limit, the gap grows as "
            "far as the tracks reach)",
            [](Options& o) -> int& { return o.init_max_gap; }),
      Switch("keyframes",
             "long or dense video: only keyframes (a frame where the view has changed enough "
             "since the last one) add points and enter bundle adjustments; the other frames "
             "are posed against the map, so every frame keeps a pose (report.json "
             "'keyframes' lists them and why)",
             [](Options& o) -> bool& { return o.keyframes; }),
      Switch("loop-closure",
             "video that returns to where it has been: revisited places are found by "
             "appearance among the keyframes, verified by their 3-D points and closed (a "
             "Sim(3) pose graph, then the final adjustment) if it moves the camera by at "
             "most 10 % of the path between its two ends (a larger move is taken for a "
             "look-alike place); report.json 'loop_closure' lists the loops closed and "
             "rejected",
             [](Options& o) -> bool& { return o.loop_closure; }),
      Reported(Entry("loop-closure-max-move", "F",
                     "with --loop-closure: the largest move a loop may ask of the camera, as a "
                     "fraction of the path between its two ends (larger: drift that large is "
                     "corrected, but a look-alike place is more likely taken for a revisit)",
                     [](Options& o) -> double& { return o.loop_closure_max_move; })),
      Reported(Entry("max-working-size", "N",
                     "track and map frames whose larger side exceeds N pixels at N, and write the "
                     "models in the input's pixels (0: the input's size; --resize-height decides "
                     "when given)",
                     [](Options& o) -> int& { return o.max_working_size; })),
      Reported(Entry("min-registered", "F",
                     "exit 1 unless the largest model holds at least this fraction of the frames "
                     "(every model is written either way; 'success' needs 0.95)",
                     [](Options& o) -> double& { return o.min_registered; })),
      Reported(Entry("cache", "DIR",
                     "detections and tracks are kept in DIR and reused by a re-run with the same "
                     "frames, detector and tracker options (other mapper options reuse them; not "
                     "inside FRAMES or --output)",
                     [](Options& o) -> std::string& { return o.cache; })),
      Entry("plot-plane", "P",
            "trajectory plot plane: auto (x-z for KITTI, else the plane of largest "
            "spread), xz, xy or yz",
            [](Options& o) -> std::string& { return o.plot_plane; }),
      Switch("undistort",
             "also write the largest model's images undistorted with PINHOLE cameras in "
             "--output/dense/ (images/, sparse/, stereo/: the layout of COLMAP's "
             "image_undistorter, for colmap patch_match_stereo and other MVS tools)",
             [](Options& o) -> bool& { return o.undistort; }),
      Switch("compare-colmap",
             "also run COLMAP's mapper on the same tracks and write the side-by-side table "
             "--output/colmap_compare.md (.csv, .json); COLMAP's files go to --output/colmap/",
             [](Options& o) -> bool& { return o.compare_colmap; }),
      Switch("compare-colmap-sift",
             "also run COLMAP's own pipeline on the same frames with its defaults (SIFT, the "
             "sequential or exhaustive matcher as --matching chose, mapper; one thread unless "
             "--colmap-threads) and write the side-by-side table "
             "--output/colmap_sift_compare.md; COLMAP's files go to --output/colmap_sift/",
             [](Options& o) -> bool& { return o.compare_colmap_sift; }),
  };
}

}  // namespace

std::vector<RunOption> RunOptionTable() {
  std::vector<RunOption> table = InputOutputAndTrackOptions();
  for (auto part : {CameraAndAdjustmentOptions, VideoAndHandOffOptions}) {
    std::vector<RunOption> entries = part();
    table.insert(table.end(), std::make_move_iterator(entries.begin()),
                 std::make_move_iterator(entries.end()));
  }
  return table;
}

}  // namespace comic::sfm
