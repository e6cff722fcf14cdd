// Tracks judged against exact truth (sfm/evaluation/boundary_tracks.h), on synthetic tracks with
// known answers: a feature that follows a point of a wall, one that stays put in the image while
// the camera moves (it slides), boundary labels by majority, and a track without depth that is
// judged by triangulation.
#include "sfm/evaluation/boundary_tracks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

constexpr int kFrames = 6;
constexpr double kWall = 5.0;  // a fronto-parallel wall at z = 5 in the world

Camera TestCamera() {
  return Camera::FromParams(CameraModelId::kPinhole, 64, 48, {50, 50, 31.5, 23.5});
}

// The camera moves sideways by 0.2 per frame, looking along +z.
std::vector<Rigid3d> Poses() {
  std::vector<Rigid3d> poses;
  for (int k = 0; k < kFrames; ++k) {
    poses.emplace_back(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.2 * k, 0.0, 0.0));
  }
  return poses;
}

frontend::Feature At(const Eigen::Vector2d& p) {
  frontend::Feature f;
  f.x = static_cast<float>(p.x());
  f.y = static_cast<float>(p.y());
  return f;
}

struct Fixture {
  frontend::FeatureTracks tracks;
  std::vector<Rigid3d> poses = Poses();
  Camera camera = TestCamera();
};

// Track 0 follows the wall point (0.3, 0.1, 5); track 1 stays at pixel (10, 10); track 2 follows
// a point 2.5 away where the depth is unknown (NaN there); track 3 has two observations.
Fixture MakeTracks() {
  Fixture f;
  f.tracks.image_size = cv::Size(64, 48);
  f.tracks.features.resize(kFrames);
  const Eigen::Vector3d wall_point(0.3, 0.1, kWall);
  const Eigen::Vector3d near_point(-0.4, 0.2, 2.5);
  for (int k = 0; k < kFrames; ++k) {
    const auto project = [&](const Eigen::Vector3d& x) {
      const Eigen::Vector3d c = f.poses[k] * x;
      return f.camera.ImageFromCam({c.x() / c.z(), c.y() / c.z()});
    };
    f.tracks.features[k] = {At(project(wall_point)), At({10.0, 10.0}), At(project(near_point)),
                            At({50.0, 40.0})};
  }
  for (int t = 0; t < 3; ++t) {
    frontend::Track track;
    for (int k = 0; k < kFrames; ++k) track.observations.push_back({k, t});
    f.tracks.tracks.push_back(track);
  }
  f.tracks.tracks.push_back({{{0, 3}, {1, 3}}});
  return f;
}

FrameTruthFn Truth(const std::vector<int>& band_frames, bool sky_at_track1 = false) {
  return [band_frames, sky_at_track1](int frame) {
    FrameTruth truth;
    truth.depth = cv::Mat(48, 64, CV_32F, cv::Scalar(kWall));
    // No depth known where the near point is first seen (a composited object), left of x = 30.
    truth.depth(cv::Rect(0, 20, 30, 28)).setTo(std::numeric_limits<float>::quiet_NaN());
    if (sky_at_track1) truth.depth(cv::Rect(5, 5, 10, 10)).setTo(0.0f);
    truth.band = cv::Mat::zeros(48, 64, CV_8UC1);
    // The pixel (10, 10) is in the band in the frames listed.
    if (std::find(band_frames.begin(), band_frames.end(), frame) != band_frames.end()) {
      truth.band.at<uint8_t>(10, 10) = 255;
    }
    return truth;
  };
}

TEST(BoundaryTracks, FollowingSlidingAndTriangulatedTracks) {
  const Fixture f = MakeTracks();
  const BoundaryTrackEvaluation e =
      EvaluateBoundaryTracks(f.tracks, f.camera, f.poses, Truth({0, 1, 2}), BoundaryTrackOptions());
  ASSERT_EQ(e.tracks.size(), 4u);
  EXPECT_TRUE(e.tracks[0].classified);
  EXPECT_TRUE(e.tracks[0].follows);
  EXPECT_LT(e.tracks[0].drift_px, 1e-3);
  // Staying at (10, 10) while the camera moves 1 m sideways: a wall point moves 50 px * 0.2 m /
  // 5 m = 2 px a frame, so the best candidate (the one seen there in the middle frame, 3) is off
  // by 6, 4, 2, 0, 2, 4 px: RMS 3.56, largest 6.
  EXPECT_TRUE(e.tracks[1].classified);
  EXPECT_FALSE(e.tracks[1].follows);
  EXPECT_NEAR(e.tracks[1].drift_px, std::sqrt(76.0 / 6.0), 1e-6);
  EXPECT_NEAR(e.tracks[1].worst_px, 6.0, 1e-6);
  // Unknown depth where it starts (its later anchors see the wall behind it): judged by the point
  // its observations triangulate.
  EXPECT_TRUE(e.tracks[2].classified);
  EXPECT_TRUE(e.tracks[2].follows);
  EXPECT_FALSE(e.tracks[3].classified);  // two observations only
  // Track 1 is in the band in 3 of its 6 frames: at least half, so a boundary track.
  EXPECT_TRUE(e.tracks[1].boundary);
  EXPECT_FALSE(e.tracks[0].boundary);
  EXPECT_EQ(e.num_features, 4u * kFrames);
  EXPECT_EQ(e.num_boundary_features, 3u);
  EXPECT_EQ(e.boundary.num_tracks, 1u);
  EXPECT_EQ(e.boundary.num_following, 0u);
  EXPECT_EQ(e.other.num_tracks, 3u);
  EXPECT_EQ(e.other.num_classified, 2u);
  EXPECT_EQ(e.other.num_following, 2u);
  EXPECT_DOUBLE_EQ(e.other.mean_length, (6 + 6 + 2) / 3.0);
  EXPECT_NEAR(e.boundary_area_fraction, 0.5 / (64 * 48), 1e-12);
}

TEST(BoundaryTracks, AFeatureThatStaysPutFollowsTheSkyUnderTranslation) {
  // Nothing drawn around (10, 10): the sky, a point at infinity, which a camera that only
  // translates sees at the same pixel. Staying put is then following it.
  const Fixture f = MakeTracks();
  const BoundaryTrackEvaluation e = EvaluateBoundaryTracks(
      f.tracks, f.camera, f.poses, Truth({}, /*sky_at_track1=*/true), BoundaryTrackOptions());
  EXPECT_TRUE(e.tracks[1].classified);
  EXPECT_TRUE(e.tracks[1].follows);
  EXPECT_LT(e.tracks[1].drift_px, 1e-3);
}

TEST(BoundaryTracks, FewerBandFramesThanHalfIsNotABoundaryTrack) {
  const Fixture f = MakeTracks();
  const BoundaryTrackEvaluation e =
      EvaluateBoundaryTracks(f.tracks, f.camera, f.poses, Truth({0, 1}), BoundaryTrackOptions());
  EXPECT_FALSE(e.tracks[1].boundary);
  EXPECT_EQ(e.boundary.num_tracks, 0u);
}

TEST(BoundaryTracks, ATighterToleranceOrBadInputsAreHandled) {
  const Fixture f = MakeTracks();
  BoundaryTrackOptions options;
  options.follow_tolerance_px = 20.0;  // loose enough that even staying put "follows"
  EXPECT_TRUE(
      EvaluateBoundaryTracks(f.tracks, f.camera, f.poses, Truth({}), options).tracks[1].follows);
  options.follow_tolerance_px = 0.0;
  EXPECT_THROW(EvaluateBoundaryTracks(f.tracks, f.camera, f.poses, Truth({}), options), Error);
  std::vector<Rigid3d> too_few = f.poses;
  too_few.pop_back();
  EXPECT_THROW(
      EvaluateBoundaryTracks(f.tracks, f.camera, too_few, Truth({}), BoundaryTrackOptions()),
      Error);
}

}  // namespace
}  // namespace comic::sfm
