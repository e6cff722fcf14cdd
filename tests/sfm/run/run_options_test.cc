// ReconstructionRunOptions::Check: every bad option is refused before any work with a message that
// names the command line's flag (the Python module raises the same text), and touches no file.
#include "sfm/run/run_options.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "frontend/matching/pairing.h"
#include "io/core/error.h"

namespace comic::sfm {
namespace {

std::string CheckMessage(const std::function<void(ReconstructionRunOptions*)>& change) {
  ReconstructionRunOptions options;
  options.frames = "/nonexistent/frames";  // Check() does not look at files
  change(&options);
  try {
    options.Check();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument) << e.what();
    return e.what();
  }
  return "";
}

TEST(ReconstructionRunOptions, DefaultsPassAndNeedNoFiles) {
  EXPECT_EQ(CheckMessage([](ReconstructionRunOptions*) {}), "");
  EXPECT_EQ(ReconstructionRunOptions().DetectorList(), std::vector<std::string>{"harris"});
  ReconstructionRunOptions compare;
  compare.compare = true;
  compare.detectors = "comic,fast";
  EXPECT_EQ(compare.DetectorList(), (std::vector<std::string>{"comic", "fast"}));
}

TEST(ReconstructionRunOptions, MessagesNameTheFlags) {
  struct Case {
    std::function<void(ReconstructionRunOptions*)> change;
    std::string flag;
  };
  const std::vector<Case> cases = {
      {[](auto* o) { o->detector = "sift"; }, "--detector: "},
      {[](auto* o) {
         o->compare = true;
         o->detector = "harris";
       },
       "--detector and --compare"},
      {[](auto* o) { o->detectors = "harris"; }, "--detectors needs --compare"},
      {[](auto* o) { o->threads = -1; }, "--threads"},
      {[](auto* o) { o->sequence.max_pixels = 0; }, "--max-pixels"},
      {[](auto* o) { o->matching = "every"; }, "--matching"},
      {[](auto* o) { o->local_ba_images = 1; }, "--local-ba-images"},
      {[](auto* o) { o->global_ba_growth = 1.0; }, "--global-ba-growth"},
      {[](auto* o) { o->global_ba_max_images = -1; }, "--global-ba-max-images"},
      {[](auto* o) { o->global_ba_max_images = 1; }, "--global-ba-max-images"},
      {[](auto* o) { o->loop_closure_max_move = 0.0; }, "--loop-closure-max-move"},
      {[](auto* o) { o->init_angle = 90.0; }, "--init-angle"},
      {[](auto* o) { o->init_max_gap = -1; }, "--init-max-gap"},
      {[](auto* o) { o->max_working_size = 10; }, "--max-working-size"},
      {[](auto* o) { o->min_registered = 1.5; }, "--min-registered"},
      {[](auto* o) { o->tracker.given.insert("psychic-radius"); }, "--psychic-radius"},
      {[](auto* o) { o->camera.camera_model = "FISHEYE"; }, "--camera-model"},
      {[](auto* o) { o->model_format = "json"; }, "--model-format"},
      {[](auto* o) { o->ply_format = "big"; }, "--ply-format"},
      {[](auto* o) { o->colmap.overwrite = true; }, "--overwrite needs --colmap-db"},
      {[](auto* o) { o->colmap.colmap_threads = 0; }, "--colmap-threads"},
      {[](auto* o) {
         o->compare = true;
         o->colmap.colmap_db = "a.db";
       },
       "--colmap-db"},
      {[](auto* o) { o->compare_colmap = true; }, "--compare-colmap needs --output"},
      {[](auto* o) { o->write_frames = kFramesInOutput; }, "--write-frames"},
      {[](auto* o) {
         o->regions = "a";
         o->masks = "b";
       },
       "--regions and --masks"},
      {[](auto* o) { o->boundary_band = 0; }, "--boundary-band"},
      {[](auto* o) { o->plot_plane = "up"; }, "--plot-plane"},
  };
  for (const Case& c : cases) {
    const std::string message = CheckMessage(c.change);
    EXPECT_NE(message.find(c.flag), std::string::npos) << c.flag << ": " << message;
  }
}

// The self-calibration rule: a camera no calibration gave has its focal length and distortion
// refined (COLMAP's ba_refine_focal_length and ba_refine_extra_params); a calibration is held.
TEST(ReconstructionRunOptions, SelfCalibrationRefinesFocalAndDistortion) {
  const ReconstructionRunOptions options;
  const frontend::TrackerOptions tracker = DefaultRunTrackerOptions();
  const SequenceReconstructionOptions calibrated =
      MakeSequenceReconstructionOptions(options, tracker, /*refine_intrinsics=*/false);
  EXPECT_FALSE(calibrated.mapper.global_ba.refine_focal_length);
  EXPECT_FALSE(calibrated.mapper.global_ba.refine_extra_params);
  const SequenceReconstructionOptions self =
      MakeSequenceReconstructionOptions(options, tracker, /*refine_intrinsics=*/true);
  EXPECT_TRUE(self.mapper.global_ba.refine_focal_length);
  EXPECT_TRUE(self.mapper.global_ba.refine_extra_params);
  EXPECT_FALSE(self.mapper.global_ba.refine_principal_point);
  // Video leaves two-view tracks out; matching several frames keeps them.
  EXPECT_TRUE(calibrated.mapper.mapper.ignore_two_view_tracks);
  frontend::TrackerOptions window = tracker;
  window.match_window = 3;
  EXPECT_FALSE(MakeSequenceReconstructionOptions(options, window, false)
                   .mapper.mapper.ignore_two_view_tracks);
}

// --loop-closure and --loop-closure-max-move reach the mapper's loop closure.
TEST(ReconstructionRunOptions, LoopClosureOptionsReachTheMapper) {
  ReconstructionRunOptions options;
  const frontend::TrackerOptions tracker = DefaultRunTrackerOptions();
  EXPECT_FALSE(MakeSequenceReconstructionOptions(options, tracker, false).mapper.close_loops);
  options.loop_closure = true;
  options.loop_closure_max_move = 0.25;
  const SequenceReconstructionOptions made =
      MakeSequenceReconstructionOptions(options, tracker, false);
  EXPECT_TRUE(made.mapper.close_loops);
  EXPECT_EQ(made.mapper.loop_closure.max_move_per_path, 0.25);
}

// Guessed poses (interpolation, rotation only) are for video only (issue 47), whatever matched it
// (a video matched by descriptors is still a video); an image set, by its pairing (exhaustive, or
// the window auto chooses for a large set: frontend::IsVideo false), gets none.
TEST(ReconstructionRunOptions, PoseGapsAreFilledForVideoOnly) {
  const ReconstructionRunOptions options;
  const frontend::TrackerOptions tracker = DefaultRunTrackerOptions();
  const frontend::ImageSetMatchingOptions descriptors;
  EXPECT_TRUE(MakeSequenceReconstructionOptions(options, tracker, false, std::nullopt,
                                                /*video=*/true)
                  .mapper.fill_pose_gaps);
  EXPECT_TRUE(MakeSequenceReconstructionOptions(options, tracker, false, descriptors,
                                                /*video=*/true)
                  .mapper.fill_pose_gaps);
  EXPECT_FALSE(MakeSequenceReconstructionOptions(options, tracker, false, std::nullopt,
                                                 /*video=*/false)
                   .mapper.fill_pose_gaps);
  EXPECT_FALSE(MakeSequenceReconstructionOptions(options, tracker, false, descriptors,
                                                 /*video=*/false)
                   .mapper.fill_pose_gaps);

  frontend::PairingChoice pairing;
  pairing.requested = frontend::ParsePairing("auto");
  pairing.chosen = frontend::ParsePairing("sequential");
  EXPECT_TRUE(frontend::IsVideo(pairing));
  pairing.chosen = frontend::ParsePairing("exhaustive");
  EXPECT_FALSE(frontend::IsVideo(pairing));
  pairing.chosen = frontend::ParsePairing("window:20");  // auto's window for a large image set
  EXPECT_FALSE(frontend::IsVideo(pairing));
  pairing.requested = frontend::ParsePairing("window:5");  // the user's: ordered frames
  pairing.chosen = pairing.requested;
  EXPECT_TRUE(frontend::IsVideo(pairing));
}

}  // namespace
}  // namespace comic::sfm
