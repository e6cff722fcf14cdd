#include "sfm/incremental_pipeline.h"

#include <chrono>
#include <map>

#include "io/error.h"

namespace comic::sfm {

const char* ReconstructionStatusName(ReconstructionStatus status) {
  switch (status) {
    case ReconstructionStatus::kSuccess:
      return "success";
    case ReconstructionStatus::kTooFewFrames:
      return "too_few_frames";
    case ReconstructionStatus::kNoInitialPair:
      return "no_initial_pair";
    case ReconstructionStatus::kTooFewPoints:
      return "too_few_points";
  }
  return "unknown";
}

std::string ReconstructionStatusMessage(ReconstructionStatus status) {
  switch (status) {
    case ReconstructionStatus::kSuccess:
      return "reconstruction succeeded";
    case ReconstructionStatus::kTooFewFrames:
      return "too few frames: at least two are needed";
    case ReconstructionStatus::kNoInitialPair:
      return "no initial pair: no two frames share enough tracks with enough parallax (pure "
             "rotation, planar scene, or too few tracked features)";
    case ReconstructionStatus::kTooFewPoints:
      return "too few points: the initial pair triangulated too few 3-D points";
  }
  return "unknown status";
}

IncrementalPipelineOptions::IncrementalPipelineOptions() {
  // A local window needs fewer iterations than the whole model: it starts close to the optimum.
  local_ba.max_num_iterations = 25;
  global_ba.max_num_iterations = 100;
}

void IncrementalPipelineOptions::Check() const {
  mapper.Check();
  local_ba.Check();
  global_ba.Check();
  COMIC_CHECK(local_ba_num_images >= 2, kInvalidArgument,
              "pipeline local_ba_num_images must be >= 2, got " << local_ba_num_images);
  COMIC_CHECK(global_ba_growth_ratio > 1.0, kInvalidArgument,
              "pipeline global_ba_growth_ratio must be > 1, got " << global_ba_growth_ratio);
  COMIC_CHECK(max_registration_trials >= 1, kInvalidArgument,
              "pipeline max_registration_trials must be >= 1");
  COMIC_CHECK(min_num_initial_points >= 1, kInvalidArgument,
              "pipeline min_num_initial_points must be >= 1");
}

namespace {

void Report(const MapperProgressCallback& progress, const IncrementalMapper& mapper,
            image_t image_id, bool initial, int num_inliers) {
  if (!progress) return;
  MapperProgress p;
  p.frame = IncrementalMapper::FrameOfImageId(image_id);
  p.frame_name = mapper.reconstruction().image(image_id).name;
  p.initial_pair = initial;
  p.num_registered = mapper.reconstruction().NumRegisteredImages();
  p.num_frames = mapper.reconstruction().NumImages();
  p.num_points3D = mapper.reconstruction().NumPoints3D();
  p.num_pose_inliers = num_inliers;
  progress(p);
}

}  // namespace

IncrementalReconstruction ReconstructIncrementally(const frontend::FeatureTracks& tracks,
                                                   const Camera& camera,
                                                   const IncrementalPipelineOptions& options,
                                                   const MapperProgressCallback& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  IncrementalReconstruction result;
  IncrementalMapper mapper(tracks, camera, options.mapper);
  const auto finish = [&](ReconstructionStatus status) {
    result.status = status;
    result.reconstruction = mapper.TakeReconstruction();
    for (const auto& [image_id, image] : result.reconstruction.images()) {
      (image.registered ? result.registered_frames : result.unregistered_frames)
          .push_back(IncrementalMapper::FrameOfImageId(image_id));
    }
    result.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(result);
  };
  const auto global_ba = [&]() {
    const BundleAdjustmentSummary summary = mapper.AdjustGlobalBundle(options.global_ba);
    ++result.num_global_ba;
    result.global_ba_time_s += summary.wall_time_s;
    result.final_ba = summary;
  };

  if (tracks.NumFrames() < 2) return finish(ReconstructionStatus::kTooFewFrames);
  const auto pair = mapper.FindInitialPair();
  if (!pair) return finish(ReconstructionStatus::kNoInitialPair);
  result.initial_frame1 = IncrementalMapper::FrameOfImageId(pair->image_id1);
  result.initial_frame2 = IncrementalMapper::FrameOfImageId(pair->image_id2);
  if (mapper.RegisterInitialPair(*pair) < static_cast<size_t>(options.min_num_initial_points)) {
    return finish(ReconstructionStatus::kTooFewPoints);
  }
  global_ba();
  if (mapper.reconstruction().NumPoints3D() < static_cast<size_t>(options.min_num_initial_points)) {
    return finish(ReconstructionStatus::kTooFewPoints);
  }
  Report(progress, mapper, pair->image_id1, true, 0);
  Report(progress, mapper, pair->image_id2, true, 0);

  std::map<image_t, int> num_trials;
  size_t num_registered_at_last_global_ba = mapper.reconstruction().NumRegisteredImages();
  while (true) {
    bool registered = false;
    for (image_t image_id : mapper.NextImageCandidates()) {
      if (num_trials[image_id] >= options.max_registration_trials) continue;
      if (!mapper.RegisterNextImage(image_id)) {
        ++num_trials[image_id];
        continue;
      }
      const int num_inliers = mapper.last_num_pose_inliers();
      mapper.TriangulateImage(image_id);
      const BundleAdjustmentSummary summary =
          mapper.AdjustLocalBundle(image_id, options.local_ba, options.local_ba_num_images);
      ++result.num_local_ba;
      result.local_ba_time_s += summary.wall_time_s;
      const size_t num_registered = mapper.reconstruction().NumRegisteredImages();
      if (static_cast<double>(num_registered) >=
          options.global_ba_growth_ratio * static_cast<double>(num_registered_at_last_global_ba)) {
        global_ba();
        mapper.TriangulateAllTracks();
        num_registered_at_last_global_ba = num_registered;
      }
      Report(progress, mapper, image_id, false, num_inliers);
      registered = true;
      break;
    }
    if (!registered) break;
  }

  // Final refinement: adjust, recover tracks the improved poses now explain, adjust again.
  global_ba();
  if (mapper.TriangulateAllTracks() > 0) global_ba();
  return finish(ReconstructionStatus::kSuccess);
}

}  // namespace comic::sfm
