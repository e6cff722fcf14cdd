#include "frontend/evaluation/track_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "frontend/evaluation/epipolar_check.h"
#include "io/core/error.h"
#include "io/datasets/kitti_odometry.h"
#include "io/image/image_sequence.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

TrackEvaluationOptions BaselineOptions(int n) {
  TrackEvaluationOptions options;
  options.detectors = {"harris", "hessian", "fast", "mser"};
  options.num_features = n;
  return options;
}

io::ImageSequence ExampleClip(int last, int height) {
  io::ImageSequenceOptions options;
  options.last_frame = last;
  options.resize_height = height;
  return io::ImageSequence::Open(test::ExampleDir() + "/image_l", options);
}

TEST(TrackEvaluation, EqualisesEveryDetectorOnTheRegionOfFrameZero) {
  const io::ImageSequence clip = ExampleClip(5, 185);
  const cv::Size size = clip.FrameSize();
  // Object region: the middle third of the frame.
  const RegionMaskSource regions = [size](size_t) {
    cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
    mask(cv::Rect(size.width / 3, 0, size.width / 3, size.height)).setTo(255);
    return mask;
  };
  TrackEvaluationOptions options = BaselineOptions(40);
  options.ns = {1, 5};
  const TrackEvaluation evaluation = EvaluateTracking(clip, regions, std::nullopt, options);
  ASSERT_EQ(evaluation.rows.size(), 4u);
  EXPECT_EQ(evaluation.reference_count, 40);
  EXPECT_TRUE(evaluation.has_regions);
  for (const EvaluationRow& row : evaluation.rows) {
    EXPECT_EQ(row.cost, MatchCost::kFullPatch);
    ASSERT_EQ(row.labels.size(), 6u);
    // Frame 0: exactly the counted features inside the region (FAST's integer scores may tie).
    int in_region = 0;
    for (RegionLabel label : row.labels[0]) in_region += label != RegionLabel::kOutside ? 1 : 0;
    EXPECT_EQ(in_region, row.cut.count) << row.label;
    if (row.detector != "fast" && row.cut.reached) {
      EXPECT_EQ(row.cut.count, 40) << row.label;
    }
    ASSERT_EQ(row.scores.size(), 2u);
    EXPECT_EQ(row.scores[1].n, 5);
    EXPECT_EQ(row.scores[1].samples.size(), 1u);  // start frame 0 only in 6 frames
    EXPECT_EQ(row.scores[1].samples[0].detections[2], in_region);
    EXPECT_GE(row.scores[0].overall.mean_m_score, row.scores[1].overall.mean_m_score);
  }
  const io::ReportTable table = ScoreTable(evaluation, 5);
  EXPECT_EQ(table.NumRows(), 4u);
  EXPECT_EQ(std::get<std::string>(table.At(0, 0)), "harris");
  EXPECT_THROW(ScoreTable(evaluation, 3), Error);
  EXPECT_THROW(PrecisionTable(evaluation, 5), Error);  // no ground truth
  const nlohmann::json json = EvaluationToJson(evaluation);
  EXPECT_EQ(json["rows"].size(), 4u);
}

TEST(TrackEvaluation, EpipolarPrecisionWithKittiPoses) {
  const io::ImageSequence clip = ExampleClip(4, 185);
  EpipolarGroundTruth truth;
  truth.K = ScaleIntrinsics(io::ReadKittiIntrinsics(test::ExampleDir() + "/calib.txt"),
                            clip.SourceFrameSize(), clip.FrameSize());
  const auto poses = io::ReadKittiPoses(test::ExampleDir() + "/poses.txt");
  truth.world_from_camera.assign(poses.begin(), poses.begin() + 5);
  TrackEvaluationOptions options = BaselineOptions(150);
  options.detectors = {"harris"};
  options.ns = {1};
  options.epipolar_tolerance = 1.5;
  options.target_precision = 0.5;
  const TrackEvaluation evaluation = EvaluateTracking(clip, {}, truth, options);
  const PrecisionSummary& p = *evaluation.rows[0].precision;
  EXPECT_GT(p.at_threshold.accepted, 4 * 10);
  EXPECT_GE(p.all_mutual.accepted, p.at_threshold.accepted);
  EXPECT_GT(p.at_threshold.precision, 0.6);
  ASSERT_TRUE(p.at_target.has_value());
  EXPECT_GE(p.at_target->precision, 0.5);
  ASSERT_EQ(p.scores_at_target.size(), 1u);
  EXPECT_EQ(PrecisionTable(evaluation, 1).NumRows(), 1u);
  // Wrong number of poses.
  truth.world_from_camera.pop_back();
  EXPECT_THROW(EvaluateTracking(clip, {}, truth, options), Error);
}

TEST(TrackEvaluation, BadOptionsAndInputs) {
  const io::ImageSequence clip = ExampleClip(3, 185);
  TrackEvaluationOptions options = BaselineOptions(20);
  options.ns = {5};
  try {
    EvaluateTracking(clip, {}, std::nullopt, options);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("n = 5 needs at least 6 frames, the sequence has 4"),
              std::string::npos)
        << e.what();
  }
  options = BaselineOptions(0);  // no CoMIC to take N from
  EXPECT_THROW(options.Check(), Error);
  options = BaselineOptions(20);
  options.detectors = {"harris", "harris"};
  EXPECT_THROW(options.Check(), Error);
  options.detectors = {"orb"};
  EXPECT_THROW(options.Check(), Error);
  options = BaselineOptions(20);
  options.matcher.gate = CandidateGate::kRectifiedStereo;
  EXPECT_THROW(options.Check(), Error);
  // A region mask of the wrong size.
  options = BaselineOptions(20);
  options.ns = {1};
  const RegionMaskSource wrong = [](size_t) { return cv::Mat(10, 10, CV_8UC1, cv::Scalar(255)); };
  EXPECT_THROW(EvaluateTracking(clip, wrong, std::nullopt, options), Error);
}

}  // namespace
}  // namespace comic::frontend
