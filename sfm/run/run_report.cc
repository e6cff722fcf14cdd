#include "sfm/run/run_report.h"

#include <type_traits>
#include <variant>

#include "frontend/matching/pairing.h"
#include "io/core/content_hash.h"
#include "sfm/focal_observability.h"
#include "sfm/run/run_option_table.h"
#include "sfm/run/run_outputs.h"
#include "sfm/run/tracker_option_table.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

namespace {

nlohmann::json CameraToJson(const Camera& camera) {
  return {{"model", CameraModelName(camera.model)},
          {"model_id", static_cast<int>(camera.model)},
          {"width", camera.width},
          {"height", camera.height},
          {"params", camera.Params()},
          {"params_info", CameraModelParamsInfo(camera.model)},
          {"pixel_convention", "OpenCV (top-left pixel centre at 0,0)"}};
}

nlohmann::json PairingToJson(const frontend::PairingChoice& pairing) {
  nlohmann::json matching = {{"requested", frontend::PairingName(pairing.requested)},
                             {"chosen", frontend::PairingName(pairing.chosen)},
                             {"reason", pairing.reason}};
  if (pairing.measured) {
    matching["looks_like_video"] = pairing.looks_like_video;
    matching["consecutive_similarity_median"] = pairing.consecutive_similarity_median;
    matching["consecutive_similarity_p10"] = pairing.consecutive_similarity_p10;
    matching["other_similarity_median"] = pairing.other_similarity_median;
    matching["gain"] = pairing.gain;
    matching["neighbour_fraction"] = pairing.neighbour_fraction;
  }
  return matching;
}

nlohmann::json DiagnosisToJson(const ReconstructionDiagnosis& d) {
  return {{"stage", d.stage},
          {"check", d.check},
          {"value", d.value},
          {"needed", d.needed},
          {"frame1", d.frame1},
          {"frame2", d.frame2},
          {"rotation_only", d.rotation_only},
          {"message", d.message},
          {"suggestion", d.suggestion}};
}

nlohmann::json RotationOnlyPathToJson(const RotationOnlyPath& path, size_t num_frames) {
  double mean_rms = 0.0;
  for (double rms : path.rms_error_px) mean_rms += rms / path.rms_error_px.size();
  return {{"registered_frames", path.num_registered},
          {"frames", num_frames},
          {"mean_rms_error_px", mean_rms}};
}

}  // namespace

nlohmann::json CameraReportJson(const SequenceReconstruction& run, const RunInputs& inputs) {
  const IncrementalReconstruction& mapping = run.mapping;
  nlohmann::json json = {{"source", inputs.camera.source},
                         {"prior_from", inputs.camera.origin},
                         {"prior", CameraToJson(inputs.camera.camera)},
                         {"refined", mapping.intrinsics_refined}};
  const Reconstruction& reconstruction = mapping.reconstruction;
  const Camera& camera = reconstruction.cameras().empty()
                             ? inputs.camera.camera
                             : reconstruction.cameras().begin()->second;
  // In the input's pixels, as the models are written (the prior is at the frames' size,
  // options.frame_size).
  const Camera final_camera = ResizedCamera(camera, run.input_size.width, run.input_size.height);
  json["final"] = CameraToJson(final_camera);
  json["focal_length_px"] = final_camera.fx;
  if (mapping.intrinsics_rejection.rejected) {
    json["rejected"] = CameraToJson(ResizedCamera(mapping.intrinsics_rejection.rejected_camera,
                                                  run.input_size.width, run.input_size.height));
    json["rejection_reason"] = mapping.intrinsics_rejection.reason;
  }
  if (mapping.focal_assessed) {
    json["focal_observable"] = mapping.focal_observability.observable;
    json["max_viewing_angle_deg"] = mapping.focal_observability.max_viewing_angle_deg;
    json["focal_observability_rule"] =
        "observable when two registered images' optical axes are >= " +
        std::to_string(FocalObservabilityOptions().min_viewing_angle_deg) +
        " deg apart (sfm/focal_observability.h); otherwise the prior focal is kept";
  } else {
    json["focal_observable"] = nullptr;  // the focal was not to be refined
  }
  return json;
}

nlohmann::json RunOptionsToJson(const ReconstructionRunOptions& options, const RunInputs& inputs) {
  const Camera& c = inputs.camera.camera;
  const frontend::TrackerOptions& tracker = inputs.tracker;
  const io::ImageSequenceOptions& sequence = options.sequence;
  // An image set matched by descriptors: no frame order for the mapper to use.
  const bool unordered = inputs.image_set.has_value() && !frontend::IsVideo(inputs.pairing);
  nlohmann::json json = {
      {"frames", options.frames},
      {"first", sequence.first_frame},
      {"last", sequence.last_frame},
      {"stride", sequence.stride},
      {"resize_height", sequence.resize_height},
      {"frame_size", {inputs.sequence->FrameSize().width, inputs.sequence->FrameSize().height}},
      {"intrinsics",
       {{"source", inputs.camera.source},
        {"model", CameraModelName(c.model)},
        {"params", c.Params()},
        {"fx", c.fx},
        {"fy", c.fy},
        {"cx", c.cx},
        {"cy", c.cy},
        {"pixel_convention", "OpenCV (top-left pixel centre at 0,0)"}}},
      {"gt", options.gt.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.gt)},
      {"gt_format", io::GroundTruthFormatName(inputs.gt_format)},
      {"scale_levels", options.detector_options.scale_space.num_levels},
      {"matching", PairingToJson(inputs.pairing)},
      {"matcher", inputs.image_set ? "descriptors" : "patches"},
      {"camera_model", options.camera.camera_model},
      {"retriangulate", !options.no_retriangulate},
      {"planar_pose_choice", !options.no_planar_pose_choice},
      {"two_view_tracks", options.two_view_tracks || tracker.match_window > 1 || unordered},
      {"init_angle_deg", options.init_angle},
      {"keyframes", options.keyframes && !unordered},
      {"loop_closure", options.loop_closure && !unordered},
      {"init_max_gap",
       unordered ? nlohmann::json("all frames (image set)") : nlohmann::json(options.init_max_gap)},
      {"input_size",
       {inputs.sequence->SourceFrameSize().width, inputs.sequence->SourceFrameSize().height}},
      {"threads", options.threads},
      {"regions", options.regions},
      {"masks", options.masks},
      {"mask_drops_nonzero", options.mask_drops_nonzero},
      {"boundary_band_px", options.boundary_band}};
  // The tracker's options as the run resolved them for its pairing, under their keywords.
  for (const TrackerOption& entry : TrackerOptionTable()) {
    frontend::TrackerOptions resolved = tracker;
    std::visit(
        [&](auto field) {
          if constexpr (std::is_same_v<decltype(field), TrackerOption::Named>) {
            json[entry.keyword] = field.get(resolved);
          } else {
            json[entry.keyword] = field(resolved);
          }
        },
        entry.field);
  }
  // The table's options reported as given, under their keywords.
  ReconstructionRunOptions given = options;
  for (const RunOption& entry : RunOptionTable()) {
    if (!entry.reported_as_given) continue;
    std::visit([&](auto field) { json[entry.keyword] = field(given); }, entry.field);
  }
  return json;
}

nlohmann::json DetectorReportJson(const DetectorRun& run, const ReconstructionRunOptions& options,
                                  const RunInputs& inputs, bool writes_outputs) {
  nlohmann::json json = RunReportToJson(run.report);
  json["options"] = RunOptionsToJson(options, inputs);
  if (!run.matcher.empty()) json["options"]["matcher"] = run.matcher;
  json["options"]["verify_min_gap"] = run.verify_min_gap;
  json["matcher_attempts"] = run.matcher_attempts;
  json["camera"] = CameraReportJson(run.run, inputs);
  if (run.diagnosis.failed) json["diagnosis"] = DiagnosisToJson(run.diagnosis);
  const frontend::TrackBuildSummary& building = run.run.track_building;
  json["track_building"] = {{"matches", building.num_matches},
                            {"tracks", run.run.tracks.tracks.size()},
                            {"conflicting_components_dropped", building.num_conflicting_components},
                            {"features_dropped", building.num_dropped_features},
                            {"matches_refused", building.num_refused_matches}};
  // --masks: the detected features they removed (null without masks).
  json["masked_features"] =
      inputs.feature_masks ? nlohmann::json(run.run.masked_features) : nlohmann::json(nullptr);
  const MovingObjectCheck& moving = run.run.moving_object;
  json["moving_object"] = {
      {"mapped_again", moving.mapped_again},
      {"measured_tracks", moving.measured_tracks},
      {"unexplained_tracks", moving.unexplained_tracks},
      {"second_model_frames", moving.second_model_frames},
      {"first_tracks_explained_by_second", moving.first_tracks_explained_by_second},
      {"second_motion", moving.second_motion},
      {"reason", moving.reason}};
  // --cache: where the tracks were kept, and whether this run read them instead of detecting.
  const TrackCacheUse& cache = run.track_cache;
  json["tracks_from_cache"] = cache.from_cache;
  if (!cache.file.empty()) {
    json["track_cache"] = {{"file", cache.file},
                           {"key", io::HexDigits(cache.key)},
                           {"from_cache", cache.from_cache},
                           {"warning", cache.warning}};
  }
  if (run.rotation_only) {
    json["rotation_only_path"] =
        RotationOnlyPathToJson(*run.rotation_only, inputs.sequence->NumFrames());
  }
  const std::vector<std::string> outputs = DetectorOutputFiles(run, options);
  if (writes_outputs && !outputs.empty()) json["outputs"] = outputs;
  return json;
}

}  // namespace comic::sfm
