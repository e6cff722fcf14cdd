// Synthetic scenes: tracks a tracker could have produced, with the noise and outliers asked for.
#include "sfm/synthetic_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <random>

#include "frontend/matching/pairing.h"
#include "io/core/error.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {
namespace {

TEST(SyntheticScene, TracksMatchTheirPointsUpToNoiseAndOutliers) {
  SyntheticSceneOptions options;
  options.num_frames = 10;
  options.num_points = 300;
  const SyntheticScene scene = MakeSyntheticScene(options);
  EXPECT_NO_THROW(scene.tracks.Check());
  ASSERT_EQ(scene.cams_from_world.size(), 10u);
  ASSERT_EQ(scene.track_point_index.size(), scene.tracks.tracks.size());
  size_t observations = 0, outliers = 0;
  double squared_error = 0;
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : scene.tracks.tracks[t].observations) {
      const frontend::Feature& feature = scene.tracks.FeatureOf(obs);
      const auto projection = ProjectPoint(scene.camera, scene.cams_from_world[obs.frame],
                                           scene.points3D[scene.track_point_index[t]]);
      ASSERT_TRUE(projection.has_value());
      ++observations;
      if (scene.is_outlier[obs.frame][obs.feature]) {
        ++outliers;
      } else {
        squared_error += (*projection - Eigen::Vector2d(feature.x, feature.y)).squaredNorm();
      }
    }
  }
  const double outlier_ratio = static_cast<double>(outliers) / observations;
  EXPECT_NEAR(outlier_ratio, 0.1, 0.02);
  // Per-axis noise of 0.5 px: mean squared 2-D error 0.5.
  EXPECT_NEAR(squared_error / (observations - outliers), 0.5, 0.05);
  EXPECT_GT(scene.PathLength(), 5.0);
}

// The frames a camera would see: each observation of a track drawn as a blob whose grey value is
// its 3-D point's, on a mid-grey background, softened.
std::vector<cv::Mat> RenderFrames(const SyntheticScene& scene) {
  const frontend::FeatureTracks& tracks = scene.tracks;
  std::vector<cv::Mat> frames(tracks.NumFrames());
  for (cv::Mat& frame : frames) frame = cv::Mat(tracks.image_size, CV_8U, cv::Scalar(128));
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    const int grey = 20 + (scene.track_point_index[t] * 97) % 216;
    for (const frontend::TrackObservation& obs : tracks.tracks[t].observations) {
      const frontend::Feature& f = tracks.FeatureOf(obs);
      cv::circle(frames[obs.frame], cv::Point(cvRound(f.x), cvRound(f.y)), 6, cv::Scalar(grey),
                 cv::FILLED);
    }
  }
  for (cv::Mat& frame : frames) cv::GaussianBlur(frame, frame, cv::Size(), 3.0);
  return frames;
}

// Issue 16: --matching auto on a synthetic video (the hand-held scene's frames in order) and on
// the same frames shuffled (an image set).
TEST(SyntheticScene, AutoPairingPicksSequentialForTheVideoAndExhaustiveShuffled) {
  SyntheticSceneOptions options;
  options.num_frames = 24;
  options.num_points = 800;
  options.outlier_ratio = 0.0;
  options.track_break_probability = 0.0;
  const std::vector<cv::Mat> frames = RenderFrames(MakeSyntheticScene(options));
  auto thumbnails = [](const std::vector<cv::Mat>& images) {
    std::vector<cv::Mat> out;
    for (const cv::Mat& image : images) out.push_back(frontend::MakeThumbnail(image, 32));
    return out;
  };
  const frontend::PairingChoice video =
      frontend::ChoosePairing(thumbnails(frames), frontend::ParsePairing("auto"));
  EXPECT_EQ(video.chosen.mode, frontend::PairingMode::kSequential) << video.reason;

  std::vector<cv::Mat> shuffled = frames;
  std::mt19937 rng(7);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  const frontend::PairingChoice set =
      frontend::ChoosePairing(thumbnails(shuffled), frontend::ParsePairing("auto"));
  EXPECT_EQ(set.chosen.mode, frontend::PairingMode::kExhaustive) << set.reason;
  EXPECT_LT(set.gain, video.gain - 0.3) << video.reason << " / " << set.reason;
}

TEST(SyntheticScene, SeededAndValidated) {
  SyntheticSceneOptions options;
  options.num_frames = 5;
  options.num_points = 50;
  const SyntheticScene a = MakeSyntheticScene(options);
  const SyntheticScene b = MakeSyntheticScene(options);
  ASSERT_EQ(a.tracks.features.size(), b.tracks.features.size());
  EXPECT_EQ(a.tracks.features[3][7].x, b.tracks.features[3][7].x);
  options.seed = 2;
  const SyntheticScene c = MakeSyntheticScene(options);
  EXPECT_NE(a.points3D[0], c.points3D[0]);
  options.outlier_ratio = 1.0;
  EXPECT_THROW(MakeSyntheticScene(options), Error);
  // Forward motion goes 1.2 m per frame along +z.
  SyntheticSceneOptions forward;
  forward.motion = SyntheticMotion::kForward;
  forward.num_frames = 6;
  forward.num_points = 50;
  const SyntheticScene f = MakeSyntheticScene(forward);
  EXPECT_NEAR(ProjectionCenter(f.cams_from_world[5]).z(), 6.0, 1e-9);
}

}  // namespace
}  // namespace comic::sfm
