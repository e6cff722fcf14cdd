#include "sfm/evaluation/sfm_report.h"

namespace comic::sfm {

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
  return report;
}

namespace {

nlohmann::json PointSetToJson(const PointSetStats& stats) {
  return {{"points", stats.num_points},
          {"observations", stats.num_observations},
          {"mean_track_length", stats.mean_track_length},
          {"mean_reprojection_error_px", stats.mean_reprojection_error_px}};
}

}  // namespace

nlohmann::json RunReportToJson(const SfmRunReport& report) {
  nlohmann::json json;
  json["detector"] = report.detector;
  json["status"] = report.status;
  json["frames"] = report.num_frames;
  json["registered_frames"] = report.stats.num_registered;
  json["registered_frame_indices"] = report.registered_frames;
  json["unregistered_frame_indices"] = report.unregistered_frames;
  json["initial_pair"] = {report.initial_frame1, report.initial_frame2};
  json["tracker"] = {{"tracks", report.num_tracks},
                     {"mean_track_length", report.mean_tracker_track_length}};
  json["points3D"] = PointSetToJson(report.stats.all);
  if (report.stats.boundary) json["boundary_points3D"] = PointSetToJson(*report.stats.boundary);
  if (report.stats.interior) json["interior_points3D"] = PointSetToJson(*report.stats.interior);
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
  json["time_s"] = {
      {"tracking", report.tracking_time_s},
      {"mapping", report.mapping_time_s},
      {"local_bundle_adjustment", report.local_ba_time_s},
      {"global_bundle_adjustment", report.global_ba_time_s},
      {"total", report.wall_time_s},
      {"cpu",
       {{"mapping", report.mapping_cpu_time_s},
        {"local_bundle_adjustment", report.local_ba_cpu_time_s},
        {"global_bundle_adjustment", report.global_ba_cpu_time_s}}},
      {"num_local_bundle_adjustments", report.num_local_ba},
      {"num_global_bundle_adjustments", report.num_global_ba},
      {"per_frame",
       report.num_frames > 0 ? report.wall_time_s / static_cast<double>(report.num_frames) : 0.0}};
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
  return json;
}

io::ReportTable MakeComparisonTable(const std::vector<SfmRunReport>& reports) {
  bool regions = false;
  for (const SfmRunReport& report : reports) regions = regions || report.stats.boundary.has_value();
  std::vector<std::string> columns = {
      "detector",     "status",           "registered", "frames",        "points",
      "track length", "reproj. error px", "ATE m",      "ATE % of path", "rot. error deg",
      "wall time s",  "tracking s",       "mapping s",  "local BA s",    "global BA s"};
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
