#include "sfm/model_growth.h"

#include <algorithm>
#include <map>
#include <set>

namespace comic::sfm {

void BundleAdjustmentTally::AddLocal(const BundleAdjustmentSummary& summary) {
  ++num_local_ba;
  num_local_ba_iterations += summary.num_iterations;
  local_ba_time_s += summary.wall_time_s;
  local_ba_cpu_time_s += summary.cpu_time_s;
}

void BundleAdjustmentTally::AddGlobal(const BundleAdjustmentSummary& summary) {
  ++num_global_ba;
  num_global_ba_iterations += summary.num_iterations;
  global_ba_time_s += summary.wall_time_s;
  global_ba_cpu_time_s += summary.cpu_time_s;
}

void BundleAdjustmentTally::Add(const BundleAdjustmentTally& other) {
  num_local_ba += other.num_local_ba;
  num_global_ba += other.num_global_ba;
  num_final_ba_windows += other.num_final_ba_windows;
  num_local_ba_iterations += other.num_local_ba_iterations;
  num_global_ba_iterations += other.num_global_ba_iterations;
  local_ba_time_s += other.local_ba_time_s;
  global_ba_time_s += other.global_ba_time_s;
  local_ba_cpu_time_s += other.local_ba_cpu_time_s;
  global_ba_cpu_time_s += other.global_ba_cpu_time_s;
}

namespace {

// The state of one model's growth; Run() is the list of stages.
class ModelGrower {
 public:
  ModelGrower(const frontend::FeatureTracks& tracks, const Camera& camera,
              const IncrementalPipelineOptions& options, int attempt,
              const std::vector<const IncrementalModel*>& earlier, const SeamLinker& seam_linker,
              const MapperProgressCallback& progress, std::vector<KeyframeDecision>* keyframes)
      : tracks_(tracks),
        prior_(camera),
        options_(options),
        attempt_(attempt),
        earlier_(earlier),
        seam_linker_(seam_linker),
        progress_(progress),
        mapper_(tracks, camera, options.mapper),
        merged_(earlier.size(), 0),
        num_shared_(earlier.size(), 0),
        next_merge_at_(earlier.size(), options.merge_overlap_frames),
        keyframes_(keyframes) {
    if (!keyframes_) return;
    std::vector<char> is_keyframe;
    for (const KeyframeDecision& decision : *keyframes_) is_keyframe.push_back(decision.keyframe);
    mapper_.SetKeyframes(std::move(is_keyframe));
  }

  GrownModel Run(const IncrementalMapper::InitialPair& pair) {
    if (!Start(pair)) return Finish(ReconstructionStatus::kTooFewPoints);
    while (true) {
      if (TrialComplete()) break;
      if (RegisterNextFrame()) continue;
      // Stopped short of some frames: adjust everything, complete the tracks and retry the
      // frames left out once more before giving up on them (a weakly textured stretch of video
      // often registers once the points next to it are refined and triangulated from all
      // views).
      if (RetryAfterGlobalAdjustment()) continue;
      // Stopped short: merge the earlier models this one can be linked to, then grow on.
      if (!MergeEarlierModels()) break;
    }
    // Revisited places: close the loops before the final adjustment holds them.
    if (options_.close_loops) {
      result_.loop_closure = CloseLoops(tracks_, options_.loop_closure, &mapper_);
    }
    // Final refinement: adjust, recover tracks (and loop points) the improved poses now explain,
    // adjust again. A bounded final adjustment sweeps the model once: the points recovered after
    // it are a percent of the model, and a second sweep cost a fifth of the mapping on the
    // rendered loop drive for the same trajectory (docs/long_video.md).
    AdjustGlobally(/*final=*/true);
    const size_t num_fused = mapper_.FuseLinkedPoints(result_.loop_closure.links,
                                                      /*keep_unexplained=*/true);
    result_.loop_closure.num_points_fused += num_fused;
    const size_t num_recovered = mapper_.TriangulateAllTracks();
    if ((num_recovered > 0 || num_fused > 0) && !FinalAdjustmentBounded()) {
      AdjustGlobally(/*final=*/true);
    }
    // The frames outside the map, posed against it as it is final.
    for (image_t image_id : mapper_.LocalizeNonKeyframes()) {
      result_.non_keyframes_lost.push_back(IncrementalMapper::FrameOfImageId(image_id));
    }
    return Finish(ReconstructionStatus::kSuccess);
  }

 private:
  // A trial growth (IncrementalPipelineOptions::max_registered_frames) has its frames.
  bool TrialComplete() const {
    return options_.max_registered_frames > 0 &&
           static_cast<int>(mapper_.reconstruction().NumRegisteredImages()) >=
               options_.max_registered_frames;
  }

  // Registers the pair and adjusts it; false if it keeps too few points.
  bool Start(const IncrementalMapper::InitialPair& pair) {
    result_.model.initial_frame1 = IncrementalMapper::FrameOfImageId(pair.image_id1);
    result_.model.initial_frame2 = IncrementalMapper::FrameOfImageId(pair.image_id2);
    const auto enough = [&](size_t num_points) {
      return num_points >= static_cast<size_t>(options_.min_num_initial_points);
    };
    result_.initial_pair_num_points = mapper_.RegisterInitialPair(pair);
    for (image_t image_id : {pair.image_id1, pair.image_id2}) {
      MarkKeyframe(image_id, KeyframeReason::kInitialPair);
    }
    if (!enough(result_.initial_pair_num_points)) return false;
    AdjustGlobally();
    result_.initial_pair_num_points = mapper_.reconstruction().NumPoints3D();
    if (!enough(result_.initial_pair_num_points)) return false;
    Report(pair.image_id1, /*initial=*/true, 0);
    Report(pair.image_id2, /*initial=*/true, 0);
    num_registered_at_last_global_ba_ = mapper_.reconstruction().NumRegisteredImages();
    return true;
  }

  // Registers the best candidate that registers; false if none does.
  bool RegisterNextFrame() {
    for (image_t image_id : mapper_.NextImageCandidates()) {
      if (num_trials_[image_id] >= options_.max_registration_trials) continue;
      // A frame between keyframes that did not register would leave the map without new points
      // there: it maps instead.
      const bool promote = !mapper_.IsKeyframe(image_id) && !KeyframeBesideRegistered(image_id);
      if (promote) {
        mapper_.PromoteToKeyframe(image_id);
        MarkKeyframe(image_id, KeyframeReason::kPromoted);
      }
      if (!mapper_.RegisterNextImage(image_id)) {
        ++num_trials_[image_id];
        continue;
      }
      const int num_inliers = mapper_.last_num_pose_inliers();
      if (mapper_.IsKeyframe(image_id)) {
        mapper_.TriangulateImage(image_id);
        result_.ba.AddLocal(
            mapper_.AdjustLocalBundle(image_id, options_.local_ba, options_.local_ba_num_images));
      }
      if (GlobalAdjustmentDue()) AdjustAndTriangulate();
      Report(image_id, /*initial=*/false, num_inliers);
      MergeOverlappingModels(image_id);
      return true;
    }
    return false;
  }

  // When the model has grown by global_ba_growth_ratio since the last global adjustment. Bounded
  // adjustments (global_ba_max_images) keep that schedule: the final sweep of windows puts
  // every frame in an adjustment, and adjusting every half window as well cost more for a worse
  // trajectory on the rendered loop drive (docs/long_video.md).
  bool GlobalAdjustmentDue() const {
    const double num_registered =
        static_cast<double>(mapper_.reconstruction().NumRegisteredImages());
    const double last = static_cast<double>(num_registered_at_last_global_ba_);
    return num_registered >= options_.global_ba_growth_ratio * last;
  }

  bool RetryAfterGlobalAdjustment() {
    const size_t num_registered = mapper_.reconstruction().NumRegisteredImages();
    if (num_registered >= mapper_.reconstruction().NumImages() ||
        num_registered <= num_registered_at_last_retry_) {
      return false;
    }
    num_registered_at_last_retry_ = num_registered;
    // The frames left out can be anywhere in the model, not only beside the adjusted window.
    if (num_registered_at_last_global_ba_ < num_registered) {
      AdjustAndTriangulate(TracksToTriangulate::kEveryTrack);
    }
    num_trials_.clear();
    return !mapper_.NextImageCandidates().empty();
  }

  // Once this model has registered merge_overlap_frames frames an earlier model holds (and at
  // each doubling), the earlier model is merged: growing it again would only repeat its work.
  void MergeOverlappingModels(image_t image_id) {
    if (!options_.merge_models) return;
    for (size_t e = 0; e < earlier_.size(); ++e) {
      if (merged_[e]) continue;
      const Reconstruction& other = earlier_[e]->reconstruction;
      if (!other.ExistsImage(image_id) || !other.image(image_id).registered) continue;
      if (++num_shared_[e] < next_merge_at_[e]) continue;
      next_merge_at_[e] *= 2;
      if (Merge(e, {}) > 0) AdjustAndTriangulate();
    }
  }

  // Merges every earlier model this one can be linked to; false if none.
  bool MergeEarlierModels() {
    if (!options_.merge_models) return false;
    size_t num_merged = 0;
    for (size_t e = 0; e < earlier_.size(); ++e) {
      if (merged_[e]) continue;
      size_t num_added = Merge(e, {});
      if (num_added == 0 && seam_linker_) {
        const std::vector<IncrementalMapper::FeatureLink> links =
            seam_linker_(mapper_.reconstruction(), earlier_[e]->reconstruction);
        if (!links.empty()) {
          num_added = Merge(e, links);
          if (num_added > 0) ++result_.num_seam_links;
        }
      }
      num_merged += num_added;
    }
    if (num_merged == 0) return false;
    AdjustAndTriangulate();
    return true;
  }

  // Merges earlier model `e` (with `links`); the number of frames it added.
  size_t Merge(size_t e, const std::vector<IncrementalMapper::FeatureLink>& links) {
    const size_t num_before = mapper_.registration_order().size();
    const size_t num_added = mapper_.MergeModel(earlier_[e]->reconstruction, links);
    if (num_added == 0) return 0;
    merged_[e] = 1;
    result_.merged.push_back(e);
    for (size_t i = num_before; i < mapper_.registration_order().size(); ++i) {
      Report(mapper_.registration_order()[i], /*initial=*/false, 0, /*merged=*/true);
    }
    return num_added;
  }

  // After a bounded adjustment only the tracks of its frames can have changed; walking every
  // track after each of them would grow with the video.
  enum class TracksToTriangulate { kOfAdjustedFrames, kEveryTrack };

  void AdjustAndTriangulate(TracksToTriangulate tracks = TracksToTriangulate::kOfAdjustedFrames) {
    AdjustGlobally();
    const int window = options_.global_ba_max_images;
    if (window > 0 && tracks == TracksToTriangulate::kOfAdjustedFrames) {
      mapper_.TriangulateTracksOf(mapper_.NewestKeyframes(window));
    } else {
      mapper_.TriangulateAllTracks();
    }
    num_registered_at_last_global_ba_ = mapper_.reconstruction().NumRegisteredImages();
    // The adjusted poses and the new points may now explain frames that failed before.
    num_trials_.clear();
  }

  // A global adjustment, refining the intrinsics the options ask for once enough frames
  // constrain them and the motion observes the focal length; a refined camera that leaves the
  // plausible range is reset to the prior and held fixed from then on.
  void AdjustGlobally(bool final = false) {
    BundleAdjustmentOptions ba_options = options_.global_ba;
    if (final) ba_options.function_tolerance = options_.final_global_ba_function_tolerance;
    const Reconstruction& model = mapper_.reconstruction();
    const int window = options_.global_ba_max_images;
    if (final && FinalAdjustmentBounded()) {
      // Bounded adjustments bound the final one too: the model in overlapping windows, so that
      // neither its cost per frame nor its memory grows with the video (issue 26). The
      // intrinsics stay as the adjustments while the model grew left them: refined in one
      // window they would disagree with the frames held constant around it.
      HoldIntrinsics(&ba_options);
      for (const BundleAdjustmentSummary& summary :
           mapper_.AdjustGlobalBundleInWindows(ba_options, window)) {
        result_.ba.AddGlobal(summary);
        ++result_.ba.num_final_ba_windows;
        result_.final_ba = summary;
      }
      return;
    }
    if (intrinsics_held_ ||
        static_cast<int>(model.NumRegisteredImages()) < options_.refine_intrinsics_min_num_images) {
      HoldIntrinsics(&ba_options);
    } else if (ba_options.refine_focal_length) {
      result_.focal_assessed = true;
      result_.focal_observability = AssessFocalObservability(model, options_.focal_observability);
      // Unobservable: keep the prior focal, and the prior distortion too, which would otherwise
      // absorb the focal's error (KITTI without calib.txt: k drifts to 0.07 for a rectified
      // image with f held 2x too long).
      if (!result_.focal_observability.observable) {
        ba_options.refine_focal_length = false;
        ba_options.refine_extra_params = false;
      }
    }
    const int max_num_images = final ? 0 : options_.global_ba_max_images;
    BundleAdjustmentSummary summary = mapper_.AdjustGlobalBundle(ba_options, max_num_images);
    result_.ba.AddGlobal(summary);
    if (summary.refined_intrinsics) {
      const Camera& refined = mapper_.reconstruction().cameras().begin()->second;
      const IntrinsicsPlausibility check =
          CheckIntrinsicsPlausibility(prior_, refined, options_.plausible_intrinsics);
      if (!check.plausible) {
        result_.intrinsics_rejection = {true, refined, check.reason};
        mapper_.ResetCamera(prior_);
        intrinsics_held_ = true;
        HoldIntrinsics(&ba_options);
        summary = mapper_.AdjustGlobalBundle(ba_options, max_num_images);
        result_.ba.AddGlobal(summary);
      }
    }
    result_.final_ba = summary;
    result_.intrinsics_refined =
        !intrinsics_held_ && (result_.intrinsics_refined || summary.refined_intrinsics);
  }

  // Whether the nearest keyframe before `image_id` or the one after it is registered (true
  // where there is no keyframe selection).
  bool KeyframeBesideRegistered(image_t image_id) const {
    if (!keyframes_) return true;
    const Reconstruction& model = mapper_.reconstruction();
    const int frame = IncrementalMapper::FrameOfImageId(image_id);
    const int num_frames = static_cast<int>(keyframes_->size());
    for (int step : {-1, 1}) {
      for (int f = frame + step; f >= 0 && f < num_frames; f += step) {
        const image_t id = IncrementalMapper::ImageIdOfFrame(f);
        if (!mapper_.IsKeyframe(id)) continue;
        if (model.image(id).registered) return true;
        break;
      }
    }
    return false;
  }

  // Records that this model made `image_id` a keyframe (if it was not one already).
  void MarkKeyframe(image_t image_id, KeyframeReason reason) {
    if (!keyframes_) return;
    KeyframeDecision& decision = (*keyframes_)[IncrementalMapper::FrameOfImageId(image_id)];
    if (decision.keyframe) return;
    decision.keyframe = true;
    decision.reason = reason;
  }

  // Whether the final adjustment runs in windows (global_ba_max_images below the keyframes).
  bool FinalAdjustmentBounded() const {
    const int window = options_.global_ba_max_images;
    return window > 0 && NumRegisteredKeyframes() > window;
  }

  int NumRegisteredKeyframes() const {
    int count = 0;
    for (image_t id : mapper_.reconstruction().RegisteredImageIds())
      count += mapper_.IsKeyframe(id);
    return count;
  }

  static void HoldIntrinsics(BundleAdjustmentOptions* ba_options) {
    ba_options->refine_focal_length = false;
    ba_options->refine_principal_point = false;
    ba_options->refine_extra_params = false;
  }

  void Report(image_t image_id, bool initial, int num_inliers, bool merged = false) const {
    if (!progress_) return;
    const Reconstruction& model = mapper_.reconstruction();
    MapperProgress p;
    p.merged = merged;
    p.frame = IncrementalMapper::FrameOfImageId(image_id);
    p.frame_name = model.image(image_id).name;
    p.initial_pair = initial;
    p.attempt = attempt_;
    p.num_registered = model.NumRegisteredImages();
    p.num_frames = model.NumImages();
    p.num_points3D = model.NumPoints3D();
    p.num_pose_inliers = num_inliers;
    progress_(p);
  }

  GrownModel Finish(ReconstructionStatus status) {
    result_.status = status;
    result_.best_failed_pose_inliers = mapper_.best_failed_pose_inliers();
    IncrementalModel& model = result_.model;
    model.reconstruction = mapper_.TakeReconstruction();
    if (status != ReconstructionStatus::kSuccess) {
      // A model that failed to start is no model: nothing registered, no points.
      for (image_t image_id : model.reconstruction.RegisteredImageIds()) {
        model.reconstruction.DeRegisterImage(image_id);
      }
    }
    for (image_t image_id : model.reconstruction.RegisteredImageIds()) {
      model.registered_frames.push_back(IncrementalMapper::FrameOfImageId(image_id));
    }
    model.num_merged_models = static_cast<int>(result_.merged.size());
    for (size_t e : result_.merged) model.num_merged_models += earlier_[e]->num_merged_models;
    return std::move(result_);
  }

  const frontend::FeatureTracks& tracks_;
  const Camera prior_;
  const IncrementalPipelineOptions& options_;
  const int attempt_;
  const std::vector<const IncrementalModel*>& earlier_;
  const SeamLinker& seam_linker_;
  const MapperProgressCallback& progress_;
  IncrementalMapper mapper_;
  GrownModel result_;
  std::map<image_t, int> num_trials_;
  size_t num_registered_at_last_global_ba_ = 0;
  size_t num_registered_at_last_retry_ = 0;
  bool intrinsics_held_ = false;
  // Per earlier model: merged already, frames registered here that it holds, and the overlap at
  // which merging is tried next.
  std::vector<char> merged_;
  std::vector<int> num_shared_;
  std::vector<int> next_merge_at_;
  std::vector<KeyframeDecision>* keyframes_;  // nullptr: every frame is a keyframe
};

}  // namespace

GrownModel GrowModel(const frontend::FeatureTracks& tracks, const Camera& camera,
                     const IncrementalPipelineOptions& options,
                     const IncrementalMapper::InitialPair& pair, int attempt,
                     const std::vector<const IncrementalModel*>& earlier,
                     const SeamLinker& seam_linker, const MapperProgressCallback& progress,
                     std::vector<KeyframeDecision>* keyframes) {
  return ModelGrower(tracks, camera, options, attempt, earlier, seam_linker, progress, keyframes)
      .Run(pair);
}

}  // namespace comic::sfm
