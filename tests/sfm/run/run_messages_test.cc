// The lines comic_sfm prints while a run goes (sfm/run/run_messages.h).
#include "sfm/run/run_messages.h"

#include <gtest/gtest.h>

namespace comic::sfm {
namespace {

TEST(RunMessages, FrameRegisteredLineNamesTheFrameAndTheModel) {
  MapperProgress progress;
  progress.frame_name = "000004.png";
  progress.num_registered = 5;
  progress.num_frames = 12;
  progress.num_points3D = 612;
  progress.num_pose_inliers = 270;
  EXPECT_EQ(FrameRegisteredLine("harris", progress),
            "[harris] registered 000004.png: 5/12 frames, 612 points, 270 PnP inliers");
  progress.attempt = 1;
  progress.merged = true;
  EXPECT_EQ(FrameRegisteredLine("comic", progress),
            "[comic] model 2: registered 000004.png: 5/12 frames, 612 points (merged from an "
            "earlier model)");
}

TEST(RunMessages, AdjustmentProgressLineSaysHowFarTheSolveIs) {
  BundleAdjustmentProgress progress;
  progress.iteration = 7;
  progress.max_num_iterations = 50;
  progress.num_variable_images = 196;
  progress.num_points = 14210;
  progress.elapsed_s = 2.26;
  EXPECT_EQ(AdjustmentProgressLine("harris", progress),
            "[harris] bundle adjustment of 196 frames, 14210 points: iteration 7 of 50, 2.3 s");
}

}  // namespace
}  // namespace comic::sfm
