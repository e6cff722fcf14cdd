#include "sfm/incremental_pipeline.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>

#include "io/core/error.h"
#include "sfm/model_growth.h"
#include "sfm/planar_pose_ambiguity.h"
#include "sfm/pose_gap_filling.h"
#include "sfm/unregistered_ranges.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

namespace {

// The models grown so far, and what the run learnt about failures to start one.
struct ModelSet {
  std::vector<GrownModel> models;  // standing models, in the order they were started
  ReconstructionStatus first_failure = ReconstructionStatus::kNoInitialPair;
  size_t first_failure_num_points = 0;
  int first_failure_frame1 = -1;
  int first_failure_frame2 = -1;
  IncrementalMapper::InitialPairSearch first_search;
  int num_attempts = 0;
  bool no_initial_pair_left = false;  // the growth stopped for want of an initial pair
  int num_merges = 0;
  int num_seam_links = 0;
  int num_appearance_links = 0;
  int num_initial_pair_searches = 0;
  double initial_pair_search_cpu_time_s = 0.0;
  std::vector<PlanarPoseChoice> planar_pose_choices;
  int num_seam_matches = 0;
  double seam_matching_cpu_time_s = 0.0;
  BundleAdjustmentTally ba;
  // keyframes_only: the decision per frame, as the models changed it.
  std::vector<KeyframeDecision> keyframes;
};

// Links between `current` and `earlier` from matching the frames facing each other across the
// gap between them: the last seam_num_frames registered frames of the earlier one in the clip
// with the first seam_num_frames of the later one, when at most seam_max_frame_gap frames apart
// and no other standing model holds a frame between them (so a clip of many fragments costs
// matches in proportion to its fragments). FrameMatcher results are cached by frame pair.
class SeamLinking {
 public:
  SeamLinking(const FrameMatcher& matcher, const IncrementalPipelineOptions& options,
              ModelSet* models)
      : matcher_(matcher), options_(options), models_(*models) {}

  std::vector<IncrementalMapper::FeatureLink> operator()(const Reconstruction& current,
                                                         const Reconstruction& earlier) {
    std::vector<IncrementalMapper::FeatureLink> links;
    const std::vector<int> frames = Frames(current), other_frames = Frames(earlier);
    if (frames.empty() || other_frames.empty()) return links;
    // The two ends that face each other.
    const bool current_first = frames.back() < other_frames.front();
    if (!current_first && other_frames.back() >= frames.front()) return links;  // spans overlap
    const int n = options_.seam_num_frames;
    const std::vector<int> ends = current_first ? Last(frames, n) : First(frames, n);
    const std::vector<int> other_ends =
        current_first ? First(other_frames, n) : Last(other_frames, n);
    const int low = current_first ? frames.back() : other_frames.back();
    const int high = current_first ? other_frames.front() : frames.front();
    if (high - low > options_.seam_max_frame_gap ||
        OtherModelBetween(current, earlier, low, high)) {
      return links;
    }
    for (int frame : ends) {
      for (int other_frame : other_ends) {
        const Image& image = current.image(IncrementalMapper::ImageIdOfFrame(frame));
        const Image& other_image = earlier.image(IncrementalMapper::ImageIdOfFrame(other_frame));
        for (const auto& [feature, other_feature] : Match(frame, other_frame)) {
          if (feature < 0 || other_feature < 0 ||
              feature >= static_cast<int>(image.points2D.size()) ||
              other_feature >= static_cast<int>(other_image.points2D.size()) ||
              !image.points2D[feature].HasPoint3D() ||
              !other_image.points2D[other_feature].HasPoint3D()) {
            continue;
          }
          links.push_back({image.image_id, static_cast<point2D_t>(feature), other_image.image_id,
                           static_cast<point2D_t>(other_feature)});
        }
      }
    }
    return links;
  }

 private:
  static std::vector<int> Frames(const Reconstruction& model) {
    std::vector<int> frames;
    for (image_t id : model.RegisteredImageIds()) {
      frames.push_back(IncrementalMapper::FrameOfImageId(id));
    }
    return frames;
  }
  static std::vector<int> First(const std::vector<int>& frames, int n) {
    return {frames.begin(), frames.begin() + std::min<long>(n, static_cast<long>(frames.size()))};
  }
  static std::vector<int> Last(const std::vector<int>& frames, int n) {
    return {frames.end() - std::min<long>(n, static_cast<long>(frames.size())), frames.end()};
  }

  bool OtherModelBetween(const Reconstruction& a, const Reconstruction& b, int low,
                         int high) const {
    for (const GrownModel& model : models_.models) {
      const Reconstruction& other = model.model.reconstruction;
      if (&other == &a || &other == &b) continue;
      for (int frame = low + 1; frame < high; ++frame) {
        const image_t id = IncrementalMapper::ImageIdOfFrame(frame);
        if (other.ExistsImage(id) && other.image(id).registered) return true;
      }
    }
    return false;
  }

  const std::vector<std::pair<int, int>>& Match(int frame1, int frame2) {
    const auto key = std::make_pair(frame1, frame2);
    auto it = cache_.find(key);
    if (it == cache_.end()) {
      const double cpu_start = ProcessCpuSeconds();
      it = cache_.emplace(key, matcher_(frame1, frame2)).first;
      models_.seam_matching_cpu_time_s += ProcessCpuSeconds() - cpu_start;
      ++models_.num_seam_matches;
    }
    return it->second;
  }

  const FrameMatcher& matcher_;
  const IncrementalPipelineOptions& options_;
  ModelSet& models_;
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> cache_;
};

// Frames no initial pair may use: those of the standing models and of the pairs tried.
std::set<image_t> ExcludedFrames(const ModelSet& set, const std::set<image_t>& tried) {
  std::set<image_t> excluded = tried;
  for (const GrownModel& model : set.models) {
    for (int frame : model.model.registered_frames) {
      excluded.insert(IncrementalMapper::ImageIdOfFrame(frame));
    }
  }
  return excluded;
}

// A near-planar initial pair allows two poses (sfm/planar_pose_ambiguity.h), and a model grown
// from the wrong one stays self-consistent. The clip's other frames choose: the pose whose
// two-view points they see nearer their reprojections starts the model.
IncrementalMapper::InitialPair ChoosePlanarPose(const frontend::FeatureTracks& tracks,
                                                const Camera& camera,
                                                const IncrementalPipelineOptions& options,
                                                const IncrementalMapper::InitialPair& pair,
                                                ModelSet* set) {
  const int frame1 = IncrementalMapper::FrameOfImageId(pair.image_id1);
  const int frame2 = IncrementalMapper::FrameOfImageId(pair.image_id2);
  const ThirdViewComparison comparison =
      CompareByThirdViews(tracks, camera, frame1, frame2, pair.track_ids, pair.geometry,
                          *pair.planar_alternative, options.planar_third_views);
  PlanarPoseChoice choice;
  choice.frame1 = frame1;
  choice.frame2 = frame2;
  choice.num_points = comparison.num_points;
  choice.num_third_frames = static_cast<int>(comparison.frames.size());
  choice.median_error_essential_px = comparison.median_error_first_px;
  choice.median_error_alternative_px = comparison.median_error_second_px;
  choice.votes_essential = comparison.votes_first;
  choice.votes_alternative = comparison.votes_second;
  choice.kept_alternative = comparison.prefers_second;
  set->planar_pose_choices.push_back(choice);
  if (!comparison.prefers_second) return pair;
  IncrementalMapper::InitialPair other = pair;
  other.geometry = *pair.planar_alternative;
  other.planar_alternative.reset();
  return other;
}

// Grows models one after another (COLMAP's IncrementalMapperController): each from the best
// initial pair among the frames no standing model holds, until every frame is in a model, no
// pair qualifies or max_num_models were started. A model that merges earlier ones replaces them.
ModelSet GrowModels(const frontend::FeatureTracks& tracks, const Camera& camera,
                    const IncrementalPipelineOptions& options,
                    const MapperProgressCallback& progress, const FrameMatcher& frame_matcher) {
  ModelSet set;
  if (options.keyframes_only) set.keyframes = SelectKeyframes(tracks, options.keyframes);
  // The initial pairs are searched once and reused; only when every remaining candidate touches
  // an excluded frame is the search repeated without those frames. The search's mapper (every
  // frame's features again) lives only during a search: kept, it doubled the mapper's memory
  // on long video (docs/long_video.md); the search depends on nothing but the tracks.
  IncrementalMapper::Options search_options = options.mapper;
  // A planar alternative is only worth its decomposition and triangulations when it is compared.
  search_options.init_find_planar_alternative &= options.choose_planar_pose;
  const auto search = [&](const std::set<image_t>& excluded,
                          IncrementalMapper::InitialPairSearch* seen) {
    const double cpu_start = ProcessCpuSeconds();
    std::vector<IncrementalMapper::InitialPair> pairs =
        IncrementalMapper(tracks, camera, search_options).FindInitialPairs(excluded, seen);
    set.initial_pair_search_cpu_time_s += ProcessCpuSeconds() - cpu_start;
    ++set.num_initial_pair_searches;
    return pairs;
  };
  std::vector<IncrementalMapper::InitialPair> candidates = search({}, &set.first_search);
  if (candidates.empty() && options.relax_initial_pair) {
    // COLMAP's relaxation; the diagnosis of a failure stays that of the strict search.
    search_options.init_min_num_matches = std::max(5, search_options.init_min_num_matches / 2);
    search_options.init_min_num_inliers = std::max(5, search_options.init_min_num_inliers / 2);
    candidates = search({}, nullptr);
    if (candidates.empty()) {
      // Still nothing: a flat scene seen with parallax may start (COLMAP's mapper would).
      search_options.init_accept_planar = true;
      candidates = search({}, nullptr);
    }
  }
  SeamLinking seam_linking(frame_matcher, options, &set);
  SeamLinker linker;
  if (frame_matcher || options.close_loops) {
    linker = [&](const Reconstruction& current, const Reconstruction& earlier) {
      std::vector<IncrementalMapper::FeatureLink> links;
      if (frame_matcher) links = seam_linking(current, earlier);
      // With loop closure, a model the camera came back to after the tracks broke (no seam).
      if (links.empty() && options.close_loops) {
        links = LinkModelsByAppearance(tracks, options.loop_closure, current, earlier).links;
        set.num_appearance_links += !links.empty();
      }
      return links;
    };
  }
  std::set<image_t> tried;
  for (int attempt = 0; attempt < options.max_num_models; ++attempt) {
    const std::set<image_t> excluded = ExcludedFrames(set, tried);
    if (excluded.size() >= tracks.NumFrames()) break;
    const auto usable = [&](const IncrementalMapper::InitialPair& pair) {
      return !excluded.count(pair.image_id1) && !excluded.count(pair.image_id2);
    };
    auto it = std::find_if(candidates.begin(), candidates.end(), usable);
    if (it == candidates.end() && attempt > 0) {
      candidates = search(excluded, nullptr);
      it = candidates.begin();
    }
    if (it == candidates.end()) {
      set.no_initial_pair_left = true;
      break;
    }
    const IncrementalMapper::InitialPair pair = *it;
    tried.insert(pair.image_id1);
    tried.insert(pair.image_id2);
    std::vector<const IncrementalModel*> earlier;
    for (const GrownModel& model : set.models) earlier.push_back(&model.model);
    IncrementalMapper::InitialPair start = pair;
    if (pair.planar_alternative && options.choose_planar_pose) {
      start = ChoosePlanarPose(tracks, camera, options, pair, &set);
    }
    GrownModel grown = GrowModel(tracks, camera, options, start, attempt, earlier, linker, progress,
                                 options.keyframes_only ? &set.keyframes : nullptr);
    ++set.num_attempts;
    set.ba.Add(grown.ba);
    if (grown.status != ReconstructionStatus::kSuccess) {
      if (set.models.empty() && set.first_failure_frame1 < 0) {
        set.first_failure = grown.status;
        set.first_failure_num_points = grown.initial_pair_num_points;
        set.first_failure_frame1 = grown.model.initial_frame1;
        set.first_failure_frame2 = grown.model.initial_frame2;
      }
      continue;
    }
    set.num_merges += static_cast<int>(grown.merged.size());
    set.num_seam_links += grown.num_seam_links;
    std::vector<size_t> merged = grown.merged;
    std::sort(merged.rbegin(), merged.rend());
    for (size_t e : merged) set.models.erase(set.models.begin() + static_cast<long>(e));
    set.models.push_back(std::move(grown));
  }
  return set;
}

// Poses for the frames in the models' gaps (sfm/pose_gap_filling.h), the largest model first; a
// frame another model registered, or interpolated, is left to that model. Frames posed by
// rotation join the model's registered frames; interpolated ones stay beside it.
void FillGaps(const frontend::FeatureTracks& tracks, const IncrementalPipelineOptions& options,
              std::vector<GrownModel*>* models) {
  std::vector<char> fillable(tracks.NumFrames(), 1);
  for (const GrownModel* model : *models) {
    for (int frame : model->model.registered_frames) fillable[frame] = 0;
  }
  PoseGapFillingOptions gap_options;
  gap_options.max_interpolated_gap = options.max_interpolated_gap;
  for (GrownModel* grown : *models) {
    IncrementalModel& model = grown->model;
    const PoseGapFilling filled =
        FillPoseGaps(tracks, fillable, gap_options, &model.reconstruction);
    model.rotation_only_frames = filled.rotation_only_frames;
    model.interpolated_frames = filled.interpolated_frames;
    model.interpolated_poses = filled.interpolated_poses;
    for (int frame : filled.rotation_only_frames) {
      fillable[frame] = 0;
      model.registered_frames.push_back(frame);
    }
    for (int frame : filled.interpolated_frames) fillable[frame] = 0;
    std::sort(model.registered_frames.begin(), model.registered_frames.end());
  }
}

// The result from the grown models, largest first (frames registered from observations; ties by
// the order they were started), unless the self-check prefers a nearly as large one.
void Assemble(const frontend::FeatureTracks& tracks, const IncrementalPipelineOptions& options,
              std::vector<GrownModel*> models, bool no_initial_pair_left,
              IncrementalReconstruction* result) {
  std::stable_sort(models.begin(), models.end(), [](const GrownModel* a, const GrownModel* b) {
    return a->model.NumObservedFrames() > b->model.NumObservedFrames();
  });
  if (options.self_check) {
    std::vector<const Reconstruction*> reconstructions;
    for (const GrownModel* model : models) reconstructions.push_back(&model->model.reconstruction);
    KeptModelChoice kept = ChooseKeptModel(reconstructions, tracks, options.self_check_options,
                                           options.self_check_yield_fraction);
    std::rotate(models.begin(), models.begin() + static_cast<long>(kept.index),
                models.begin() + static_cast<long>(kept.index) + 1);
    result->self_check = std::move(kept.check);
  }
  GrownModel& largest = *models.front();
  for (size_t m = 1; m < models.size(); ++m) {
    result->other_models.push_back(std::move(models[m]->model));
  }
  IncrementalModel& model = largest.model;
  result->reconstruction = std::move(model.reconstruction);
  result->registered_frames = model.registered_frames;
  result->rotation_only_frames = model.rotation_only_frames;
  result->interpolated_frames = model.interpolated_frames;
  result->interpolated_poses = model.interpolated_poses;
  result->initial_frame1 = model.initial_frame1;
  result->initial_frame2 = model.initial_frame2;
  result->initial_pair_num_points = largest.initial_pair_num_points;
  result->final_ba = largest.final_ba;
  result->non_keyframes_lost = largest.non_keyframes_lost;
  if (options.close_loops) result->loop_closure = largest.loop_closure;
  result->focal_assessed = largest.focal_assessed;
  result->focal_observability = largest.focal_observability;
  result->intrinsics_refined = largest.intrinsics_refined;
  result->intrinsics_rejection = largest.intrinsics_rejection;
  for (size_t frame = 0; frame < tracks.NumFrames(); ++frame) {
    if (!std::binary_search(result->registered_frames.begin(), result->registered_frames.end(),
                            static_cast<int>(frame))) {
      result->unregistered_frames.push_back(static_cast<int>(frame));
    }
  }
  result->unregistered_ranges = ExplainUnregisteredFrames(
      tracks, result->reconstruction, result->other_models, largest.best_failed_pose_inliers,
      options.mapper.absolute_pose, no_initial_pair_left);
  const double observed = static_cast<double>(result->registered_frames.size());
  result->status =
      observed >= options.success_min_registered_fraction * static_cast<double>(tracks.NumFrames())
          ? ReconstructionStatus::kSuccess
          : ReconstructionStatus::kPartial;
  if (result->self_check.suspect) result->status = ReconstructionStatus::kSuspect;
}

// Every model back in the input's pixels (the work ran at `scale` of them).
void ToInputPixels(double scale, const Camera& input, IncrementalReconstruction* result) {
  if (scale == 1.0) return;
  ScaleReconstruction(1.0 / scale, input.width, input.height, &result->reconstruction);
  for (IncrementalModel& model : result->other_models) {
    ScaleReconstruction(1.0 / scale, input.width, input.height, &model.reconstruction);
  }
  if (result->intrinsics_rejection.rejected) {
    Camera& rejected = result->intrinsics_rejection.rejected_camera;
    rejected = rejected.Scaled(1.0 / scale);
    rejected.width = input.width;
    rejected.height = input.height;
  }
}

}  // namespace

IncrementalReconstruction ReconstructIncrementally(const frontend::FeatureTracks& tracks,
                                                   const Camera& camera,
                                                   const IncrementalPipelineOptions& options,
                                                   const MapperProgressCallback& progress,
                                                   const FrameMatcher& frame_matcher) {
  options.Check();
  tracks.Check();
  camera.Check();
  COMIC_CHECK(!options.close_loops || tracks.HasDescriptors() || tracks.NumFrames() == 0,
              kInvalidArgument,
              "loop closure needs tracks with descriptors (frontend::DescribeTrackedFeatures)");
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ProcessCpuSeconds();
  IncrementalReconstruction result;
  const auto finish = [&]() {
    result.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.cpu_time_s = ProcessCpuSeconds() - cpu_start;
    return std::move(result);
  };
  for (size_t frame = 0; frame < tracks.NumFrames(); ++frame) {
    result.unregistered_frames.push_back(static_cast<int>(frame));
  }
  if (tracks.NumFrames() < 2) return finish();

  // Stage 1: the working resolution.
  result.working_scale = WorkingScale(camera.width, camera.height, options.max_working_image_size);
  frontend::FeatureTracks scaled_tracks;
  Camera working_camera = camera;
  if (result.working_scale != 1.0) {
    scaled_tracks = ScaleTracks(tracks, result.working_scale);
    working_camera = camera.Scaled(result.working_scale);
  }
  const frontend::FeatureTracks& working_tracks =
      result.working_scale != 1.0 ? scaled_tracks : tracks;

  // Stage 2: the models.
  ModelSet set = GrowModels(working_tracks, working_camera, options, progress, frame_matcher);
  result.initial_pair_search = set.first_search;
  result.num_models = set.num_attempts;
  result.num_merges = set.num_merges;
  result.num_seam_links = set.num_seam_links;
  result.num_appearance_links = set.num_appearance_links;
  result.num_initial_pair_searches = set.num_initial_pair_searches;
  result.planar_pose_choices = set.planar_pose_choices;
  result.initial_pair_search_cpu_time_s = set.initial_pair_search_cpu_time_s;
  result.num_seam_matches = set.num_seam_matches;
  result.seam_matching_cpu_time_s = set.seam_matching_cpu_time_s;
  result.num_local_ba = set.ba.num_local_ba;
  result.num_global_ba = set.ba.num_global_ba;
  result.num_final_ba_windows = set.ba.num_final_ba_windows;
  result.num_local_ba_iterations = set.ba.num_local_ba_iterations;
  result.num_global_ba_iterations = set.ba.num_global_ba_iterations;
  result.local_ba_time_s = set.ba.local_ba_time_s;
  result.global_ba_time_s = set.ba.global_ba_time_s;
  result.local_ba_cpu_time_s = set.ba.local_ba_cpu_time_s;
  result.global_ba_cpu_time_s = set.ba.global_ba_cpu_time_s;
  result.keyframe_decisions = std::move(set.keyframes);
  if (set.models.empty()) {
    result.status = set.first_failure;
    result.initial_pair_num_points = set.first_failure_num_points;
    result.initial_frame1 = set.first_failure_frame1;
    result.initial_frame2 = set.first_failure_frame2;
    return finish();
  }
  std::vector<GrownModel*> models;
  for (GrownModel& model : set.models) models.push_back(&model);
  std::stable_sort(models.begin(), models.end(), [](const GrownModel* a, const GrownModel* b) {
    return a->model.registered_frames.size() > b->model.registered_frames.size();
  });

  // Stage 3: poses through the gaps; stage 4: the largest model first, the status, the reasons.
  if (options.fill_pose_gaps) FillGaps(working_tracks, options, &models);
  result.unregistered_frames.clear();
  Assemble(working_tracks, options, models, set.no_initial_pair_left, &result);
  ToInputPixels(result.working_scale, camera, &result);
  return finish();
}

}  // namespace comic::sfm
