// Why frames are missing from the largest model: the first check each fails, consecutive frames
// with one reason in one range, with the best value measured and the threshold it missed.
#include "sfm/unregistered_ranges.h"

#include <gtest/gtest.h>

#include <set>

#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

TEST(UnregisteredRanges, NamesTheFirstCheckEachStretchFailed) {
  SyntheticSceneOptions options;
  options.num_frames = 20;
  options.num_points = 600;
  options.outlier_ratio = 0.0;
  SyntheticScene scene = MakeSyntheticScene(options);
  frontend::FeatureTracks& tracks = scene.tracks;
  // Frames 0-1 without features (no texture); frames 2-3 with features in no track.
  for (frontend::Track& track : tracks.tracks) {
    std::vector<frontend::TrackObservation> kept;
    for (const frontend::TrackObservation& obs : track.observations) {
      if (obs.frame >= 4) kept.push_back(obs);
    }
    track.observations = kept;
  }
  tracks.features[0].clear();
  tracks.features[1].clear();
  // The largest model: frames 5-14 at their true poses, with points for the tracks frame 4
  // does not see (so frame 4 sees none of them).
  Reconstruction largest;
  const camera_t camera_id = largest.AddCamera(scene.camera);
  for (size_t frame = 0; frame < tracks.NumFrames(); ++frame) {
    Image image;
    image.image_id = static_cast<image_t>(frame + 1);
    image.camera_id = camera_id;
    for (const frontend::Feature& f : tracks.features[frame]) {
      image.points2D.push_back({Eigen::Vector2d(f.x, f.y)});
    }
    image.cam_from_world = scene.cams_from_world[frame];
    largest.AddImage(std::move(image));
    if (frame >= 5 && frame <= 14) largest.RegisterImage(static_cast<image_t>(frame + 1));
  }
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    std::vector<TrackElement> elements;
    bool in_frame_4 = false;
    for (const frontend::TrackObservation& obs : tracks.tracks[t].observations) {
      in_frame_4 |= obs.frame == 4;
      if (obs.frame >= 5 && obs.frame <= 14) {
        elements.push_back(
            {static_cast<image_t>(obs.frame + 1), static_cast<point2D_t>(obs.feature)});
      }
    }
    if (!in_frame_4 && elements.size() >= 2) {
      largest.AddPoint3D(scene.points3D[scene.track_point_index[t]], elements);
    }
  }
  // Frames 17-19 in another model.
  IncrementalModel other;
  other.reconstruction = largest;
  for (image_t id : other.reconstruction.RegisteredImageIds()) {
    other.reconstruction.DeRegisterImage(id);
  }
  for (int frame : {17, 18, 19}) {
    other.reconstruction.RegisterImage(static_cast<image_t>(frame + 1));
    other.registered_frames.push_back(frame);
  }
  std::vector<int> best_inliers(20, -1);
  best_inliers[15] = 12;
  best_inliers[16] = 20;

  const std::vector<UnregisteredRange> ranges =
      ExplainUnregisteredFrames(tracks, largest, {other}, best_inliers, AbsolutePoseOptions(),
                                /*no_initial_pair_left=*/false);
  ASSERT_EQ(ranges.size(), 5u);
  const auto expect = [&](size_t i, int first, int last, const std::string& stage,
                          const std::string& check) {
    EXPECT_EQ(ranges[i].first_frame, first) << i;
    EXPECT_EQ(ranges[i].last_frame, last) << i;
    EXPECT_EQ(ranges[i].stage, stage) << i;
    EXPECT_EQ(ranges[i].check, check) << i;
    EXPECT_FALSE(ranges[i].message.empty());
  };
  expect(0, 0, 1, "tracking", "features");
  EXPECT_EQ(ranges[0].value, 0.0);
  EXPECT_EQ(ranges[0].needed, AbsolutePoseOptions().min_num_inliers);
  expect(1, 2, 3, "tracking", "tracked_features");
  expect(2, 4, 4, "registration", "visible_points");
  EXPECT_EQ(ranges[2].value, 0.0);
  expect(3, 15, 16, "registration", "pose_inliers");
  EXPECT_EQ(ranges[3].value, 20.0);  // the best of the range
  EXPECT_NE(ranges[3].message.find("frames 15-16"), std::string::npos) << ranges[3].message;
  expect(4, 17, 19, "linking", "other_model");
  EXPECT_EQ(ranges[4].other_model, 0);
  EXPECT_NE(ranges[4].message.find("sparse/1"), std::string::npos) << ranges[4].message;
}

}  // namespace
}  // namespace comic::sfm
