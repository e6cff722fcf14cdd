#include "sfm/chunk_model_merging.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "io/core/error.h"
#include "sfm/similarity_ransac.h"

namespace comic::sfm {

void ChunkMergingOptions::Check() const {
  COMIC_CHECK(max_relative_distance > 0, kInvalidArgument,
              "chunk merging max_relative_distance must be > 0, got " << max_relative_distance);
  COMIC_CHECK(min_num_inliers >= 3, kInvalidArgument,
              "chunk merging min_num_inliers must be >= 3, got " << min_num_inliers);
  COMIC_CHECK(min_inlier_ratio >= 0 && min_inlier_ratio <= 1, kInvalidArgument,
              "chunk merging min_inlier_ratio must be in [0, 1], got " << min_inlier_ratio);
  COMIC_CHECK(
      global_ba_max_images == -1 || global_ba_max_images == 0 || global_ba_max_images >= 2,
      kInvalidArgument,
      "chunk merging global_ba_max_images must be -1, 0 or >= 2, got " << global_ba_max_images);
  bundle_adjustment.Check();
}

namespace {

// One physical point as the two models give it, seen by a feature of a shared frame.
struct PointPair {
  Eigen::Vector3d chunk_xyz;
  Eigen::Vector3d model_xyz;
  double depth = 0.0;  // of model_xyz in the shared frame (the model's units)
};

// A feature's pixel as a key: a shared frame's features come from one detector run on one image
// and are written alike by both chunks, so equal positions are exactly equal.
using PixelKey = std::pair<double, double>;

std::map<std::string, image_t> RegisteredImagesByName(const Reconstruction& reconstruction) {
  std::map<std::string, image_t> ids;
  for (const auto& [id, image] : reconstruction.images()) {
    if (image.registered) ids.emplace(image.name, id);
  }
  return ids;
}

// For each frame registered in both: the chunk's point2D index -> the model's with the same pixel.
std::map<image_t, std::map<point2D_t, point2D_t>> SharedFeatures(
    const Reconstruction& model, const Reconstruction& chunk,
    std::map<image_t, image_t>* model_image_of_chunk_image) {
  const std::map<std::string, image_t> model_ids = RegisteredImagesByName(model);
  std::map<image_t, std::map<point2D_t, point2D_t>> shared;
  for (const auto& [chunk_id, chunk_image] : chunk.images()) {
    if (!chunk_image.registered) continue;
    const auto found = model_ids.find(chunk_image.name);
    if (found == model_ids.end()) continue;
    (*model_image_of_chunk_image)[chunk_id] = found->second;
    std::map<PixelKey, point2D_t> model_index;
    const Image& model_image = model.image(found->second);
    for (point2D_t i = 0; i < model_image.points2D.size(); ++i) {
      const Eigen::Vector2d& xy = model_image.points2D[i].xy;
      model_index.emplace(PixelKey(xy.x(), xy.y()), i);
    }
    std::map<point2D_t, point2D_t>& features = shared[chunk_id];
    for (point2D_t i = 0; i < chunk_image.points2D.size(); ++i) {
      const Eigen::Vector2d& xy = chunk_image.points2D[i].xy;
      const auto match = model_index.find(PixelKey(xy.x(), xy.y()));
      if (match != model_index.end()) features.emplace(i, match->second);
    }
  }
  return shared;
}

std::vector<PointPair> PointPairs(const Reconstruction& model, const Reconstruction& chunk,
                                  const std::map<image_t, std::map<point2D_t, point2D_t>>& shared,
                                  const std::map<image_t, image_t>& model_image_of_chunk_image) {
  std::vector<PointPair> pairs;
  for (const auto& [chunk_id, features] : shared) {
    const Image& chunk_image = chunk.image(chunk_id);
    const Image& model_image = model.image(model_image_of_chunk_image.at(chunk_id));
    for (const auto& [chunk_idx, model_idx] : features) {
      const Point2D& chunk_point = chunk_image.points2D[chunk_idx];
      const Point2D& model_point = model_image.points2D[model_idx];
      if (!chunk_point.HasPoint3D() || !model_point.HasPoint3D()) continue;
      PointPair pair;
      pair.chunk_xyz = chunk.point3D(chunk_point.point3D_id).xyz;
      pair.model_xyz = model.point3D(model_point.point3D_id).xyz;
      pair.depth = (model_image.cam_from_world * pair.model_xyz).z();
      if (pair.depth > 0) pairs.push_back(pair);
    }
  }
  return pairs;
}

// The similarity taking the chunk's points onto the model's (EstimateSim3dRansac), a pair
// agreeing when it lands within max_relative_distance of its depth in the model.
std::optional<Sim3d> EstimateModelFromChunk(const std::vector<PointPair>& pairs,
                                            const ChunkMergingOptions& options, int* num_inliers) {
  std::vector<Eigen::Vector3d> chunk_points, model_points;
  for (const PointPair& pair : pairs) {
    chunk_points.push_back(pair.chunk_xyz);
    model_points.push_back(pair.model_xyz);
  }
  return EstimateSim3dRansac(
      chunk_points, model_points,
      [&](const Sim3d& sim, size_t i) {
        return (sim * pairs[i].chunk_xyz - pairs[i].model_xyz).norm() <=
               options.max_relative_distance * pairs[i].depth;
      },
      options.min_num_inliers, options.min_inlier_ratio, num_inliers);
}

camera_t FindOrAddCamera(const Camera& camera, Reconstruction* model) {
  for (const auto& [id, existing] : model->cameras()) {
    if (existing.model == camera.model && existing.width == camera.width &&
        existing.height == camera.height && existing.Params() == camera.Params()) {
      return id;
    }
  }
  return model->AddCamera(camera);
}

// Adds the chunk's frames the model lacks (poses mapped by `model_from_chunk`) and its points
// (mapped; fused with the model's point where a shared frame's feature has one and the two agree
// as the similarity's pairs must: a disagreeing pair is a wrong point in one of the two, and
// fusing it would pull the right one; the chunk's point then keeps its other observations).
void AddChunk(const Reconstruction& chunk, const Sim3d& model_from_chunk,
              const std::map<image_t, std::map<point2D_t, point2D_t>>& shared,
              const std::map<image_t, image_t>& model_image_of_chunk_image,
              double max_relative_distance, Reconstruction* model) {
  std::map<camera_t, camera_t> camera_ids;
  for (const auto& [id, camera] : chunk.cameras()) camera_ids[id] = FindOrAddCamera(camera, model);
  std::map<image_t, image_t> new_image_ids;
  for (const auto& [id, chunk_image] : chunk.images()) {
    if (!chunk_image.registered || model_image_of_chunk_image.count(id)) continue;
    Image image;
    image.camera_id = camera_ids.at(chunk_image.camera_id);
    image.name = chunk_image.name;
    image.cam_from_world = model_from_chunk.TransformPose(chunk_image.cam_from_world);
    for (const Point2D& point : chunk_image.points2D) {
      Point2D unlinked;
      unlinked.xy = point.xy;
      image.points2D.push_back(unlinked);
    }
    const image_t new_id = model->AddImage(std::move(image));
    model->RegisterImage(new_id);
    new_image_ids[id] = new_id;
  }
  for (const auto& [chunk_point_id, chunk_point] : chunk.points3D()) {
    std::vector<TrackElement> track;
    point3D_t fused = kInvalidPoint3DId;
    for (const TrackElement& element : chunk_point.track) {
      const auto added = new_image_ids.find(element.image_id);
      if (added != new_image_ids.end()) {
        track.push_back({added->second, element.point2D_idx});
        continue;
      }
      const auto features = shared.find(element.image_id);
      if (features == shared.end()) continue;
      const auto feature = features->second.find(element.point2D_idx);
      if (feature == features->second.end()) continue;
      const image_t model_id = model_image_of_chunk_image.at(element.image_id);
      const Point2D& point = model->image(model_id).points2D[feature->second];
      if (point.HasPoint3D()) {
        const Eigen::Vector3d& xyz = model->point3D(point.point3D_id).xyz;
        const double depth = (model->image(model_id).cam_from_world * xyz).z();
        const bool agree =
            (model_from_chunk * chunk_point.xyz - xyz).norm() <= max_relative_distance * depth;
        if (agree && fused == kInvalidPoint3DId) fused = point.point3D_id;
      } else {
        track.push_back({model_id, feature->second});
      }
    }
    if (fused != kInvalidPoint3DId) {
      for (const TrackElement& element : track) {
        const Point2D& point = model->image(element.image_id).points2D[element.point2D_idx];
        const bool seen_already =
            std::any_of(model->point3D(fused).track.begin(), model->point3D(fused).track.end(),
                        [&](const TrackElement& e) { return e.image_id == element.image_id; });
        if (!point.HasPoint3D() && !seen_already) model->AddObservation(fused, element);
      }
    } else if (track.size() >= 2) {
      model->AddPoint3D(model_from_chunk * chunk_point.xyz, track, chunk_point.color);
    }
  }
}

// A chunk as a model of its own: its registered frames, their cameras and its points.
Reconstruction StartModel(const Reconstruction& chunk) {
  Reconstruction model;
  AddChunk(chunk, Sim3d(), {}, {}, 0.0, &model);
  return model;
}

// The final adjustment: windows of `window` frames in name order (image ids follow the chunks'
// order), half a window apart; the first window's first pose and second scale fix the gauge, the
// frames outside a later window that see its points hold it.
std::vector<BundleAdjustmentSummary> AdjustInWindows(const BundleAdjustmentOptions& ba_options,
                                                     int window, Reconstruction* model) {
  std::vector<image_t> ids;
  {
    std::map<std::string, image_t> by_name = RegisteredImagesByName(*model);
    for (const auto& [name, id] : by_name) ids.push_back(id);
  }
  std::vector<BundleAdjustmentSummary> summaries;
  if (ids.size() < 2) return summaries;
  const size_t size = window == 0 ? ids.size() : static_cast<size_t>(window);
  const size_t step = std::max<size_t>(1, size / 2);
  for (size_t begin = 0; begin < ids.size(); begin += step) {
    const size_t end = std::min(ids.size(), begin + size);
    BundleAdjustmentConfig config;
    config.image_ids.insert(ids.begin() + begin, ids.begin() + end);
    const std::set<point3D_t> point_ids = PointsSeenBy(*model, config.image_ids);
    if (begin == 0 || ConstantNeighbourImages(*model, config.image_ids, point_ids).size() < 2) {
      config.constant_pose_ids.insert(ids[begin]);
      if (end - begin >= 2) config.fixed_scale_image_ids.insert(ids[begin + 1]);
    }
    summaries.push_back(BundleAdjuster(ba_options, config).Solve(model));
    if (end == ids.size()) break;
  }
  return summaries;
}

}  // namespace

ChunkMergingResult MergeChunkModels(const std::vector<Reconstruction>& chunks,
                                    const ChunkMergingOptions& options) {
  options.Check();
  ChunkMergingResult result;
  result.chunks.resize(chunks.size());
  int current = -1;  // the model the chunk before is in
  for (size_t c = 0; c < chunks.size(); ++c) {
    ChunkMergeOutcome& outcome = result.chunks[c];
    const Reconstruction& chunk = chunks[c];
    if (chunk.NumRegisteredImages() == 0) {
      outcome.reason = "no registered frame";
      continue;
    }
    if (current >= 0) {
      Reconstruction& model = result.models[static_cast<size_t>(current)];
      std::map<image_t, image_t> model_image_of_chunk_image;
      const auto shared = SharedFeatures(model, chunk, &model_image_of_chunk_image);
      const std::vector<PointPair> pairs =
          PointPairs(model, chunk, shared, model_image_of_chunk_image);
      outcome.num_shared_frames = static_cast<int>(model_image_of_chunk_image.size());
      outcome.num_point_pairs = static_cast<int>(pairs.size());
      const std::optional<Sim3d> sim = EstimateModelFromChunk(pairs, options, &outcome.num_inliers);
      if (sim) {
        AddChunk(chunk, *sim, shared, model_image_of_chunk_image, options.max_relative_distance,
                 &model);
        outcome.model_index = current;
        outcome.model_from_chunk = *sim;
        continue;
      }
      outcome.reason = outcome.num_shared_frames == 0
                           ? "no frame registered in the model before"
                           : "too few points of the shared frames agree on a similarity";
    }
    result.models.push_back(StartModel(chunk));
    current = static_cast<int>(result.models.size()) - 1;
    outcome.model_index = current;
    outcome.started_model = true;
  }
  if (options.global_ba_max_images >= 0) {
    for (Reconstruction& model : result.models) {
      for (BundleAdjustmentSummary& summary :
           AdjustInWindows(options.bundle_adjustment, options.global_ba_max_images, &model)) {
        result.adjustments.push_back(std::move(summary));
      }
    }
  }
  return result;
}

}  // namespace comic::sfm
