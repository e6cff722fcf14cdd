// Merging separately reconstructed chunks by their shared frames (MergeChunkModels): chunks of a
// synthetic video, each in a world of its own (another similarity, scale included), sharing one
// frame, are put back into the first chunk's world; a point of the shared frame that disagrees is
// not fused; a chunk whose shared frame disagrees, or that shares no frame, begins a model of its
// own.
#include "sfm/chunk_model_merging.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

SyntheticScene HandHeldScene() {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kHandHeld;
  options.num_frames = 15;
  options.num_points = 800;
  options.seed = 3;
  return MakeSyntheticScene(options);
}

std::string FrameName(int frame) { return "frame_" + std::to_string(frame) + ".png"; }

Sim3d MakeSim3(double scale, double angle, const Eigen::Vector3d& axis,
               const Eigen::Vector3d& translation) {
  Sim3d sim;
  sim.scale = scale;
  sim.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
  sim.translation = translation;
  return sim;
}

// The chunk of frames [first, last] as a run would give it, in the world `world_from_truth`
// makes: every point each frame sees, at its exact pixel (computed in the true world, so a frame
// in two chunks has the same features), and the points seen twice or more.
Reconstruction MakeChunk(const SyntheticScene& scene, int first, int last,
                         const Sim3d& world_from_truth) {
  Reconstruction chunk;
  const camera_t camera_id = chunk.AddCamera(scene.camera);
  std::vector<std::vector<TrackElement>> tracks(scene.points3D.size());
  for (int frame = first; frame <= last; ++frame) {
    Image image;
    image.camera_id = camera_id;
    image.name = FrameName(frame);
    image.cam_from_world = world_from_truth.TransformPose(scene.cams_from_world[frame]);
    std::vector<size_t> seen;
    for (size_t p = 0; p < scene.points3D.size(); ++p) {
      const auto xy = ProjectPoint(scene.camera, scene.cams_from_world[frame], scene.points3D[p]);
      if (!xy || xy->x() < 0 || xy->y() < 0 || xy->x() > scene.camera.width - 1 ||
          xy->y() > scene.camera.height - 1) {
        continue;
      }
      Point2D point;
      point.xy = *xy;
      image.points2D.push_back(point);
      seen.push_back(p);
    }
    const image_t image_id = chunk.AddImage(std::move(image));
    chunk.RegisterImage(image_id);
    for (size_t i = 0; i < seen.size(); ++i) {
      tracks[seen[i]].push_back({image_id, static_cast<point2D_t>(i)});
    }
  }
  for (size_t p = 0; p < tracks.size(); ++p) {
    if (tracks[p].size() >= 2) chunk.AddPoint3D(world_from_truth * scene.points3D[p], tracks[p]);
  }
  return chunk;
}

ChunkMergingOptions WithoutAdjustment() {
  ChunkMergingOptions options;
  options.global_ba_max_images = -1;  // exact chunks: the merge alone must be exact
  return options;
}

TEST(ChunkModelMerging, PutsChunksSharingOneFrameIntoTheFirstChunksWorld) {
  const SyntheticScene scene = HandHeldScene();
  const Sim3d first_world = MakeSim3(2.0, 0.3, {0, 1, 0}, {1, -2, 3});
  const std::vector<Reconstruction> chunks = {
      MakeChunk(scene, 0, 5, first_world),
      MakeChunk(scene, 5, 10, MakeSim3(0.5, -1.0, {1, 1, 0}, {-4, 0, 2})),
      MakeChunk(scene, 10, 14, MakeSim3(7.0, 2.0, {0, 0, 1}, {0, 5, 0}))};
  const ChunkMergingResult merged = MergeChunkModels(chunks, WithoutAdjustment());
  ASSERT_EQ(merged.models.size(), 1u);
  const Reconstruction& model = merged.models[0];
  EXPECT_EQ(model.NumRegisteredImages(), 15u);
  ASSERT_EQ(merged.chunks.size(), 3u);
  EXPECT_TRUE(merged.chunks[0].started_model);
  for (int c = 1; c < 3; ++c) {
    EXPECT_EQ(merged.chunks[c].model_index, 0);
    EXPECT_FALSE(merged.chunks[c].started_model);
    EXPECT_EQ(merged.chunks[c].num_shared_frames, 1);
    EXPECT_EQ(merged.chunks[c].num_inliers, merged.chunks[c].num_point_pairs);
    EXPECT_GT(merged.chunks[c].num_inliers, 15);
  }
  EXPECT_NEAR(merged.chunks[1].model_from_chunk.scale, 4.0, 1e-9);
  EXPECT_NEAR(merged.chunks[2].model_from_chunk.scale, 2.0 / 7.0, 1e-9);
  // One camera: the chunks' cameras are the same.
  EXPECT_EQ(model.cameras().size(), 1u);
  for (const auto& [id, image] : model.images()) {
    const int frame = std::stoi(image.name.substr(6));
    const Eigen::Vector3d expected = first_world * ProjectionCenter(scene.cams_from_world[frame]);
    EXPECT_LT((ProjectionCenter(image.cam_from_world) - expected).norm(), 1e-6) << image.name;
  }
  // The points of the shared frames are fused, not doubled: each frame sees each point once.
  for (const auto& [id, image] : model.images()) {
    std::set<point3D_t> points;
    for (const Point2D& point : image.points2D) {
      if (point.HasPoint3D()) {
        EXPECT_TRUE(points.insert(point.point3D_id).second);
      }
    }
  }
  EXPECT_LT(model.ComputeMeanReprojectionError(), 1e-6);
}

TEST(ChunkModelMerging, APointOfTheSharedFrameThatDisagreesIsNotFused) {
  const SyntheticScene scene = HandHeldScene();
  const Reconstruction first = MakeChunk(scene, 0, 5, Sim3d());
  Reconstruction second = MakeChunk(scene, 5, 10, Sim3d());
  // One point the shared frame (frame 5, the second chunk's first image) sees, moved far off.
  image_t shared_id = 0;
  for (const auto& [id, image] : second.images()) {
    if (image.name == FrameName(5)) shared_id = id;
  }
  const Image& shared = second.image(shared_id);
  point3D_t moved = kInvalidPoint3DId;
  for (const Point2D& point : shared.points2D) {
    if (point.HasPoint3D() && second.point3D(point.point3D_id).track.size() >= 3) {
      moved = point.point3D_id;
      break;
    }
  }
  ASSERT_NE(moved, kInvalidPoint3DId);
  second.point3D(moved).xyz += Eigen::Vector3d(5, -5, 5);
  const Eigen::Vector3d moved_xyz = second.point3D(moved).xyz;
  const ChunkMergingResult merged = MergeChunkModels({first, second}, WithoutAdjustment());
  ASSERT_EQ(merged.models.size(), 1u);
  const Reconstruction& model = merged.models[0];
  // The moved point stays a point of its own, without the shared frame's observation, and every
  // point the shared frame sees is where the first chunk put it.
  size_t num_moved = 0;
  for (const auto& [id, point] : model.points3D()) {
    if ((point.xyz - moved_xyz).norm() < 1e-9) {
      ++num_moved;
      EXPECT_EQ(point.track.size(), second.point3D(moved).track.size() - 1);
    }
  }
  EXPECT_EQ(num_moved, 1u);
  for (const auto& [id, image] : model.images()) {
    if (image.name != FrameName(5)) continue;
    for (point2D_t i = 0; i < image.points2D.size(); ++i) {
      if (image.points2D[i].HasPoint3D()) {
        EXPECT_LT(model.ReprojectionError(id, i), 1e-6);
      }
    }
  }
}

TEST(ChunkModelMerging, AChunkThatDisagreesOrSharesNoFrameBeginsAModelOfItsOwn) {
  const SyntheticScene scene = HandHeldScene();
  const Sim3d identity;
  Reconstruction wrong = MakeChunk(scene, 5, 10, identity);
  // Its shared frame's points scattered: nothing agrees on a similarity.
  for (const auto& [id, point] : std::map<point3D_t, Point3D>(wrong.points3D())) {
    wrong.point3D(id).xyz += Eigen::Vector3d(std::sin(id * 1.7), std::cos(id * 2.3), id % 5) * 3;
  }
  const ChunkMergingResult merged = MergeChunkModels(
      {MakeChunk(scene, 0, 5, identity), wrong, MakeChunk(scene, 11, 14, identity)},
      WithoutAdjustment());
  ASSERT_EQ(merged.models.size(), 3u);
  EXPECT_TRUE(merged.chunks[1].started_model);
  EXPECT_EQ(merged.chunks[1].num_shared_frames, 1);
  EXPECT_EQ(merged.chunks[1].reason, "too few points of the shared frames agree on a similarity");
  EXPECT_TRUE(merged.chunks[2].started_model);
  EXPECT_EQ(merged.chunks[2].num_shared_frames, 0);
  EXPECT_EQ(merged.chunks[2].reason, "no frame registered in the model before");
  EXPECT_EQ(merged.models[0].NumRegisteredImages(), 6u);
}

TEST(ChunkModelMerging, TheBoundedAdjustmentKeepsAnExactModelExact) {
  const SyntheticScene scene = HandHeldScene();
  ChunkMergingOptions options;
  options.global_ba_max_images = 4;
  const ChunkMergingResult merged = MergeChunkModels(
      {MakeChunk(scene, 0, 7, Sim3d()),
       MakeChunk(scene, 7, 14, MakeSim3(3.0, 1.0, {1, 0, 0}, Eigen::Vector3d::Zero()))},
      options);
  ASSERT_EQ(merged.models.size(), 1u);
  EXPECT_EQ(merged.models[0].NumRegisteredImages(), 15u);
  // Windows of 4 frames, half a window apart, over 15 frames.
  EXPECT_EQ(merged.adjustments.size(), 7u);
  for (const BundleAdjustmentSummary& summary : merged.adjustments) {
    EXPECT_TRUE(summary.usable);
    EXPECT_LT(summary.final_rmse_px, 1e-3);
  }
}

}  // namespace
}  // namespace comic::sfm
