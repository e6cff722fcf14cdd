// End to end on real video: the bundled KITTI example (always) and the 51-frame KITTI clip of
// ../shared/data (the acceptance case: forward motion, every frame in one model, ATE < 1 % of
// the path); masks of moving objects remove the features they cover on both front-end paths.
#include "sfm/sequence_reconstruction.h"

#include <gtest/gtest.h>

#include "frontend/detector_factory.h"
#include "frontend/feature_masks.h"
#include "io/core/error.h"
#include "io/datasets/ground_truth_cameras.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/trajectory_evaluation.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

struct KittiRun {
  SequenceReconstruction run;
  std::optional<TrajectoryEvaluation> evaluation;
};

KittiRun ReconstructKitti(const std::string& folder) {
  const io::ImageSequence sequence = io::ImageSequence::Open(folder + "/image_l");
  std::vector<int> indices(sequence.NumFrames());
  for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<int>(i);
  const FrameGroundTruth truth = MatchGroundTruthToFrames(
      io::ReadGroundTruthCameras(folder + "/poses.txt"), sequence.FrameNames(), indices,
      sequence.SourceFrameSize(), sequence.FrameSize());
  EXPECT_TRUE(truth.camera.has_value());  // from calib.txt beside poses.txt
  const auto detector = frontend::MakeDetector("harris");
  KittiRun result;
  result.run =
      ReconstructSequence(sequence, *detector, *truth.camera, SequenceReconstructionOptions());
  result.evaluation = EvaluateTrajectory(
      RegisteredPosesByName(result.run.mapping.reconstruction, sequence.FrameNames()),
      truth.cams_from_world);
  return result;
}

TEST(SequenceReconstruction, BundledExampleRegistersEveryFrame) {
  const KittiRun kitti = ReconstructKitti(test::ExampleDir());
  const IncrementalReconstruction& mapping = kitti.run.mapping;
  ASSERT_EQ(mapping.status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(mapping.reconstruction.NumRegisteredImages(), 12u);
  EXPECT_EQ(kitti.run.tracks.NumFrames(), 12u);
  EXPECT_EQ(kitti.run.detector_name, "harris");
  EXPECT_GT(mapping.reconstruction.NumPoints3D(), 500u);
  EXPECT_LT(mapping.reconstruction.ComputeMeanReprojectionError(), 1.0);
  ASSERT_TRUE(kitti.evaluation.has_value());
  EXPECT_EQ(kitti.evaluation->frames.size(), 12u);
  EXPECT_LT(kitti.evaluation->ate_fraction_of_path, 0.01);
  EXPECT_LT(kitti.evaluation->mean_rotation_error_deg, 1.0);
  // Colours come from the (grey) frames: equal channels, not all black.
  int lit = 0;
  for (const auto& [id, point] : mapping.reconstruction.points3D()) {
    EXPECT_EQ(point.color[0], point.color[1]);
    EXPECT_EQ(point.color[1], point.color[2]);
    lit += point.color[0] > 0;
  }
  EXPECT_GT(lit, static_cast<int>(mapping.reconstruction.NumPoints3D()) / 2);
  EXPECT_GT(kitti.run.tracking_time_s, 0.0);
  EXPECT_GE(kitti.run.wall_time_s, kitti.run.tracking_time_s + kitti.run.mapping_time_s);
}

TEST(SequenceReconstruction, KittiClipForwardMotionAcceptance) {
  COMIC_REQUIRE_SHARED_DATA();
  const KittiRun kitti = ReconstructKitti(test::SharedDataDir() + "/kitti_odometry_seq06_000-050");
  const IncrementalReconstruction& mapping = kitti.run.mapping;
  ASSERT_EQ(mapping.status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(mapping.reconstruction.NumRegisteredImages(), 51u);
  EXPECT_TRUE(mapping.unregistered_frames.empty());
  EXPECT_EQ(mapping.num_models, 1);
  ASSERT_TRUE(kitti.evaluation.has_value());
  EXPECT_NEAR(kitti.evaluation->path_length, 59.9, 0.1);
  EXPECT_LT(kitti.evaluation->ate_fraction_of_path, 0.01);
  EXPECT_LT(mapping.reconstruction.ComputeMeanReprojectionError(), 1.0);
}

TEST(SequenceReconstruction, CameraMustMatchTheFrames) {
  const io::ImageSequence sequence = io::ImageSequence::Open(test::ExampleDir() + "/image_l");
  const auto detector = frontend::MakeDetector("harris");
  EXPECT_THROW(ReconstructSequence(sequence, *detector, Camera::FromImageSize(640, 480),
                                   SequenceReconstructionOptions()),
               Error);
}

// The two halves a track cache sits between: tracks of other frames are refused before mapping.
TEST(SequenceReconstruction, TracksMustBeOfTheFrames) {
  io::ImageSequenceOptions three;
  three.last_frame = 2;
  const io::ImageSequence sequence =
      io::ImageSequence::Open(test::ExampleDir() + "/image_l", three);
  const auto detector = frontend::MakeDetector("harris");
  const SequenceReconstructionOptions options;
  SequenceTracking tracking = TrackFrames(sequence, *detector, options);
  EXPECT_EQ(tracking.tracks.NumFrames(), 3u);
  EXPECT_FALSE(tracking.tracks.tracks.empty());
  tracking.tracks.features.pop_back();
  tracking.tracks.frame_names.pop_back();
  const Camera camera =
      Camera::FromImageSize(sequence.FrameSize().width, sequence.FrameSize().height);
  try {
    ReconstructFromTracks(sequence, *detector, camera, options, std::move(tracking));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("tracks of 2 frames for a sequence of 3"),
              std::string::npos)
        << e.what();
  }
}

// Masks over the left half of three example frames (issue 47): on the patch tracker's path and
// on the descriptor matcher's, every feature the masks (with their 2 px margin) cover is gone,
// every other feature is kept as it was without masks, in its order, and the count of dropped
// features is the count of the detector's candidates in the masks.
TEST(SequenceReconstruction, MasksRemoveTheFeaturesTheyCoverOnBothPaths) {
  io::ImageSequenceOptions three;
  three.last_frame = 2;
  const io::ImageSequence sequence =
      io::ImageSequence::Open(test::ExampleDir() + "/image_l", three);
  const cv::Size size = sequence.FrameSize();
  std::vector<cv::Mat> object(3, cv::Mat(size, CV_8UC1, cv::Scalar(0)));
  for (int f = 0; f < 3; ++f) {
    object[f] = cv::Mat(size, CV_8UC1, cv::Scalar(0));
    object[f].colRange(0, size.width / 2 + 7 * f).setTo(255);  // moves a little each frame
  }
  const auto masks =
      std::make_shared<const frontend::FeatureMasks>(object, frontend::FeatureMaskOptions());
  const auto detector = frontend::MakeDetector("harris");
  int64_t candidates_in_masks = 0;
  for (int f = 0; f < 3; ++f) {
    for (const frontend::Feature& feature : detector->Detect(sequence.ReadFrame(f).gray)) {
      candidates_in_masks += masks->Drops(f, feature.x, feature.y);
    }
  }
  ASSERT_GT(candidates_in_masks, 100);

  SequenceReconstructionOptions patches;
  patches.tracker.max_features = 0;  // no cap: what the masks leave is kept whole
  SequenceReconstructionOptions descriptors;
  descriptors.image_set.emplace();
  descriptors.image_set->max_features = 0;
  for (SequenceReconstructionOptions options : {patches, descriptors}) {
    SCOPED_TRACE(options.image_set ? "descriptors" : "patches");
    const SequenceTracking plain = TrackFrames(sequence, *detector, options);
    EXPECT_EQ(plain.masked_features, 0);
    options.feature_masks = masks;
    const SequenceTracking masked = TrackFrames(sequence, *detector, options);
    EXPECT_EQ(masked.masked_features, candidates_in_masks);
    for (int f = 0; f < 3; ++f) {
      std::vector<cv::Point2f> expected, kept;
      for (const frontend::Feature& feature : plain.tracks.features[f]) {
        if (!masks->Drops(f, feature.x, feature.y)) expected.push_back(feature.Position());
      }
      for (const frontend::Feature& feature : masked.tracks.features[f]) {
        EXPECT_FALSE(masks->Drops(f, feature.x, feature.y)) << feature.x << " " << feature.y;
        kept.push_back(feature.Position());
      }
      EXPECT_EQ(kept, expected) << "frame " << f;
      EXPECT_LT(kept.size(), plain.tracks.features[f].size());
    }
    EXPECT_FALSE(masked.tracks.tracks.empty());
  }
  // Masks of other frames are refused.
  SequenceReconstructionOptions wrong = patches;
  wrong.feature_masks = std::make_shared<const frontend::FeatureMasks>(
      std::vector<cv::Mat>(2, object[0]), frontend::FeatureMaskOptions());
  EXPECT_THROW(TrackFrames(sequence, *detector, wrong), Error);
}

}  // namespace
}  // namespace comic::sfm
