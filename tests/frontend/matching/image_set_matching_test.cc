#include "frontend/matching/image_set_matching.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "frontend/detector_factory.h"
#include "io/core/error.h"
#include "io/datasets/ground_truth_cameras.h"
#include "io/datasets/kitti_odometry.h"
#include "io/image/image_io.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

// Epipolar distance (pixels) of x2 from the line of x1 for views with cam_from_world (R, t) and
// intrinsics K (OpenCV pixel convention).
struct View {
  cv::Matx33d R;
  cv::Vec3d t;
};
double EpipolarDistance(const cv::Matx33d& K, const View& a, const View& b, cv::Point2f x1,
                        cv::Point2f x2) {
  const cv::Matx33d R = b.R * a.R.t();
  const cv::Vec3d t = b.t - R * a.t;
  const cv::Matx33d tx(0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0);
  const cv::Matx33d F = K.inv().t() * tx * R * K.inv();
  const cv::Vec3d line = F * cv::Vec3d(x1.x, x1.y, 1.0);
  return std::abs(line.dot(cv::Vec3d(x2.x, x2.y, 1.0))) / std::hypot(line[0], line[1]);
}

// Square crops of the bundled KITTI frames, one turned by 90 degrees, listed out of order, with
// the true camera of each (in the crop's pixels, before turning) and how to undo the turn.
struct KittiSet {
  std::vector<cv::Mat> grays;
  std::vector<View> views;
  std::vector<bool> turned;
  cv::Matx33d K;
};

KittiSet MakeKittiSet() {
  const std::string dir = test::ExampleDir();
  const std::vector<cv::Matx34d> poses = io::ReadKittiPoses(dir + "/poses.txt");
  KittiSet set;
  set.K = io::ReadKittiIntrinsics(dir + "/calib.txt", 0);
  const cv::Rect crop(430, 0, 370, 370);  // around the principal point (601.9, 183.1)
  set.K(0, 2) -= crop.x;
  for (int frame : {2, 0, 1}) {
    char name[32];
    std::snprintf(name, sizeof(name), "/image_l/%06d.png", frame);
    cv::Mat gray = io::LoadImage(dir + name, 0, 1 << 30).gray(crop).clone();
    const bool turn = frame == 1;
    if (turn) cv::rotate(gray, gray, cv::ROTATE_90_CLOCKWISE);  // (x, y) -> (369 - y, x)
    set.grays.push_back(gray);
    set.turned.push_back(turn);
    const cv::Matx33d world_from_cam = poses[frame].get_minor<3, 3>(0, 0);
    const cv::Vec3d center(poses[frame](0, 3), poses[frame](1, 3), poses[frame](2, 3));
    set.views.push_back({world_from_cam.t(), -(world_from_cam.t() * center)});
  }
  return set;
}

// A feature position in the crop before turning.
cv::Point2f Unturned(const Feature& f, bool turned) {
  return turned ? cv::Point2f(f.y, 369.0f - f.x) : f.Position();
}

TEST(ImageSetMatching, MatchesViewsInAnyOrderAndTurned) {
  const KittiSet set = MakeKittiSet();
  ImageSetMatchingOptions options;
  options.max_features = 1000;
  const auto detector = MakeDetector("harris");
  const ImageSetMatching result = MatchImageFrames(set.grays, *detector, options, {"a", "b", "c"});
  EXPECT_EQ(result.summary.num_pairs, 3);
  EXPECT_EQ(result.summary.num_verified_pairs, 3);
  ASSERT_EQ(result.verified_pairs.size(), 3u);
  ASSERT_TRUE(result.tracks.HasDescriptors());
  EXPECT_NO_THROW(result.tracks.Check());
  for (const FramePairMatches& pair : result.verified_pairs) {
    int correct = 0;
    for (const PatchMatch& m : pair.matches) {
      const cv::Point2f x1 =
          Unturned(result.tracks.features[pair.frame1][m.index1], set.turned[pair.frame1]);
      const cv::Point2f x2 =
          Unturned(result.tracks.features[pair.frame2][m.index2], set.turned[pair.frame2]);
      correct +=
          EpipolarDistance(set.K, set.views[pair.frame1], set.views[pair.frame2], x1, x2) < 3.0;
    }
    // The turned view matches as well as the others, and the verified matches are right (within
    // 3 px: a single-scale corner shifts by a pixel or two as the car drives 2.4 m towards it).
    EXPECT_GE(pair.matches.size(), 150u) << pair.frame1 << "-" << pair.frame2;
    EXPECT_GE(correct, 0.8 * pair.matches.size()) << pair.frame1 << "-" << pair.frame2;
  }
  // Tracks come from the verified matches: some run through all three views.
  int three_view = 0;
  for (const Track& track : result.tracks.tracks) three_view += track.Length() == 3;
  EXPECT_GT(three_view, 20);
}

TEST(ImageSetMatching, SameResultForAnyThreadCount) {
  const KittiSet set = MakeKittiSet();
  ImageSetMatchingOptions options;
  options.max_features = 500;
  const auto detector = MakeDetector("harris");
  options.num_threads = 1;
  const ImageSetMatching one = MatchImageFrames(set.grays, *detector, options);
  options.num_threads = 3;
  const ImageSetMatching three = MatchImageFrames(set.grays, *detector, options);
  ASSERT_EQ(one.tracks.tracks.size(), three.tracks.tracks.size());
  for (size_t t = 0; t < one.tracks.tracks.size(); ++t) {
    ASSERT_EQ(one.tracks.tracks[t].observations.size(), three.tracks.tracks[t].observations.size());
    for (size_t k = 0; k < one.tracks.tracks[t].observations.size(); ++k) {
      EXPECT_EQ(one.tracks.tracks[t].observations[k].feature,
                three.tracks.tracks[t].observations[k].feature);
    }
  }
  for (size_t f = 0; f < one.tracks.descriptors.size(); ++f) {
    EXPECT_EQ(cv::norm(one.tracks.descriptors[f], three.tracks.descriptors[f], cv::NORM_INF), 0.0);
  }
  EXPECT_EQ(one.summary.num_verified_matches, three.summary.num_verified_matches);
}

TEST(ImageSetMatching, CombinedDetectorMatchesEachComponentOnItsOwn) {
  const KittiSet set = MakeKittiSet();
  ImageSetMatchingOptions options;
  options.max_features = 300;
  const auto combined = MakeDetector("hessian+harris");
  const ImageSetMatching result = MatchImageFrames(set.grays, *combined, options);
  EXPECT_EQ(result.tracks.detector_name, "hessian+harris");
  const auto hessian = MakeDetector("hessian");
  const ImageSetMatching alone = MatchImageFrames(set.grays, *hessian, options);
  for (size_t f = 0; f < set.grays.size(); ++f) {
    const int first_harris = static_cast<int>(alone.tracks.features[f].size());
    EXPECT_EQ(result.tracks.descriptors[f].rows,
              static_cast<int>(result.tracks.features[f].size()));
    // The hessian part comes first and is what hessian alone gives.
    EXPECT_EQ(cv::norm(result.tracks.descriptors[f].rowRange(0, first_harris),
                       alone.tracks.descriptors[f], cv::NORM_INF),
              0.0);
  }
  // No track mixes the two detectors' features.
  for (const Track& track : result.tracks.tracks) {
    const TrackObservation& first = track.observations.front();
    const bool first_is_hessian =
        first.feature < static_cast<int>(alone.tracks.features[first.frame].size());
    for (const TrackObservation& obs : track.observations) {
      EXPECT_EQ(obs.feature < static_cast<int>(alone.tracks.features[obs.frame].size()),
                first_is_hessian);
    }
  }
  EXPECT_GT(result.tracks.tracks.size(), alone.tracks.tracks.size());
}

TEST(ImageSetMatching, RenderedViewsAgreeWithTheirExactCameras) {
  COMIC_REQUIRE_SHARED_DATA();
  // Five NeRF lego views on their hemisphere, out of any order (views 5, 9, 14, 16 and 23 of the
  // set: neighbours of 5 in different directions).
  const std::string dir = test::SharedDataDir() + "/nerf_synthetic_lego";
  const io::GroundTruthCameras truth = io::ReadGroundTruthCameras(dir + "/transforms_train.json");
  const std::vector<int> frames = {16, 5, 23, 9, 14};
  std::vector<cv::Mat> grays;
  std::vector<View> views;
  for (int frame : frames) {
    grays.push_back(
        io::LoadImage(dir + "/train/r_" + std::to_string(frame) + ".png", 0, 1 << 30).gray);
    const io::GroundTruthCamera& camera = truth.cameras[frame];
    cv::Matx33d R;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) R(r, c) = camera.cam_from_world_rotation(r, c);
    }
    views.push_back(
        {R, cv::Vec3d(camera.cam_from_world_translation.x(), camera.cam_from_world_translation.y(),
                      camera.cam_from_world_translation.z())});
  }
  const double f = 400.0 / std::tan(0.5 * 0.6911112070083618);
  const cv::Matx33d K(f, 0, 399.5, 0, f, 399.5, 0, 0, 1);
  for (const char* name : {"harris", "comic"}) {
    const auto detector = MakeDetector(name);
    const ImageSetMatching result = MatchImageFrames(grays, *detector, {});
    int64_t correct = 0, total = 0;
    for (const FramePairMatches& pair : result.verified_pairs) {
      for (const PatchMatch& m : pair.matches) {
        correct += EpipolarDistance(K, views[pair.frame1], views[pair.frame2],
                                    result.tracks.features[pair.frame1][m.index1].Position(),
                                    result.tracks.features[pair.frame2][m.index2].Position()) < 2.0;
        ++total;
      }
    }
    EXPECT_GE(result.summary.num_verified_pairs, 4) << name;
    EXPECT_GE(total, 400) << name;
    EXPECT_GE(correct, 0.85 * total) << name;
  }
}

TEST(ImageSetMatching, PairsAndOptions) {
  EXPECT_EQ(ImageSetPairs(4, 0).size(), 6u);
  EXPECT_EQ(ImageSetPairs(4, 1), (std::vector<std::pair<int, int>>{{0, 1}, {1, 2}, {2, 3}}));
  EXPECT_EQ(ImageSetPairs(4, 2).size(), 5u);
  EXPECT_TRUE(ImageSetPairs(1, 0).empty());
  // COLMAP's quadratic overlap: past the window, the frames 2^k after each frame.
  EXPECT_EQ(
      ImageSetPairs(6, 1, true),
      (std::vector<std::pair<int, int>>{
          {0, 1}, {0, 2}, {0, 4}, {1, 2}, {1, 3}, {1, 5}, {2, 3}, {2, 4}, {3, 4}, {3, 5}, {4, 5}}));
  EXPECT_EQ(ImageSetPairs(4, 0, true).size(), 6u);  // every pair already
  // 300 frames, window 10: 10 each (fewer at the end) plus 16, 32, ..., 256 where they fit.
  const auto pairs = ImageSetPairs(300, 10, true);
  EXPECT_EQ(std::count(pairs.begin(), pairs.end(), std::make_pair(0, 256)), 1);
  EXPECT_EQ(std::count(pairs.begin(), pairs.end(), std::make_pair(0, 12)), 0);
  EXPECT_EQ(std::count(pairs.begin(), pairs.end(), std::make_pair(100, 132)), 1);
  ImageSetMatchingOptions options;
  EXPECT_EQ(options.verification.min_num_inliers, 15);  // COLMAP's defaults
  EXPECT_EQ(options.verification.max_error_px, 4.0);
  options.window = -1;
  EXPECT_THROW(options.Check(), Error);
  const auto detector = MakeDetector("harris");
  EXPECT_THROW(
      MatchImageFrames({cv::Mat(50, 50, CV_8UC1), cv::Mat(40, 50, CV_8UC1)}, *detector, {}), Error);
  const ImageSetMatching empty = MatchImageFrames({}, *detector, {});
  EXPECT_EQ(empty.tracks.NumFrames(), 0u);
}

}  // namespace
}  // namespace comic::frontend
