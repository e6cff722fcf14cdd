#include "sfm/incremental_pipeline.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <set>

#include "io/core/error.h"

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
  // A local window starts close to its optimum and the global adjustments follow: on KITTI, 10
  // iterations give the same trajectory (ATE within 1 mm) as 25 in a third of the time.
  local_ba.max_num_iterations = 10;
  global_ba.max_num_iterations = 50;
  // Stopping tolerances (relative cost gain of an iteration), as loose as the trajectory allows.
  // Weak-perspective scenes (the Middlebury dino, f = 3310 px) otherwise crawl along a nearly flat
  // valley for all iterations, gaining 1e-6 per step. On KITTI 06 with Harris tracks (process CPU
  // time of the mapper; docs/sfm.md "Speed"): a 6-image window with global 1e-4 instead of 8 images
  // and 1e-5 gives 8.8 instead of 10.9 s (ATE 0.0283 vs 0.0278 m; global 1e-3: 0.0329 m); local
  // 1e-3 on top halves the local adjustments (3.4 -> 1.8 s) at the same ATE (0.0284 m), since the
  // next window and the global adjustments go on refining the same poses.
  local_ba.function_tolerance = 1e-3;
  global_ba.function_tolerance = 1e-4;
  // Soft-L1 rather than Huber in the global adjustments: with Huber, Ceres models the cost of a
  // residual in its linear part by reweighting alone, Levenberg-Marquardt's steps then fall short
  // (each realised about twice the predicted decrease) and the final adjustment of KITTI's Harris
  // tracks crawled through 23 iterations; Soft-L1's curvature correction converges in about half
  // (docs/sfm.md "Loss"). The local windows keep Huber (Soft-L1 there cost dino ATE).
  global_ba.loss = BundleAdjustmentLoss::kSoftL1;
}

void IncrementalPipelineOptions::Check() const {
  mapper.Check();
  local_ba.Check();
  global_ba.Check();
  COMIC_CHECK(local_ba_num_images >= 2, kInvalidArgument,
              "pipeline local_ba_num_images must be >= 2, got " << local_ba_num_images);
  COMIC_CHECK(final_global_ba_function_tolerance >= 0, kInvalidArgument,
              "pipeline final_global_ba_function_tolerance must be >= 0");
  COMIC_CHECK(global_ba_growth_ratio > 1.0, kInvalidArgument,
              "pipeline global_ba_growth_ratio must be > 1, got " << global_ba_growth_ratio);
  COMIC_CHECK(max_registration_trials >= 1, kInvalidArgument,
              "pipeline max_registration_trials must be >= 1");
  COMIC_CHECK(min_num_initial_points >= 1, kInvalidArgument,
              "pipeline min_num_initial_points must be >= 1");
  COMIC_CHECK(max_num_models >= 1, kInvalidArgument, "pipeline max_num_models must be >= 1");
  COMIC_CHECK(refine_intrinsics_min_num_images >= 2, kInvalidArgument,
              "pipeline refine_intrinsics_min_num_images must be >= 2, got "
                  << refine_intrinsics_min_num_images);
  focal_observability.Check();
}

namespace {

void Report(const MapperProgressCallback& progress, const IncrementalMapper& mapper,
            image_t image_id, bool initial, int num_inliers, int attempt, bool merged = false) {
  if (!progress) return;
  MapperProgress p;
  p.merged = merged;
  p.frame = IncrementalMapper::FrameOfImageId(image_id);
  p.frame_name = mapper.reconstruction().image(image_id).name;
  p.initial_pair = initial;
  p.attempt = attempt;
  p.num_registered = mapper.reconstruction().NumRegisteredImages();
  p.num_frames = mapper.reconstruction().NumImages();
  p.num_points3D = mapper.reconstruction().NumPoints3D();
  p.num_pose_inliers = num_inliers;
  progress(p);
}

// One model grown from `pair` (std::nullopt: no initial pair).
IncrementalReconstruction ReconstructOnce(const frontend::FeatureTracks& tracks,
                                          const Camera& camera,
                                          const IncrementalPipelineOptions& options,
                                          const std::optional<IncrementalMapper::InitialPair>& pair,
                                          int attempt,
                                          const std::vector<Reconstruction>& earlier_models,
                                          const MapperProgressCallback& progress) {
  IncrementalReconstruction result;
  IncrementalMapper mapper(tracks, camera, options.mapper);
  const auto finish = [&](ReconstructionStatus status) {
    result.status = status;
    result.reconstruction = mapper.TakeReconstruction();
    if (status != ReconstructionStatus::kSuccess) {
      // A model that failed to start is no model: nothing registered, no points.
      for (image_t image_id : result.reconstruction.RegisteredImageIds()) {
        result.reconstruction.DeRegisterImage(image_id);
      }
    }
    for (const auto& [image_id, image] : result.reconstruction.images()) {
      (image.registered ? result.registered_frames : result.unregistered_frames)
          .push_back(IncrementalMapper::FrameOfImageId(image_id));
    }
    return std::move(result);
  };
  BundleAdjustmentOptions final_global_ba = options.global_ba;
  final_global_ba.function_tolerance = options.final_global_ba_function_tolerance;
  const auto global_ba = [&](bool final = false) {
    BundleAdjustmentOptions ba_options = final ? final_global_ba : options.global_ba;
    const Reconstruction& model = mapper.reconstruction();
    if (static_cast<int>(model.NumRegisteredImages()) < options.refine_intrinsics_min_num_images) {
      ba_options.refine_focal_length = false;
      ba_options.refine_principal_point = false;
      ba_options.refine_extra_params = false;
    } else if (ba_options.refine_focal_length) {
      result.focal_assessed = true;
      result.focal_observability = AssessFocalObservability(model, options.focal_observability);
      // Unobservable: keep the prior focal, and the prior distortion too, which would otherwise
      // absorb the focal's error (KITTI without calib.txt: k drifts to 0.07 for a rectified
      // image with f held 2x too long).
      if (!result.focal_observability.observable) {
        ba_options.refine_focal_length = false;
        ba_options.refine_extra_params = false;
      }
    }
    const BundleAdjustmentSummary summary = mapper.AdjustGlobalBundle(ba_options);
    ++result.num_global_ba;
    result.num_global_ba_iterations += summary.num_iterations;
    result.global_ba_time_s += summary.wall_time_s;
    result.global_ba_cpu_time_s += summary.cpu_time_s;
    result.final_ba = summary;
    result.intrinsics_refined = result.intrinsics_refined || summary.refined_intrinsics;
  };

  if (!pair) return finish(ReconstructionStatus::kNoInitialPair);
  result.initial_frame1 = IncrementalMapper::FrameOfImageId(pair->image_id1);
  result.initial_frame2 = IncrementalMapper::FrameOfImageId(pair->image_id2);
  result.initial_pair_num_points = mapper.RegisterInitialPair(*pair);
  if (result.initial_pair_num_points < static_cast<size_t>(options.min_num_initial_points)) {
    return finish(ReconstructionStatus::kTooFewPoints);
  }
  global_ba();
  result.initial_pair_num_points = mapper.reconstruction().NumPoints3D();
  if (mapper.reconstruction().NumPoints3D() < static_cast<size_t>(options.min_num_initial_points)) {
    return finish(ReconstructionStatus::kTooFewPoints);
  }
  Report(progress, mapper, pair->image_id1, true, 0, attempt);
  Report(progress, mapper, pair->image_id2, true, 0, attempt);

  std::map<image_t, int> num_trials;
  size_t num_registered_at_last_global_ba = mapper.reconstruction().NumRegisteredImages();
  size_t num_registered_at_last_retry = 0;
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
      result.num_local_ba_iterations += summary.num_iterations;
      result.local_ba_time_s += summary.wall_time_s;
      result.local_ba_cpu_time_s += summary.cpu_time_s;
      const size_t num_registered = mapper.reconstruction().NumRegisteredImages();
      if (static_cast<double>(num_registered) >=
          options.global_ba_growth_ratio * static_cast<double>(num_registered_at_last_global_ba)) {
        global_ba();
        mapper.TriangulateAllTracks();
        num_registered_at_last_global_ba = num_registered;
        // The adjusted poses and the new points may now explain frames that failed before.
        num_trials.clear();
      }
      Report(progress, mapper, image_id, false, num_inliers, attempt);
      registered = true;
      break;
    }
    if (registered) continue;
    // Stopped short of some frames: adjust everything, complete the tracks and retry the frames
    // left out once more before giving up on them (a weakly textured stretch of video often
    // registers once the points next to it are refined and triangulated from all views).
    const size_t num_registered = mapper.reconstruction().NumRegisteredImages();
    if (num_registered < mapper.reconstruction().NumImages() &&
        num_registered > num_registered_at_last_retry) {
      num_registered_at_last_retry = num_registered;
      if (num_registered_at_last_global_ba < num_registered) {
        global_ba();
        mapper.TriangulateAllTracks();
        num_registered_at_last_global_ba = num_registered;
      }
      num_trials.clear();
      if (!mapper.NextImageCandidates().empty()) continue;
    }
    // Stopped short: merge the earlier models that share a frame with this one, then grow on.
    size_t num_merged = 0;
    if (options.merge_models) {
      for (const Reconstruction& other : earlier_models) {
        const size_t num_before = mapper.registration_order().size();
        if (mapper.MergeModel(other) == 0) continue;
        num_merged += mapper.registration_order().size() - num_before;
        for (size_t i = num_before; i < mapper.registration_order().size(); ++i) {
          Report(progress, mapper, mapper.registration_order()[i], false, 0, attempt, true);
        }
      }
    }
    if (num_merged == 0) break;
    global_ba();
    mapper.TriangulateAllTracks();
    num_registered_at_last_global_ba = mapper.reconstruction().NumRegisteredImages();
    num_trials.clear();
  }

  // Final refinement: adjust, recover tracks the improved poses now explain, adjust again.
  global_ba(/*final=*/true);
  if (mapper.TriangulateAllTracks() > 0) global_ba(/*final=*/true);
  return finish(ReconstructionStatus::kSuccess);
}

}  // namespace

IncrementalReconstruction ReconstructIncrementally(const frontend::FeatureTracks& tracks,
                                                   const Camera& camera,
                                                   const IncrementalPipelineOptions& options,
                                                   const MapperProgressCallback& progress) {
  options.Check();
  tracks.Check();
  camera.Check();
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ProcessCpuSeconds();
  IncrementalReconstruction best;
  if (tracks.NumFrames() < 2) {
    best.status = ReconstructionStatus::kTooFewFrames;
    for (size_t frame = 0; frame < tracks.NumFrames(); ++frame) {
      best.unregistered_frames.push_back(static_cast<int>(frame));
    }
  } else {
    // A model that stops short (a sparse ring that falls apart into segments) is kept only if no
    // later attempt, started from frames it did not reach, registers more.
    // The initial pairs are searched once and reused; only when every remaining candidate
    // touches a frame an earlier model reached is the search repeated without those frames.
    IncrementalMapper::Options search_options = options.mapper;
    std::optional<IncrementalMapper> searcher;
    searcher.emplace(tracks, camera, search_options);
    IncrementalMapper::InitialPairSearch first_search;
    std::vector<IncrementalMapper::InitialPair> candidates =
        searcher->FindInitialPairs({}, &first_search);
    if (candidates.empty() && options.relax_initial_pair) {
      // COLMAP's relaxation; the diagnosis of a failure stays that of the strict search.
      search_options.init_min_num_matches = std::max(5, search_options.init_min_num_matches / 2);
      search_options.init_min_num_inliers = std::max(5, search_options.init_min_num_inliers / 2);
      searcher.emplace(tracks, camera, search_options);
      candidates = searcher->FindInitialPairs({});
    }
    std::set<image_t> excluded;
    std::vector<Reconstruction> earlier_models;
    for (int attempt = 0; attempt < options.max_num_models; ++attempt) {
      const auto usable = [&](const IncrementalMapper::InitialPair& pair) {
        return !excluded.count(pair.image_id1) && !excluded.count(pair.image_id2);
      };
      auto it = std::find_if(candidates.begin(), candidates.end(), usable);
      if (it == candidates.end() && attempt > 0) {
        candidates = searcher->FindInitialPairs(excluded);
        it = candidates.begin();
      }
      std::optional<IncrementalMapper::InitialPair> pair;
      if (it != candidates.end()) pair = *it;
      IncrementalReconstruction model =
          ReconstructOnce(tracks, camera, options, pair, attempt, earlier_models, progress);
      const bool better =
          attempt == 0 || (model.status == ReconstructionStatus::kSuccess &&
                           (best.status != ReconstructionStatus::kSuccess ||
                            model.registered_frames.size() > best.registered_frames.size()));
      const int num_local_ba = best.num_local_ba + model.num_local_ba;
      const int num_global_ba = best.num_global_ba + model.num_global_ba;
      const int num_local_ba_iterations =
          best.num_local_ba_iterations + model.num_local_ba_iterations;
      const int num_global_ba_iterations =
          best.num_global_ba_iterations + model.num_global_ba_iterations;
      const double local_ba_time = best.local_ba_time_s + model.local_ba_time_s;
      const double global_ba_time = best.global_ba_time_s + model.global_ba_time_s;
      const double local_ba_cpu_time = best.local_ba_cpu_time_s + model.local_ba_cpu_time_s;
      const double global_ba_cpu_time = best.global_ba_cpu_time_s + model.global_ba_cpu_time_s;
      const bool complete = model.unregistered_frames.empty();
      const bool started = model.initial_frame1 >= 0;
      if (started) {
        excluded.insert(IncrementalMapper::ImageIdOfFrame(model.initial_frame1));
        excluded.insert(IncrementalMapper::ImageIdOfFrame(model.initial_frame2));
      }
      for (int frame : model.registered_frames) {
        excluded.insert(IncrementalMapper::ImageIdOfFrame(frame));
      }
      if (options.merge_models && model.status == ReconstructionStatus::kSuccess) {
        earlier_models.push_back(model.reconstruction);
      }
      if (better) best = std::move(model);
      best.num_models = attempt + 1;
      best.num_local_ba = num_local_ba;
      best.num_global_ba = num_global_ba;
      best.num_local_ba_iterations = num_local_ba_iterations;
      best.num_global_ba_iterations = num_global_ba_iterations;
      best.local_ba_time_s = local_ba_time;
      best.global_ba_time_s = global_ba_time;
      best.local_ba_cpu_time_s = local_ba_cpu_time;
      best.global_ba_cpu_time_s = global_ba_cpu_time;
      if (complete || !started) break;
    }
    best.initial_pair_search = first_search;
  }
  best.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  best.cpu_time_s = ProcessCpuSeconds() - cpu_start;
  return best;
}

}  // namespace comic::sfm
