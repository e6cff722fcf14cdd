// The mapping engine's steps on synthetic tracks: initial pair under forward motion, exclusions,
// registration, filtering.
#include "sfm/incremental_mapper.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "io/core/error.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

SyntheticScene ForwardScene() {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kForward;
  options.num_frames = 16;
  options.num_points = 700;
  options.seed = 21;
  return MakeSyntheticScene(options);
}

TEST(IncrementalMapper, FindsAnInitialPairUnderForwardMotion) {
  const SyntheticScene scene = ForwardScene();
  const IncrementalMapper mapper(scene.tracks, scene.camera, IncrementalMapper::Options());
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  EXPECT_EQ(pair->geometry.configuration, TwoViewConfiguration::kCalibrated);
  EXPECT_GE(pair->score, IncrementalMapper::Options().init_min_score);
  // Forward motion: most points lie near the epipole, so the median triangulation angle is far
  // below COLMAP's 16 degree initial-pair threshold; the parallax score still finds the pair.
  EXPECT_LT(pair->geometry.median_triangulation_angle_deg, 16.0);
  EXPECT_GT(pair->image_id2, pair->image_id1);
  // Candidates come best first: those of the most tracked anchors, then those of the anchors
  // over the whole clip.
  const auto pairs = mapper.FindInitialPairs();
  ASSERT_FALSE(pairs.empty());
  EXPECT_TRUE(pairs.front().most_tracked_anchor);
  for (size_t i = 1; i < pairs.size(); ++i) {
    EXPECT_GE(pairs[i - 1].most_tracked_anchor, pairs[i].most_tracked_anchor);
    if (pairs[i - 1].most_tracked_anchor == pairs[i].most_tracked_anchor) {
      EXPECT_GE(pairs[i - 1].score, pairs[i].score);
    }
  }
  // The anchors over the whole clip reach its start and its end.
  int first_frame = 1 << 30, last_frame = -1;
  for (const auto& candidate : pairs) {
    first_frame = std::min(first_frame, IncrementalMapper::FrameOfImageId(candidate.image_id1));
    last_frame = std::max(last_frame, IncrementalMapper::FrameOfImageId(candidate.image_id2));
  }
  EXPECT_LT(first_frame, 8);
  EXPECT_GT(last_frame, static_cast<int>(scene.tracks.NumFrames()) - 9);
  // Excluded frames take no part.
  std::set<image_t> excluded = {pair->image_id1, pair->image_id2};
  const auto other = mapper.FindInitialPair(excluded);
  ASSERT_TRUE(other.has_value());
  EXPECT_FALSE(excluded.count(other->image_id1));
  EXPECT_FALSE(excluded.count(other->image_id2));
}

TEST(IncrementalMapper, RegistersTriangulatesAndFilters) {
  const SyntheticScene scene = ForwardScene();
  IncrementalMapper mapper(scene.tracks, scene.camera, IncrementalMapper::Options());
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  const size_t num_points = mapper.RegisterInitialPair(*pair);
  EXPECT_GT(num_points, 100u);
  EXPECT_EQ(mapper.reconstruction().NumRegisteredImages(), 2u);
  EXPECT_THROW(mapper.RegisterInitialPair(*pair), Error);  // only once
  mapper.AdjustGlobalBundle(BundleAdjustmentOptions());
  const std::vector<image_t> candidates = mapper.NextImageCandidates();
  ASSERT_FALSE(candidates.empty());
  for (image_t id : candidates) EXPECT_FALSE(mapper.reconstruction().image(id).registered);
  ASSERT_TRUE(mapper.RegisterNextImage(candidates[0]));
  EXPECT_GT(mapper.last_num_pose_inliers(), 30);
  EXPECT_THROW(mapper.RegisterNextImage(candidates[0]), Error);  // already registered
  EXPECT_GT(mapper.TriangulateImage(candidates[0]), 0u);
  const BundleAdjustmentSummary local =
      mapper.AdjustLocalBundle(candidates[0], BundleAdjustmentOptions(), 3);
  EXPECT_TRUE(local.usable);
  EXPECT_LE(local.num_variable_images, 3);
  EXPECT_EQ(mapper.registration_order().size(), 3u);

  // Filtering keeps what is consistent...
  const size_t before = mapper.reconstruction().NumObservations();
  EXPECT_EQ(mapper.FilterPoints(), 0u);
  EXPECT_EQ(mapper.reconstruction().NumObservations(), before);
}

// A frame that is not a keyframe gets a pose but adds nothing to the map until it is posed again
// against the final map; the initial pair's frames become keyframes whatever the flags say.
TEST(IncrementalMapper, NonKeyframesArePosedButStayOutOfTheMapUntilLocalized) {
  const SyntheticScene scene = ForwardScene();
  IncrementalMapper mapper(scene.tracks, scene.camera, IncrementalMapper::Options());
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  EXPECT_THROW(mapper.SetKeyframes(std::vector<char>(3, 1)), Error);  // one flag per frame
  mapper.SetKeyframes(std::vector<char>(scene.tracks.NumFrames(), 0));
  EXPECT_FALSE(mapper.IsKeyframe(pair->image_id1));
  ASSERT_GT(mapper.RegisterInitialPair(*pair), 100u);
  EXPECT_TRUE(mapper.IsKeyframe(pair->image_id1));
  EXPECT_TRUE(mapper.IsKeyframe(pair->image_id2));
  EXPECT_THROW(mapper.SetKeyframes({}), Error);  // only before registration
  mapper.AdjustGlobalBundle(BundleAdjustmentOptions());
  const size_t num_points = mapper.reconstruction().NumPoints3D();
  const size_t num_observations = mapper.reconstruction().NumObservations();

  const std::vector<image_t> candidates = mapper.NextImageCandidates();
  ASSERT_GE(candidates.size(), 2u);
  const image_t non_keyframe = candidates[0];
  EXPECT_FALSE(mapper.IsKeyframe(non_keyframe));
  ASSERT_TRUE(mapper.RegisterNextImage(non_keyframe));
  EXPECT_TRUE(mapper.reconstruction().image(non_keyframe).registered);
  EXPECT_EQ(mapper.reconstruction().NumObservations(), num_observations);
  EXPECT_EQ(mapper.TriangulateImage(non_keyframe), 0u);  // its views do not triangulate
  EXPECT_EQ(mapper.reconstruction().NumPoints3D(), num_points);
  EXPECT_EQ(mapper.reconstruction().NumObservations(), num_observations);
  EXPECT_THROW(mapper.PromoteToKeyframe(non_keyframe), Error);  // registered already

  const image_t promoted = candidates[1];
  mapper.PromoteToKeyframe(promoted);
  ASSERT_TRUE(mapper.RegisterNextImage(promoted));
  EXPECT_GT(mapper.reconstruction().NumObservations(), num_observations);
  // Global adjustment: the non-keyframe is not in the problem.
  const BundleAdjustmentSummary global = mapper.AdjustGlobalBundle(BundleAdjustmentOptions());
  EXPECT_EQ(global.num_images, 3);
  EXPECT_EQ(global.num_variable_images, 2);  // the first frame of the pair is held (gauge)
  // Bounded to the newest keyframe: the initial pair sees its points and is held constant.
  const BundleAdjustmentSummary newest = mapper.AdjustGlobalBundle(BundleAdjustmentOptions(), 1);
  EXPECT_TRUE(newest.usable);
  EXPECT_EQ(newest.num_variable_images, 1);
  EXPECT_EQ(newest.num_images, 3);
  EXPECT_THROW(mapper.AdjustGlobalBundle(BundleAdjustmentOptions(), -1), Error);

  // Posed again against the map, with its inlier observations.
  EXPECT_TRUE(mapper.LocalizeNonKeyframes().empty());
  const Image& image = mapper.reconstruction().image(non_keyframe);
  EXPECT_TRUE(image.registered);
  int num_observed = 0;
  for (const Point2D& point2D : image.points2D) num_observed += point2D.HasPoint3D();
  EXPECT_GT(num_observed, 30);
  const Rigid3d& truth = scene.cams_from_world[IncrementalMapper::FrameOfImageId(non_keyframe)];
  const Rigid3d& first = scene.cams_from_world[IncrementalMapper::FrameOfImageId(pair->image_id1)];
  // Rotation relative to the first frame of the pair (the model's origin) within 0.5 degrees.
  const Eigen::Quaterniond estimated = image.cam_from_world.rotation;
  const Eigen::Quaterniond expected = truth.rotation * first.rotation.inverse();
  EXPECT_LT(estimated.angularDistance(expected) * 180.0 / M_PI, 0.5);
}

// The per-frame counts that rank the next frames are kept from the model's link changes, not
// recounted: through registrations, triangulation, re-triangulation, adjustment and filtering
// (which deletes observations and, with the last two, points) they must equal a recount.
// Loop closure skips pairs of frames the tracks already link (sfm/loop_closure.h): the count
// is that of the tracks holding a feature of each frame, and falls as the frames part.
TEST(IncrementalMapper, CountsTheTracksTwoFramesShare) {
  const SyntheticScene scene = ForwardScene();
  const IncrementalMapper mapper(scene.tracks, scene.camera, IncrementalMapper::Options());
  for (int frame2 : {1, 5, 15}) {
    size_t expected = 0;
    for (const frontend::Track& track : scene.tracks.tracks) {
      bool in0 = false, in2 = false;
      for (const frontend::TrackObservation& obs : track.observations) {
        in0 = in0 || obs.frame == 0;
        in2 = in2 || obs.frame == frame2;
      }
      expected += in0 && in2;
    }
    EXPECT_EQ(mapper.NumSharedTracks(0, frame2), expected) << "frame " << frame2;
    EXPECT_EQ(mapper.NumSharedTracks(frame2, 0), expected) << "frame " << frame2;
  }
  EXPECT_GT(mapper.NumSharedTracks(0, 1), mapper.NumSharedTracks(0, 15));
  EXPECT_GT(mapper.NumSharedTracks(0, 1), 100u);
}

TEST(IncrementalMapper, CountsOfTracksWithPointsFollowEveryChangeOfTheModel) {
  SyntheticSceneOptions options;  // hand-held, with outliers for the filter to remove
  options.num_frames = 20;
  options.num_points = 900;
  options.seed = 5;
  const SyntheticScene scene = MakeSyntheticScene(options);
  // A strict filter (below the noise level of 0.5 px; angles a hand-held baseline seldom gives)
  // removes observations and whole points after every step.
  IncrementalMapper::Options mapper_options;
  mapper_options.filter_max_reprojection_error_px = 0.3;
  mapper_options.filter_min_tri_angle_deg = 4.0;
  IncrementalMapper mapper(scene.tracks, scene.camera, mapper_options);
  const Reconstruction& model = mapper.reconstruction();
  const auto expect_recount = [&]() {
    std::vector<int> recount(scene.tracks.NumFrames(), 0);
    for (const frontend::Track& track : scene.tracks.tracks) {
      bool has_point = false;
      for (const frontend::TrackObservation& o : track.observations) {
        has_point = has_point || model.image(IncrementalMapper::ImageIdOfFrame(o.frame))
                                     .points2D[o.feature]
                                     .HasPoint3D();
      }
      for (const frontend::TrackObservation& o : track.observations) recount[o.frame] += has_point;
    }
    std::vector<std::pair<int, image_t>> expected;
    for (size_t frame = 0; frame < recount.size(); ++frame) {
      const image_t image_id = IncrementalMapper::ImageIdOfFrame(static_cast<int>(frame));
      EXPECT_EQ(mapper.NumTracksWithPoints(image_id), recount[frame]) << "frame " << frame;
      if (!model.image(image_id).registered &&
          recount[frame] >= mapper_options.absolute_pose.min_num_inliers) {
        expected.emplace_back(recount[frame], image_id);
      }
    }
    std::stable_sort(expected.begin(), expected.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<image_t> expected_ids;
    for (const auto& e : expected) expected_ids.push_back(e.second);
    EXPECT_EQ(mapper.NextImageCandidates(), expected_ids);
  };
  expect_recount();  // no point yet: all zero
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  ASSERT_GT(mapper.RegisterInitialPair(*pair), 100u);
  expect_recount();
  size_t num_removed = 0;  // observations the adjustment's and the filter's steps removed
  for (std::vector<image_t> next = mapper.NextImageCandidates(); !next.empty();
       next = mapper.NextImageCandidates()) {
    if (!mapper.RegisterNextImage(next.front())) break;
    mapper.TriangulateImage(next.front());
    expect_recount();
    const size_t before = model.NumObservations();
    mapper.AdjustLocalBundle(next.front(), BundleAdjustmentOptions(), 4);
    mapper.FilterPoints();
    num_removed += before - std::min(before, model.NumObservations());
    expect_recount();
  }
  EXPECT_GT(model.NumRegisteredImages(), 10u);
  EXPECT_GT(num_removed, 50u) << "observations must be unlinked for this to test it";
  EXPECT_THROW(mapper.NumTracksWithPoints(9999), Error);
}

// Every frame of the forward scene registered and triangulated, without any global adjustment.
void RegisterEveryFrame(IncrementalMapper* mapper) {
  const auto pair = mapper->FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  ASSERT_GT(mapper->RegisterInitialPair(*pair), 100u);
  for (std::vector<image_t> next = mapper->NextImageCandidates(); !next.empty();
       next = mapper->NextImageCandidates()) {
    ASSERT_TRUE(mapper->RegisterNextImage(next[0]));
    mapper->TriangulateImage(next[0]);
  }
}

// The final adjustment of long video in windows (issue 26): half-overlapping windows from the
// oldest frame cover the model, none holds more than its window variable, and the model ends as
// consistent as after one adjustment of everything.
TEST(IncrementalMapper, AdjustsTheModelInOverlappingWindows) {
  const SyntheticScene scene = ForwardScene();
  IncrementalMapper windowed(scene.tracks, scene.camera, IncrementalMapper::Options());
  RegisterEveryFrame(&windowed);
  ASSERT_EQ(windowed.reconstruction().NumRegisteredImages(), 16u);
  IncrementalMapper whole(scene.tracks, scene.camera, IncrementalMapper::Options());
  RegisterEveryFrame(&whole);
  const double error_before = windowed.reconstruction().ComputeMeanReprojectionError();
  ASSERT_EQ(whole.reconstruction().ComputeMeanReprojectionError(), error_before);

  const std::vector<BundleAdjustmentSummary> windows =
      windowed.AdjustGlobalBundleInWindows(BundleAdjustmentOptions(), 4);
  // 16 frames, 4 a window, a new window every 2: starting at 0, 2, ..., 12.
  ASSERT_EQ(windows.size(), 7u);
  for (const BundleAdjustmentSummary& summary : windows) {
    EXPECT_TRUE(summary.usable);
    EXPECT_LE(summary.num_variable_images, 4);
    EXPECT_GT(summary.num_images, summary.num_variable_images) << "neighbours held constant";
    EXPECT_LE(summary.final_rmse_px, summary.initial_rmse_px + 1e-9);
  }
  const double error_windowed = windowed.reconstruction().ComputeMeanReprojectionError();
  whole.AdjustGlobalBundle(BundleAdjustmentOptions());
  const double error_whole = whole.reconstruction().ComputeMeanReprojectionError();
  EXPECT_LT(error_windowed, error_before);
  EXPECT_LT(error_windowed, 1.05 * error_whole)
      << "windows " << error_windowed << " px, whole " << error_whole << " px";
  EXPECT_THROW(windowed.AdjustGlobalBundleInWindows(BundleAdjustmentOptions(), 1), Error);
}

// Two tracks of one point that overlap in two frames (a detector's duplicate corner), made one
// point by a link (a merge or a loop closure): completing the tracks afterwards must not give the
// point a second observation in a frame it already sees.
TEST(IncrementalMapper, FusedPointsKeepOneObservationPerFrame) {
  SyntheticScene scene = ForwardScene();
  frontend::FeatureTracks& tracks = scene.tracks;
  size_t chosen = tracks.tracks.size();
  for (size_t t = 0; t < tracks.tracks.size() && chosen == tracks.tracks.size(); ++t) {
    const auto& obs = tracks.tracks[t].observations;
    bool clean = obs.size() >= 9;
    for (const auto& o : obs) clean = clean && !scene.is_outlier[o.frame][o.feature];
    if (clean) chosen = t;
  }
  ASSERT_LT(chosen, tracks.tracks.size());
  const std::vector<frontend::TrackObservation> all = tracks.tracks[chosen].observations;
  // First: observations 0-4; second: duplicates of 3 and 4, then 5 onwards.
  frontend::Track second;
  for (size_t k = 3; k < 5; ++k) {
    tracks.features[all[k].frame].push_back(tracks.features[all[k].frame][all[k].feature]);
    second.observations.push_back(
        {all[k].frame, static_cast<int>(tracks.features[all[k].frame].size()) - 1});
  }
  for (size_t k = 5; k < all.size(); ++k) second.observations.push_back(all[k]);
  tracks.tracks[chosen].observations.resize(5);
  tracks.tracks.push_back(second);
  tracks.Check();

  IncrementalMapper mapper(tracks, scene.camera, IncrementalMapper::Options());
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  ASSERT_GT(mapper.RegisterInitialPair(*pair), 0u);
  for (std::vector<image_t> next = mapper.NextImageCandidates(); !next.empty();
       next = mapper.NextImageCandidates()) {
    if (!mapper.RegisterNextImage(next.front())) break;
    mapper.TriangulateImage(next.front());
  }
  const Reconstruction& model = mapper.reconstruction();
  const auto point_of = [&](const frontend::TrackObservation& o) {
    return model.image(IncrementalMapper::ImageIdOfFrame(o.frame)).points2D[o.feature].point3D_id;
  };
  const point3D_t a = point_of(all[0]);
  const point3D_t b = point_of(second.observations.back());
  ASSERT_NE(a, kInvalidPoint3DId);
  ASSERT_NE(b, kInvalidPoint3DId);
  ASSERT_NE(a, b);
  IncrementalMapper::FeatureLink link;
  link.image_id = IncrementalMapper::ImageIdOfFrame(all[0].frame);
  link.point2D_idx = all[0].feature;
  link.other_image_id = IncrementalMapper::ImageIdOfFrame(second.observations.back().frame);
  link.other_point2D_idx = second.observations.back().feature;
  EXPECT_EQ(mapper.FuseLinkedPoints({link}), 1u);
  EXPECT_FALSE(model.ExistsPoint3D(b));
  EXPECT_NO_THROW(mapper.TriangulateAllTracks());
  for (const auto& [point3D_id, point] : model.points3D()) {
    std::set<image_t> images;
    for (const TrackElement& element : point.track) {
      EXPECT_TRUE(images.insert(element.image_id).second) << "point " << point3D_id;
    }
  }
  // The fused point took over the second track's frames its position explains.
  int taken = 0;
  for (size_t k = 2; k < second.observations.size(); ++k) {
    taken += point_of(second.observations[k]) == a;
  }
  EXPECT_GE(taken, 1);
}

TEST(IncrementalMapper, FilterRemovesLargeErrorsAndSmallAngles) {
  const SyntheticScene scene = ForwardScene();
  // ... and removes what its thresholds reject: with 0.5 px noise, a 0.05 px limit rejects nearly
  // every observation; a 60 degree minimum angle every point.
  IncrementalMapper::Options strict_error;
  strict_error.filter_max_reprojection_error_px = 0.05;
  IncrementalMapper mapper(scene.tracks, scene.camera, strict_error);
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  const size_t num_points = mapper.RegisterInitialPair(*pair);
  ASSERT_GT(num_points, 100u);
  EXPECT_GT(mapper.FilterPoints(), num_points);
  EXPECT_LT(mapper.reconstruction().NumPoints3D(), num_points / 4);

  IncrementalMapper::Options strict_angle;
  strict_angle.filter_min_tri_angle_deg = 60;
  IncrementalMapper angle_mapper(scene.tracks, scene.camera, strict_angle);
  angle_mapper.RegisterInitialPair(*pair);
  EXPECT_EQ(angle_mapper.FilterPoints(), 2 * num_points);
  EXPECT_EQ(angle_mapper.reconstruction().NumPoints3D(), 0u);
}

// A point triangulated from two close frames can lie off along the ray; the later views of its
// track then miss it by more than the completion threshold. Planted here: for every second track
// seen by the initial pair, the feature in the pair's second frame is moved to where a point at 50
// % of the true depth (on the first frame's ray) projects, so the pair triangulates it exactly
// there; only points nearer than 20 m, which the later, closer frames see far from the wrong
// point (farther ones still reproject within the completion threshold, and bundle adjustment
// corrects them). Noise-free otherwise, poses from the truth, so every good point is exact.
TEST(IncrementalMapper, RetriangulatesPointsTheirLaterViewsMiss) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kForward;
  scene_options.num_frames = 12;
  scene_options.num_points = 1500;
  scene_options.noise_px = 0.0;
  scene_options.outlier_ratio = 0.0;
  scene_options.track_break_probability = 0.0;
  scene_options.seed = 5;
  SyntheticScene scene = MakeSyntheticScene(scene_options);
  constexpr int kFrame1 = 0;
  constexpr int kFrame2 = 2;
  const Rigid3d& cam1_from_world = scene.cams_from_world[kFrame1];
  const Rigid3d& cam2_from_world = scene.cams_from_world[kFrame2];

  IncrementalMapper::InitialPair pair;
  pair.image_id1 = IncrementalMapper::ImageIdOfFrame(kFrame1);
  pair.image_id2 = IncrementalMapper::ImageIdOfFrame(kFrame2);
  pair.geometry.configuration = TwoViewConfiguration::kCalibrated;
  pair.geometry.cam2_from_cam1 = cam2_from_world * cam1_from_world.Inverse();
  std::vector<int> planted;
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    const frontend::Track& track = scene.tracks.tracks[t];
    int feature1 = -1, feature2 = -1;
    for (const frontend::TrackObservation& obs : track.observations) {
      if (obs.frame == kFrame1) feature1 = obs.feature;
      if (obs.frame == kFrame2) feature2 = obs.feature;
    }
    if (feature1 < 0 || feature2 < 0) continue;
    const Eigen::Vector3d xyz = scene.points3D[scene.track_point_index[t]];
    if (pair.track_ids.size() % 2 == 0 && track.Length() >= 5 &&
        (cam1_from_world * xyz).z() < 20.0) {
      const Eigen::Vector3d center1 = ProjectionCenter(cam1_from_world);
      const auto moved =
          ProjectPoint(scene.camera, cam2_from_world, center1 + 0.5 * (xyz - center1));
      ASSERT_TRUE(moved.has_value());
      frontend::Feature& feature = scene.tracks.features[kFrame2][feature2];
      feature.x = static_cast<float>(moved->x());
      feature.y = static_cast<float>(moved->y());
      planted.push_back(static_cast<int>(t));
    }
    pair.track_ids.push_back(static_cast<int>(t));
    pair.point2D_idxs1.push_back(static_cast<point2D_t>(feature1));
    pair.point2D_idxs2.push_back(static_cast<point2D_t>(feature2));
    pair.geometry.inlier_mask.push_back(1);
  }
  ASSERT_GE(planted.size(), 20u);

  // Maps every frame in order; returns, per planted track, its point's relative depth error and
  // observation count (no point: error 1, 0 observations).
  struct PlantedResult {
    double mean_relative_error = 0.0;
    double mean_num_observations = 0.0;
    size_t num_still_off = 0;  // points more than 5 % of the depth from the truth
  };
  const auto map = [&](bool retriangulate) {
    IncrementalMapper::Options options;
    options.retriangulate_incomplete_tracks = retriangulate;
    IncrementalMapper mapper(scene.tracks, scene.camera, options);
    EXPECT_GT(mapper.RegisterInitialPair(pair), 100u);
    for (int frame = 0; frame < scene_options.num_frames; ++frame) {
      const image_t image_id = IncrementalMapper::ImageIdOfFrame(frame);
      if (mapper.reconstruction().image(image_id).registered) continue;
      EXPECT_TRUE(mapper.RegisterNextImage(image_id)) << "frame " << frame;
      mapper.TriangulateImage(image_id);
    }
    mapper.TriangulateAllTracks();
    // The model's world is the first frame's camera at the true scale.
    const Reconstruction& reconstruction = mapper.reconstruction();
    PlantedResult result;
    for (int t : planted) {
      const frontend::TrackObservation& first = scene.tracks.tracks[t].observations.front();
      const point2D_t idx = static_cast<point2D_t>(first.feature);
      const Point2D& point2D =
          reconstruction.image(IncrementalMapper::ImageIdOfFrame(first.frame)).points2D[idx];
      const Eigen::Vector3d truth = cam1_from_world * scene.points3D[scene.track_point_index[t]];
      double error = 1.0;
      if (point2D.HasPoint3D()) {
        const Point3D& point = reconstruction.point3D(point2D.point3D_id);
        error = (point.xyz - truth).norm() / truth.z();
        result.mean_num_observations += static_cast<double>(point.track.size());
      }
      result.mean_relative_error += error;
      result.num_still_off += error > 0.05;
    }
    result.mean_relative_error /= static_cast<double>(planted.size());
    result.mean_num_observations /= static_cast<double>(planted.size());
    return result;
  };

  const PlantedResult without = map(false);
  const PlantedResult with = map(true);
  // Without re-triangulation most planted points keep their 50 % depth error and their short
  // tracks.
  EXPECT_GT(without.num_still_off, planted.size() / 2);
  EXPECT_GT(without.mean_relative_error, 0.1);
  // With it, they are re-triangulated from their whole tracks (5 frames or more), the wrong
  // observation left out.
  EXPECT_EQ(with.num_still_off, 0u);
  EXPECT_LT(with.mean_relative_error, 0.01);
  EXPECT_GE(with.mean_num_observations, 5.0);
  EXPECT_GT(with.mean_num_observations, without.mean_num_observations + 2.0);
}

TEST(IncrementalMapper, ImageIdsAreFramesPlusOne) {
  EXPECT_EQ(IncrementalMapper::ImageIdOfFrame(0), 1u);
  EXPECT_EQ(IncrementalMapper::FrameOfImageId(12), 11);
  const SyntheticScene scene = ForwardScene();
  const IncrementalMapper mapper(scene.tracks, scene.camera, IncrementalMapper::Options());
  EXPECT_EQ(mapper.reconstruction().NumImages(), 16u);
  EXPECT_EQ(mapper.reconstruction().image(1).name, "000000.png");
  EXPECT_EQ(mapper.reconstruction().image(1).points2D.size(), scene.tracks.features[0].size());
  IncrementalMapper::Options bad;
  bad.init_tri_angle_deg = 0;
  EXPECT_THROW(IncrementalMapper(scene.tracks, scene.camera, bad), Error);
}

}  // namespace
}  // namespace comic::sfm
