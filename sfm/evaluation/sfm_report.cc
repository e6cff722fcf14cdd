#include "sfm/evaluation/sfm_report.h"

#include <map>

#include "sfm/working_resolution.h"

namespace comic::sfm {

namespace {

nlohmann::json LoopClosureToJson(const LoopClosureSummary& summary) {
  const auto edges = [](const std::vector<LoopClosureEdge>& list) {
    nlohmann::json json = nlohmann::json::array();
    for (const LoopClosureEdge& loop : list) {
      json.push_back({{"query_frame", loop.query_frame},
                      {"match_frame", loop.match_frame},
                      {"similarity", loop.similarity},
                      {"matches", loop.num_matches},
                      {"inliers", loop.num_inliers},
                      {"scale", loop.scale},
                      {"path_length", loop.path_length},
                      {"loop_move", loop.loop_move},
                      {"correction", loop.correction}});
    }
    return json;
  };
  return {{"keyframes_searched", summary.num_nodes},
          {"candidates", summary.num_candidates},
          {"ruled_out_by_odometry", summary.num_ruled_out_by_odometry},
          {"verified", summary.num_verified},
          {"loops", edges(summary.loops)},
          {"rejected", edges(summary.rejected)},
          {"points_fused", summary.num_points_fused},
          {"max_correction", summary.max_correction},
          {"pose_graph_iterations", summary.pose_graph.iterations},
          {"cpu_time_s", summary.cpu_time_s}};
}

SfmModelReport ModelReport(int index, const Reconstruction& reconstruction,
                           const std::vector<int>& registered_frames,
                           const std::vector<int>& rotation_only_frames,
                           const std::vector<int>& interpolated_frames, int initial_frame1,
                           int initial_frame2, int num_merged_models) {
  SfmModelReport model;
  model.index = index;
  model.num_registered = registered_frames.size();
  model.num_rotation_only = rotation_only_frames.size();
  model.num_interpolated = interpolated_frames.size();
  model.num_points = reconstruction.NumPoints3D();
  if (!registered_frames.empty()) {
    model.first_frame = registered_frames.front();
    model.last_frame = registered_frames.back();
  }
  model.registered_frames = registered_frames;
  model.initial_frame1 = initial_frame1;
  model.initial_frame2 = initial_frame2;
  model.num_merged_models = num_merged_models;
  return model;
}

}  // namespace

SfmRunReport MakeRunReport(const SequenceReconstruction& run, const ReconstructionStats& stats,
                           const std::optional<TrajectoryEvaluation>& trajectory) {
  SfmRunReport report;
  report.detector = run.detector_name;
  report.status = ReconstructionStatusName(run.mapping.status);
  report.num_frames = run.tracks.NumFrames();
  report.num_tracks = run.tracks.tracks.size();
  size_t num_observations = 0;
  for (const frontend::Track& track : run.tracks.tracks) num_observations += track.Length();
  if (report.num_tracks > 0) {
    report.mean_tracker_track_length =
        static_cast<double>(num_observations) / static_cast<double>(report.num_tracks);
  }
  report.registered_frames = run.mapping.registered_frames;
  report.unregistered_frames = run.mapping.unregistered_frames;
  report.initial_frame1 = run.mapping.initial_frame1;
  report.initial_frame2 = run.mapping.initial_frame2;
  const IncrementalReconstruction& mapping = run.mapping;
  if (HasModel(mapping.status)) {
    report.models.push_back(ModelReport(0, mapping.reconstruction, mapping.registered_frames,
                                        mapping.rotation_only_frames, mapping.interpolated_frames,
                                        mapping.initial_frame1, mapping.initial_frame2, 0));
    for (size_t m = 0; m < mapping.other_models.size(); ++m) {
      const IncrementalModel& model = mapping.other_models[m];
      report.models.push_back(ModelReport(static_cast<int>(m) + 1, model.reconstruction,
                                          model.registered_frames, model.rotation_only_frames,
                                          model.interpolated_frames, model.initial_frame1,
                                          model.initial_frame2, model.num_merged_models));
    }
  }
  report.rotation_only_frames = mapping.rotation_only_frames;
  report.interpolated_frames = mapping.interpolated_frames;
  report.interpolated_poses = mapping.interpolated_poses;
  report.self_check = mapping.self_check;
  if (report.num_frames > 0) {
    report.registered_fraction = static_cast<double>(mapping.registered_frames.size()) /
                                 static_cast<double>(report.num_frames);
  }
  report.unregistered_ranges = mapping.unregistered_ranges;
  report.num_models_started = mapping.num_models;
  report.num_merges = mapping.num_merges;
  report.num_seam_links = mapping.num_seam_links;
  report.num_appearance_links = mapping.num_appearance_links;
  report.num_initial_pair_searches = mapping.num_initial_pair_searches;
  report.initial_pair_search_cpu_time_s = mapping.initial_pair_search_cpu_time_s;
  report.planar_pose_choices = mapping.planar_pose_choices;
  report.num_seam_matches = mapping.num_seam_matches;
  report.seam_matching_cpu_time_s = mapping.seam_matching_cpu_time_s;
  if (mapping.intrinsics_rejection.rejected) {
    const Camera& rejected = mapping.intrinsics_rejection.rejected_camera;
    const Camera in_input_pixels =
        run.input_size.height > 0
            ? ResizedCamera(rejected, run.input_size.width, run.input_size.height)
            : rejected;
    report.intrinsics_rejection = "self-calibration gave " + in_input_pixels.Describe() + ": " +
                                  mapping.intrinsics_rejection.reason +
                                  "; the camera was reset to its prior and held fixed";
  }
  report.working_scale = mapping.working_scale;
  report.stats = stats;
  report.trajectory = trajectory;
  report.tracking_time_s = run.tracking_time_s;
  report.mapping_time_s = run.mapping_time_s;
  report.wall_time_s = run.wall_time_s;
  report.local_ba_time_s = run.mapping.local_ba_time_s;
  report.global_ba_time_s = run.mapping.global_ba_time_s;
  report.mapping_cpu_time_s = run.mapping.cpu_time_s;
  report.local_ba_cpu_time_s = run.mapping.local_ba_cpu_time_s;
  report.global_ba_cpu_time_s = run.mapping.global_ba_cpu_time_s;
  report.num_local_ba = run.mapping.num_local_ba;
  report.num_global_ba = run.mapping.num_global_ba;
  report.image_set_matching = run.image_set_matching;
  report.keyframes_only = !mapping.keyframe_decisions.empty();
  for (size_t frame = 0; frame < mapping.keyframe_decisions.size(); ++frame) {
    const KeyframeDecision& decision = mapping.keyframe_decisions[frame];
    if (!decision.keyframe) continue;
    report.keyframes.push_back(static_cast<int>(frame));
    report.keyframe_reasons.push_back(KeyframeReasonName(decision.reason));
  }
  report.non_keyframes_lost = mapping.non_keyframes_lost;
  report.loop_closure = mapping.loop_closure;
  return report;
}

namespace {

nlohmann::json PlanarPoseChoicesJson(const std::vector<PlanarPoseChoice>& choices) {
  nlohmann::json json = nlohmann::json::array();
  for (const PlanarPoseChoice& choice : choices) {
    json.push_back({{"initial_pair", {choice.frame1, choice.frame2}},
                    {"points", choice.num_points},
                    {"third_frames", choice.num_third_frames},
                    {"median_error_essential_px", choice.median_error_essential_px},
                    {"median_error_alternative_px", choice.median_error_alternative_px},
                    {"votes_essential", choice.votes_essential},
                    {"votes_alternative", choice.votes_alternative},
                    {"kept", choice.kept_alternative ? "alternative" : "essential"}});
  }
  return json;
}

nlohmann::json PointSetToJson(const PointSetStats& stats) {
  return {{"points", stats.num_points},
          {"observations", stats.num_observations},
          {"mean_track_length", stats.mean_track_length},
          {"mean_reprojection_error_px", stats.mean_reprojection_error_px}};
}

// Counts and indices of the frames by how they got a pose, with the interpolated poses.
void AddFrameCounts(const SfmRunReport& report, nlohmann::json& json) {
  json["frames"] = report.num_frames;
  // Registered: a pose from observations (rotation-only ones included, counted apart). Interpolated
  // poses are guesses: never counted as registered, listed with their poses, not in any model.
  json["registered_frames"] = report.stats.num_registered;
  json["rotation_only_frames"] = report.rotation_only_frames.size();
  json["interpolated_frames"] = report.interpolated_frames.size();
  json["registered_fraction"] = report.registered_fraction;
  json["registered_frame_indices"] = report.registered_frames;
  json["unregistered_frame_indices"] = report.unregistered_frames;
  json["pose_sources"] = {{"rotation_only", report.rotation_only_frames},
                          {"interpolated", report.interpolated_frames}};
  json["interpolated_poses"] = nlohmann::json::array();
  for (size_t i = 0; i < report.interpolated_frames.size(); ++i) {
    const Rigid3d& pose = report.interpolated_poses[i];
    const Eigen::Quaterniond& q = pose.rotation;
    json["interpolated_poses"].push_back(
        {{"frame", report.interpolated_frames[i]},
         {"cam_from_world_qvec", {q.w(), q.x(), q.y(), q.z()}},
         {"cam_from_world_tvec",
          {pose.translation.x(), pose.translation.y(), pose.translation.z()}}});
  }
}

// The model self-check: its verdict and the frame pairs that disagree with the model.
void AddSelfCheck(const SfmRunReport& report, nlohmann::json& json) {
  const ModelSelfCheck& check = report.self_check;
  json["self_check"] = {{"pairs_checked", check.pairs_checked},
                        {"pairs_disagreeing", check.pairs_disagreeing},
                        {"median_error_ratio", check.median_error_ratio},
                        {"median_rotation_difference_deg", check.median_rotation_difference_deg},
                        {"max_rotation_difference_deg", check.max_rotation_difference_deg},
                        {"suspect", check.suspect},
                        {"reason", check.reason},
                        {"disagreeing_pairs", nlohmann::json::array()}};
  if (check.passed_over_model_frames > 0) {
    json["self_check"]["passed_over_model"] = {
        {"registered_frames", check.passed_over_model_frames},
        {"pairs_disagreeing", check.passed_over_pairs_disagreeing}};
  }
  for (const DisagreeingPair& pair : check.disagreeing) {
    json["self_check"]["disagreeing_pairs"].push_back(
        {{"frame1", pair.frame1},
         {"frame2", pair.frame2},
         {"error_ratio", pair.error_ratio},
         {"rotation_difference_deg", pair.rotation_difference_deg},
         {"inliers", pair.inliers},
         {"shared_tracks", pair.shared_tracks}});
  }
}

// Runs of frames left without a pose, with the check that stopped each.
void AddUnregisteredRanges(const SfmRunReport& report, nlohmann::json& json) {
  json["unregistered_ranges"] = nlohmann::json::array();
  for (const UnregisteredRange& range : report.unregistered_ranges) {
    json["unregistered_ranges"].push_back({{"first", range.first_frame},
                                           {"last", range.last_frame},
                                           {"stage", range.stage},
                                           {"check", range.check},
                                           {"value", range.value},
                                           {"needed", range.needed},
                                           {"message", range.message}});
    if (range.other_model >= 0) json["unregistered_ranges"].back()["model"] = range.other_model + 1;
  }
}

// One entry per model written under sparse/.
void AddModels(const SfmRunReport& report, nlohmann::json& json) {
  json["models"] = nlohmann::json::array();
  for (const SfmModelReport& model : report.models) {
    json["models"].push_back({{"index", model.index},
                              {"path", "sparse/" + std::to_string(model.index)},
                              {"registered_frames", model.num_registered},
                              {"rotation_only_frames", model.num_rotation_only},
                              {"interpolated_frames", model.num_interpolated},
                              {"points3D", model.num_points},
                              {"first_frame", model.first_frame},
                              {"last_frame", model.last_frame},
                              {"registered_frame_indices", model.registered_frames},
                              {"initial_pair", {model.initial_frame1, model.initial_frame2}},
                              {"merged_models", model.num_merged_models}});
  }
}

// What the mapper did (models, merges, links) and which frames were keyframes.
void AddMappingAndKeyframes(const SfmRunReport& report, nlohmann::json& json) {
  json["mapping"] = {{"models_started", report.num_models_started},
                     {"merges", report.num_merges},
                     {"seam_links", report.num_seam_links},
                     {"appearance_links", report.num_appearance_links},
                     {"initial_pair_searches", report.num_initial_pair_searches},
                     {"planar_pose_choices", PlanarPoseChoicesJson(report.planar_pose_choices)},
                     {"seam_matches", report.num_seam_matches},
                     {"working_scale", report.working_scale}};
  if (report.keyframes_only) {
    std::map<std::string, int> count_by_reason;
    for (const std::string& reason : report.keyframe_reasons) ++count_by_reason[reason];
    json["keyframes"] = {{"count", report.keyframes.size()},
                         {"frames", report.keyframes},
                         {"reasons", report.keyframe_reasons},
                         {"count_by_reason", count_by_reason},
                         {"non_keyframes_lost", report.non_keyframes_lost}};
  } else {
    json["keyframes"] = nullptr;
  }
}

// The trajectory against ground truth, or null without it.
void AddGroundTruth(const SfmRunReport& report, nlohmann::json& json) {
  if (report.trajectory) {
    const TrajectoryEvaluation& t = *report.trajectory;
    const Sim3d& sim3 = t.gt_from_estimated;
    json["ground_truth"] = {
        {"evaluated_frames", t.frames},
        {"ate_rmse", t.ate_rmse},
        {"ate_mean", t.ate_mean},
        {"ate_max", t.ate_max},
        {"path_length", t.path_length},
        {"ate_fraction_of_path", t.ate_fraction_of_path},
        {"end_to_start_error", t.end_to_start_error},
        {"mean_rotation_error_deg", t.mean_rotation_error_deg},
        {"mean_rotation_error_sim3_deg", t.mean_rotation_error_sim3_deg},
        {"position_errors", t.position_errors},
        {"rotation_errors_deg", t.rotation_errors_deg},
        {"gt_from_estimated",
         {{"scale", sim3.scale},
          {"rotation_wxyz",
           {sim3.rotation.w(), sim3.rotation.x(), sim3.rotation.y(), sim3.rotation.z()}},
          {"translation", {sim3.translation.x(), sim3.translation.y(), sim3.translation.z()}}}}};
  } else {
    json["ground_truth"] = nullptr;
  }
}

// Wall and CPU time per stage.
void AddTimes(const SfmRunReport& report, nlohmann::json& json) {
  json["time_s"] = {
      {"tracking", report.tracking_time_s},
      {"mapping", report.mapping_time_s},
      {"local_bundle_adjustment", report.local_ba_time_s},
      {"global_bundle_adjustment", report.global_ba_time_s},
      {"total", report.wall_time_s},
      {"cpu",
       {{"mapping", report.mapping_cpu_time_s},
        {"initial_pair_search", report.initial_pair_search_cpu_time_s},
        {"seam_matching", report.seam_matching_cpu_time_s},
        {"local_bundle_adjustment", report.local_ba_cpu_time_s},
        {"global_bundle_adjustment", report.global_ba_cpu_time_s}}},
      {"num_local_bundle_adjustments", report.num_local_ba},
      {"num_global_bundle_adjustments", report.num_global_ba},
      {"per_frame",
       report.num_frames > 0 ? report.wall_time_s / static_cast<double>(report.num_frames) : 0.0}};
}

// The unordered image-set matching summary, when the run matched an image set.
void AddImageSetMatching(const SfmRunReport& report, nlohmann::json& json) {
  if (report.image_set_matching) {
    const frontend::ImageSetMatchingSummary& m = *report.image_set_matching;
    json["image_set_matching"] = {{"frames", m.num_frames},
                                  {"features", m.num_features},
                                  {"pairs", m.num_pairs},
                                  {"verified_pairs", m.num_verified_pairs},
                                  {"raw_matches", m.num_raw_matches},
                                  {"verified_matches", m.num_verified_matches},
                                  {"detection_cpu_s", m.detection_cpu_s},
                                  {"description_cpu_s", m.description_cpu_s},
                                  {"matching_cpu_s", m.matching_cpu_s},
                                  {"verification_cpu_s", m.verification_cpu_s},
                                  {"track_building_cpu_s", m.track_building_cpu_s}};
  }
}

}  // namespace

std::string DescribeUnregisteredRanges(const std::vector<UnregisteredRange>& ranges) {
  std::string text;
  for (const UnregisteredRange& range : ranges) {
    if (!text.empty()) text += "; ";
    text += std::to_string(range.first_frame);
    if (range.last_frame > range.first_frame) text += "-" + std::to_string(range.last_frame);
    text += " " + range.stage + "/" + range.check;
    if (range.check == "other_model") text += " " + std::to_string(range.other_model + 1);
  }
  return text;
}

nlohmann::json RunReportToJson(const SfmRunReport& report) {
  nlohmann::json json;
  json["detector"] = report.detector;
  json["status"] = report.status;
  AddFrameCounts(report, json);
  AddSelfCheck(report, json);
  AddUnregisteredRanges(report, json);
  AddModels(report, json);
  AddMappingAndKeyframes(report, json);
  json["loop_closure"] =
      report.loop_closure ? LoopClosureToJson(*report.loop_closure) : nlohmann::json(nullptr);
  json["intrinsics_rejection"] = report.intrinsics_rejection.empty()
                                     ? nlohmann::json(nullptr)
                                     : nlohmann::json(report.intrinsics_rejection);
  json["initial_pair"] = {report.initial_frame1, report.initial_frame2};
  json["tracker"] = {{"tracks", report.num_tracks},
                     {"mean_track_length", report.mean_tracker_track_length}};
  json["points3D"] = PointSetToJson(report.stats.all);
  if (report.stats.boundary) json["boundary_points3D"] = PointSetToJson(*report.stats.boundary);
  if (report.stats.interior) json["interior_points3D"] = PointSetToJson(*report.stats.interior);
  AddGroundTruth(report, json);
  AddTimes(report, json);
  AddImageSetMatching(report, json);
  return json;
}

io::ReportTable MakeComparisonTable(const std::vector<SfmRunReport>& reports) {
  bool regions = false;
  for (const SfmRunReport& report : reports) regions = regions || report.stats.boundary.has_value();
  std::vector<std::string> columns = {"detector",
                                      "status",
                                      "registered",
                                      "frames",
                                      "models",
                                      "points",
                                      "track length",
                                      "reproj. error px",
                                      "ATE m",
                                      "ATE % of path",
                                      "rot. error deg",
                                      "wall time s",
                                      "tracking s",
                                      "mapping s",
                                      "local BA s",
                                      "global BA s",
                                      "unregistered (stage/check)"};
  if (regions) {
    for (const char* column : {"boundary points", "boundary track length", "boundary reproj. px",
                               "interior points", "interior reproj. px"}) {
      columns.push_back(column);
    }
  }
  io::ReportTable table(columns);
  table.SetPrecision("track length", 2);
  table.SetPrecision("reproj. error px", 3);
  table.SetPrecision("ATE m", 3);
  table.SetPrecision("ATE % of path", 3);
  table.SetPrecision("rot. error deg", 3);
  // Per stage, to see where the time goes: the mapper's bundle adjustments are part of mapping.
  for (const char* column :
       {"wall time s", "tracking s", "mapping s", "local BA s", "global BA s"}) {
    table.SetPrecision(column, 1);
  }
  if (regions) {
    table.SetPrecision("boundary track length", 2);
    table.SetPrecision("boundary reproj. px", 3);
    table.SetPrecision("interior reproj. px", 3);
  }
  for (const SfmRunReport& report : reports) {
    const bool has_model = report.stats.num_registered > 0;
    const auto number = [&](double value) -> io::ReportTable::Cell {
      if (!has_model) return std::monostate{};
      return value;
    };
    std::vector<io::ReportTable::Cell> row = {report.detector,
                                              report.status,
                                              static_cast<int64_t>(report.stats.num_registered),
                                              static_cast<int64_t>(report.num_frames),
                                              static_cast<int64_t>(report.models.size()),
                                              static_cast<int64_t>(report.stats.all.num_points),
                                              number(report.stats.all.mean_track_length),
                                              number(report.stats.all.mean_reprojection_error_px)};
    if (report.trajectory) {
      row.push_back(report.trajectory->ate_rmse);
      row.push_back(100.0 * report.trajectory->ate_fraction_of_path);
      row.push_back(report.trajectory->mean_rotation_error_deg);
    } else {
      row.insert(row.end(), 3, std::monostate{});
    }
    row.push_back(report.wall_time_s);
    row.push_back(report.tracking_time_s);
    row.push_back(report.mapping_time_s);
    row.push_back(report.local_ba_time_s);
    row.push_back(report.global_ba_time_s);
    row.push_back(DescribeUnregisteredRanges(report.unregistered_ranges));
    if (regions) {
      if (report.stats.boundary && report.stats.interior) {
        row.push_back(static_cast<int64_t>(report.stats.boundary->num_points));
        row.push_back(number(report.stats.boundary->mean_track_length));
        row.push_back(number(report.stats.boundary->mean_reprojection_error_px));
        row.push_back(static_cast<int64_t>(report.stats.interior->num_points));
        row.push_back(number(report.stats.interior->mean_reprojection_error_px));
      } else {
        row.insert(row.end(), 5, std::monostate{});
      }
    }
    table.AddRow(std::move(row));
  }
  return table;
}

}  // namespace comic::sfm
