// comic_sfm: structure from motion on a frame sequence. Detects and tracks features with the
// chosen detector, reconstructs the cameras and points incrementally (two-view initialisation,
// PnP, triangulation, Ceres bundle adjustment), and writes a COLMAP model (text, and binary under
// sparse/0/), a coloured PLY point cloud, report.json and a top-view trajectory plot; with
// ground-truth cameras it also reports the Sim(3)-aligned trajectory error. --compare runs several
// detectors on the same frames and writes one table. All the work is done by the libraries
// (sfm/sequence_reconstruction.h, sfm/evaluation/sfm_report.h, ...); this file only wires flags to
// them.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/common/arg_parser.h"
#include "apps/common/camera_intrinsics.h"
#include "apps/common/colmap_db_flags.h"
#include "apps/common/frame_range_flags.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/matching_flags.h"
#include "apps/common/progress_line.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "apps/common/tracker_flags.h"
#include "frontend/detector_factory.h"
#include "frontend/evaluation/region_labels.h"
#include "frontend/matching/pairing.h"
#include "frontend/matching/tracker.h"
#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/pixel_budget.h"
#include "io/core/staged_folder.h"
#include "io/datasets/ground_truth_cameras.h"
#include "io/datasets/region_annotations.h"
#include "io/image/frame_export.h"
#include "io/image/image_sequence.h"
#include "io/image/mask_folder.h"
#include "io/report/ply.h"
#include "io/report/report_table.h"
#include "sfm/bundle_adjuster.h"
#include "sfm/camera.h"
#include "sfm/colmap/colmap_comparison.h"
#include "sfm/colmap/colmap_export.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/colmap/colmap_pipeline.h"
#include "sfm/colmap/colmap_runner.h"
#include "sfm/colmap/model_set_writer.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/evaluation/reconstruction_stats.h"
#include "sfm/evaluation/sfm_report.h"
#include "sfm/evaluation/trajectory_plot.h"
#include "sfm/reconstruction_diagnosis.h"
#include "sfm/rotation_only_path.h"
#include "sfm/sequence_reconstruction.h"
#include "sfm/trajectory_evaluation.h"
#include "sfm/working_resolution.h"

namespace {

using comic::Error;
using comic::ErrorKind;
namespace io = comic::io;
namespace frontend = comic::frontend;
namespace sfm = comic::sfm;

// Every flag, with its default.
struct Flags {
  std::string frames;
  std::string detector = "harris";
  bool compare = false;
  std::string detectors;
  std::string intrinsics;
  std::string gt;
  std::string gt_format = "auto";
  bool gt_partial = false;
  int max_pixels = static_cast<int>(io::kDefaultMaxPixels);
  std::string out = "out/sfm";
  std::string model_format = "both";  // txt, bin or both
  std::string ply_format = "binary";
  io::ImageSequenceOptions sequence;
  std::string matching = "auto";      // frontend::ParsePairing
  comic::apps::TrackerFlags tracker;  // sfm::SequenceReconstructionOptions' tracker defaults
  bool refine_focal = false;
  bool refine_principal_point = false;
  bool refine_distortion = false;
  bool fixed_intrinsics = false;
  bool ignore_gt_intrinsics = false;
  std::string camera_model;  // empty: SIMPLE_RADIAL for the default camera, the file's otherwise
  bool no_retriangulate = false;
  bool two_view_tracks = false;
  int local_ba_images = sfm::IncrementalPipelineOptions().local_ba_num_images;
  double global_ba_growth = 1.5;
  double init_angle = 4.0;
  int init_max_gap = 0;
  int threads = 0;
  comic::apps::ObjectRegionFlags region{"", "", 11.0};
  std::string plot_plane = "auto";
  bool quiet = false;
  comic::apps::ColmapDbFlags colmap;
  bool compare_colmap = false;
  bool compare_colmap_sift = false;  // COLMAP's own pipeline on the same frames
  // Exit 1 when the largest model holds fewer than this fraction of the frames (issue 30).
  double min_registered = 0.5;
  // --write-frames: where a video's frames are written as PNGs (empty: not written, unless
  // --colmap-db needs them; kFramesInOutput: images/ in --output).
  std::string write_frames;
};

// --write-frames without a folder: images/ in --output, beside the model (COLMAP's layout).
const char kFramesInOutput[] = "<--output>/images";

// What every run shares, resolved and validated before any heavy work.
struct Inputs {
  std::unique_ptr<io::ImageSequence> sequence;
  std::vector<int> source_indices;
  sfm::Camera camera;
  std::string intrinsics_source;
  // No calibration was given: the default camera, self-calibrated unless --fixed-intrinsics.
  bool self_calibrating = false;
  std::optional<sfm::FrameGroundTruth> ground_truth;
  io::GroundTruthFormat gt_format = io::GroundTruthFormat::kAuto;
  std::vector<cv::Mat> region_labels;  // per frame, empty without --regions / --masks
  sfm::PlotPlane plot_plane;
  bool plot_plane_from_estimate = false;  // auto without ground truth: PCA of our centres
  // --matching resolved on the frames, and the tracker options it gives with the tracker flags.
  frontend::PairingChoice pairing;
  frontend::TrackerOptions tracker;
};

// `self_calibrating`: no calibration was given, so the focal length and distortion are refined
// (COLMAP's defaults, ba_refine_focal_length and ba_refine_extra_params) unless
// --fixed-intrinsics; the pipeline refines them once the model constrains them
// (sfm/incremental_pipeline.h) and keeps the prior focal where it is unobservable.
sfm::SequenceReconstructionOptions MakeOptions(const Flags& flags,
                                               const frontend::TrackerOptions& tracker,
                                               bool self_calibrating = false) {
  sfm::SequenceReconstructionOptions options;
  options.tracker = tracker;
  const bool automatic = self_calibrating && !flags.fixed_intrinsics;
  options.mapper.global_ba.refine_focal_length = flags.refine_focal || automatic;
  options.mapper.global_ba.refine_principal_point = flags.refine_principal_point;
  options.mapper.global_ba.refine_extra_params = flags.refine_distortion || automatic;
  options.mapper.mapper.retriangulate_incomplete_tracks = !flags.no_retriangulate;
  // Two-view tracks are left out of video (frame-to-frame tracks are long; the two-frame ones
  // are the unchecked leftovers) but kept for image sets matched across several frames, where a
  // track of two views is often all a sparse ring has: on the temple sparse ring leaving them out
  // took CoMIC's ATE from 0.0095 to 0.030 m (docs/sfm.md "Two-view tracks and the global loss").
  options.mapper.mapper.ignore_two_view_tracks =
      !flags.two_view_tracks && tracker.match_window <= 1;
  options.mapper.local_ba_num_images = flags.local_ba_images;
  options.mapper.global_ba_growth_ratio = flags.global_ba_growth;
  options.mapper.mapper.init_tri_angle_deg = flags.init_angle;
  options.mapper.mapper.init_max_frame_gap = flags.init_max_gap;
  // --threads is not passed to the bundle adjustments: Ceres sums the residual blocks of its
  // threads in a scheduling-dependent order (docs/sfm.md, determinism), and no app's output may
  // depend on the thread count. They stay on one thread; detection and the export use --threads.
  comic::apps::CheckThreadCount("--threads", flags.threads);
  options.Check();
  return options;
}

nlohmann::json CameraToJson(const sfm::Camera& camera) {
  return {{"model", sfm::CameraModelName(camera.model)},
          {"model_id", static_cast<int>(camera.model)},
          {"width", camera.width},
          {"height", camera.height},
          {"params", camera.Params()},
          {"params_info", sfm::CameraModelParamsInfo(camera.model)},
          {"pixel_convention", "OpenCV (top-left pixel centre at 0,0)"}};
}

// report.json "camera": the prior, the camera of the model (refined or not), and whether the
// motion let the focal length be refined.
nlohmann::json CameraReport(const sfm::SequenceReconstruction& run, const Inputs& inputs) {
  const sfm::IncrementalReconstruction& mapping = run.mapping;
  nlohmann::json json = {{"source", inputs.intrinsics_source},
                         {"prior", CameraToJson(inputs.camera)},
                         {"refined", mapping.intrinsics_refined}};
  const sfm::Reconstruction& reconstruction = mapping.reconstruction;
  const sfm::Camera& camera =
      reconstruction.cameras().empty() ? inputs.camera : reconstruction.cameras().begin()->second;
  // In the input's pixels (the prior is at the frames' size, see options.frame_size).
  const sfm::Camera final_camera =
      sfm::ResizedCamera(camera, run.input_size.width, run.input_size.height);
  json["final"] = CameraToJson(final_camera);
  json["focal_length_px"] = final_camera.fx;
  if (mapping.intrinsics_rejection.rejected) {
    json["rejected"] = CameraToJson(sfm::ResizedCamera(
        mapping.intrinsics_rejection.rejected_camera, run.input_size.width, run.input_size.height));
    json["rejection_reason"] = mapping.intrinsics_rejection.reason;
  }
  if (mapping.focal_assessed) {
    json["focal_observable"] = mapping.focal_observability.observable;
    json["max_viewing_angle_deg"] = mapping.focal_observability.max_viewing_angle_deg;
    json["focal_observability_rule"] =
        "observable when two registered images' optical axes are >= " +
        std::to_string(sfm::FocalObservabilityOptions().min_viewing_angle_deg) +
        " deg apart (sfm/focal_observability.h); otherwise the prior focal is kept";
  } else {
    json["focal_observable"] = nullptr;  // the focal was not to be refined
  }
  return json;
}

nlohmann::json OptionsToJson(const Flags& flags, const Inputs& inputs) {
  const sfm::Camera& c = inputs.camera;
  const frontend::TrackerOptions& tracker = inputs.tracker;
  const frontend::PairingChoice& pairing = inputs.pairing;
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
  return {{"frames", flags.frames},
          {"first", flags.sequence.first_frame},
          {"last", flags.sequence.last_frame},
          {"stride", flags.sequence.stride},
          {"resize_height", flags.sequence.resize_height},
          {"frame_size", {inputs.sequence->FrameSize().width, inputs.sequence->FrameSize().height}},
          {"intrinsics",
           {{"source", inputs.intrinsics_source},
            {"model", sfm::CameraModelName(c.model)},
            {"params", c.Params()},
            {"fx", c.fx},
            {"fy", c.fy},
            {"cx", c.cx},
            {"cy", c.cy},
            {"pixel_convention", "OpenCV (top-left pixel centre at 0,0)"}}},
          {"gt", flags.gt.empty() ? nlohmann::json(nullptr) : nlohmann::json(flags.gt)},
          {"gt_format", io::GroundTruthFormatName(inputs.gt_format)},
          {"max_features", tracker.max_features},
          {"search_radius_px", tracker.matcher.radius},
          {"unpredicted_radius_px", tracker.unpredicted_radius},
          {"matching", matching},
          {"prediction", frontend::MotionPredictionName(tracker.prediction)},
          {"coarse_radius_px", tracker.coarse_radius},
          {"match_window", tracker.match_window},
          {"track_conflicts", flags.tracker.track_conflicts},
          {"verify_min_gap", tracker.verify_min_gap},
          {"match_turned", tracker.match_turned_180},
          {"max_cost", tracker.matcher.max_cost},
          {"refine_focal", flags.refine_focal},
          {"refine_principal_point", flags.refine_principal_point},
          {"refine_distortion", flags.refine_distortion},
          {"fixed_intrinsics", flags.fixed_intrinsics},
          {"ignore_gt_intrinsics", flags.ignore_gt_intrinsics},
          {"camera_model", flags.camera_model},
          {"retriangulate", !flags.no_retriangulate},
          {"two_view_tracks", flags.two_view_tracks || inputs.tracker.match_window > 1},
          {"local_ba_images", flags.local_ba_images},
          {"global_ba_growth", flags.global_ba_growth},
          {"init_angle_deg", flags.init_angle},
          {"init_max_gap", flags.init_max_gap},
          {"threads", flags.threads},
          {"regions", flags.region.regions},
          {"masks", flags.region.masks},
          {"boundary_band_px", flags.region.boundary_band}};
}

sfm::PlotPlane ParsePlotPlane(const std::string& name) {
  if (name == "xz") return sfm::PlotPlaneFromAxes(0, 2);
  if (name == "xy") return sfm::PlotPlaneFromAxes(0, 1);
  if (name == "yz") return sfm::PlotPlaneFromAxes(1, 2);
  throw Error(ErrorKind::kInvalidArgument,
              "--plot-plane: expected auto, xz, xy or yz, got '" + name + "'");
}

Inputs ResolveInputs(const Flags& flags) {
  const comic::apps::ObjectRegionFlags& region = flags.region;
  COMIC_CHECK(region.regions.empty() || region.masks.empty(), kInvalidArgument,
              "--regions and --masks exclude each other");
  COMIC_CHECK(region.boundary_band > 0, kInvalidArgument, "--boundary-band must be > 0");
  if (flags.plot_plane != "auto") ParsePlotPlane(flags.plot_plane);
  const io::GroundTruthFormat gt_format = io::ParseGroundTruthFormat(flags.gt_format);

  Inputs inputs;
  inputs.sequence =
      std::make_unique<io::ImageSequence>(io::ImageSequence::Open(flags.frames, flags.sequence));
  const io::ImageSequence& sequence = *inputs.sequence;
  for (size_t k = 0; k < sequence.NumFrames(); ++k) {
    inputs.source_indices.push_back(flags.sequence.first_frame +
                                    static_cast<int>(k) * flags.sequence.stride);
  }
  const cv::Size source_size = sequence.SourceFrameSize();
  const cv::Size frame_size = sequence.FrameSize();

  if (!flags.gt.empty()) {
    const io::GroundTruthCameras truth = io::ReadGroundTruthCameras(flags.gt, gt_format);
    inputs.gt_format = truth.format;
    inputs.ground_truth = sfm::MatchGroundTruthToFrames(
        truth, sequence.FrameNames(), inputs.source_indices, source_size, frame_size);
    sfm::CheckGroundTruthCoverage(*inputs.ground_truth, sequence.FrameNames(), flags.gt,
                                  flags.gt_partial);
  }
  std::optional<sfm::CameraModelId> model;
  if (!flags.camera_model.empty()) model = comic::apps::ParseCameraModelFlag(flags.camera_model);
  if (!flags.intrinsics.empty()) {
    inputs.camera =
        comic::apps::LoadCameraIntrinsics(flags.intrinsics, source_size, frame_size, model);
    inputs.intrinsics_source = "file " + flags.intrinsics;
  } else if (inputs.ground_truth && inputs.ground_truth->camera && !flags.ignore_gt_intrinsics) {
    inputs.camera = *inputs.ground_truth->camera;
    if (model) inputs.camera = comic::apps::ConvertCameraModel(inputs.camera, *model);
    inputs.intrinsics_source = "ground truth " + flags.gt;
  } else {
    // COLMAP's default for unknown cameras: SIMPLE_RADIAL, f = 1.2 max(w, h), k = 0.
    inputs.camera = sfm::Camera::FromImageSize(frame_size.width, frame_size.height,
                                               model.value_or(sfm::CameraModelId::kSimpleRadial));
    inputs.self_calibrating = true;
    inputs.intrinsics_source =
        std::string("default: f = 1.2 max(w, h), principal point at the centre") +
        (flags.fixed_intrinsics ? ", held fixed" : ", refined once the model constrains it");
  }
  inputs.camera.width = frame_size.width;
  inputs.camera.height = frame_size.height;

  if (!region.regions.empty() || !region.masks.empty()) {
    std::optional<io::RegionAnnotations> regions;
    std::optional<io::MaskFolder> masks;
    if (!region.regions.empty()) {
      regions = io::ReadRegionFile(region.regions);
    } else {
      masks = io::MaskFolder::Open(region.masks);
    }
    for (int source_index : inputs.source_indices) {
      cv::Mat mask;
      if (regions) {
        COMIC_CHECK(source_index < static_cast<int>(regions->polygons.size()), kInvalidData,
                    region.regions << ": no region for frame " << source_index);
        mask = io::RasterizeRegion(regions->polygons[source_index], source_size, frame_size);
      } else {
        COMIC_CHECK(source_index < static_cast<int>(masks->NumMasks()), kInvalidData,
                    region.masks << ": no mask for frame " << source_index);
        mask = masks->Read(source_index, source_size);
        if (mask.size() != frame_size) {
          cv::resize(mask, mask, frame_size, 0, 0, cv::INTER_NEAREST);
        }
      }
      inputs.region_labels.push_back(frontend::LabelRegion(mask, region.boundary_band));
    }
  }

  if (flags.plot_plane != "auto") {
    inputs.plot_plane = ParsePlotPlane(flags.plot_plane);
  } else if (inputs.gt_format == io::GroundTruthFormat::kKitti) {
    inputs.plot_plane = sfm::PlotPlaneFromAxes(0, 2);  // KITTI: y points down, x–z is the ground
  } else if (inputs.ground_truth) {
    std::vector<Eigen::Vector3d> centers;
    for (const auto& pose : inputs.ground_truth->cams_from_world) {
      if (pose) centers.push_back(sfm::ProjectionCenter(*pose));
    }
    inputs.plot_plane = sfm::PlotPlaneFromCenters(centers);
  } else {
    inputs.plot_plane_from_estimate = true;
  }
  return inputs;
}

sfm::RegionLabelFn RegionLabels(const Inputs& inputs) {
  if (inputs.region_labels.empty()) return {};
  return [&inputs](const sfm::Image& image, const Eigen::Vector2d& xy) {
    const cv::Mat& labels = inputs.region_labels.at(image.image_id - 1);
    const int x = static_cast<int>(std::lround(xy.x()));
    const int y = static_cast<int>(std::lround(xy.y()));
    if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows) {
      return frontend::RegionLabel::kOutside;
    }
    return static_cast<frontend::RegionLabel>(labels.at<uint8_t>(y, x));
  };
}

cv::Mat RenderPlot(const Inputs& inputs, const sfm::Reconstruction& reconstruction,
                   const std::optional<sfm::TrajectoryEvaluation>& evaluation,
                   const std::string& title) {
  const io::ImageSequence& sequence = *inputs.sequence;
  const auto estimated = sfm::RegisteredPosesByName(reconstruction, sequence.FrameNames());
  std::vector<std::optional<Eigen::Vector3d>> estimated_centers(estimated.size());
  std::vector<std::optional<Eigen::Vector3d>> true_centers(estimated.size());
  std::vector<Eigen::Vector3d> all_estimated;
  for (size_t i = 0; i < estimated.size(); ++i) {
    if (estimated[i]) {
      Eigen::Vector3d center = sfm::ProjectionCenter(*estimated[i]);
      if (evaluation) center = evaluation->gt_from_estimated * center;
      estimated_centers[i] = center;
      all_estimated.push_back(center);
    }
    if (inputs.ground_truth && inputs.ground_truth->cams_from_world[i]) {
      true_centers[i] = sfm::ProjectionCenter(*inputs.ground_truth->cams_from_world[i]);
    }
  }
  // Without an alignment the estimate lives in its own frame: draw it alone.
  if (!evaluation) std::fill(true_centers.begin(), true_centers.end(), std::nullopt);
  const sfm::PlotPlane plane = inputs.plot_plane_from_estimate
                                   ? sfm::PlotPlaneFromCenters(all_estimated)
                                   : inputs.plot_plane;
  sfm::TrajectoryPlotOptions options;
  options.title = title;
  return sfm::RenderTrajectoryPlot(estimated_centers, true_centers, plane, options);
}

bool IntrinsicsKnown(const Flags& flags, const Inputs& inputs);
sfm::ColmapExportOptions ExportOptions(const Flags& flags, const Inputs& inputs);

struct DetectorRun {
  sfm::SequenceReconstruction run;
  sfm::SfmRunReport report;
  sfm::ReconstructionDiagnosis diagnosis;  // failed = false for a model
  bool wrote_tracks = false;               // no model: tracks.db holds the tracks
  int rotation_only_frames = 0;            // panning: frames of rotation_only/ (0: none)
};

// Reconstructs with one detector and writes its outputs into `out_dir`.
DetectorRun RunDetector(const std::string& detector_name, const Flags& flags, const Inputs& inputs,
                        const std::string& out_dir) {
  frontend::DetectorOptions detector_options;
  detector_options.name = detector_name;
  detector_options.comic.num_threads = flags.threads;
  detector_options.comic_paper.num_threads = flags.threads;
  const std::unique_ptr<frontend::Detector> detector = frontend::MakeDetector(detector_options);
  const sfm::SequenceReconstructionOptions options =
      MakeOptions(flags, inputs.tracker, inputs.self_calibrating);
  const std::string tag = "[" + detector_name + "] ";
  // Detection and tracking are most of a run's time (issue 17: 39.5 s of 48 s silent on KITTI).
  comic::apps::ProgressLine tracking_progress(tag + "detection and tracking", flags.quiet);
  DetectorRun result;
  result.run = sfm::ReconstructSequence(
      *inputs.sequence, *detector, inputs.camera, options, tracking_progress.Callback(),
      [&](const sfm::MapperProgress& p) {
        if (flags.quiet) return;
        std::cout << tag << (p.attempt > 0 ? "model " + std::to_string(p.attempt + 1) + ": " : "")
                  << "registered " << p.frame_name << (p.initial_pair ? " (initial pair)" : "")
                  << ": " << p.num_registered << "/" << p.num_frames << " frames, "
                  << p.num_points3D << " points";
        if (p.merged) {
          std::cout << " (merged from an earlier model)";
        } else if (!p.initial_pair) {
          std::cout << ", " << p.num_pose_inliers << " PnP inliers";
        }
        std::cout << std::endl;
      });
  const sfm::Reconstruction& reconstruction = result.run.mapping.reconstruction;
  const sfm::ReconstructionStats stats =
      sfm::ComputeReconstructionStats(reconstruction, RegionLabels(inputs));
  std::optional<sfm::TrajectoryEvaluation> evaluation;
  if (inputs.ground_truth) {
    evaluation = sfm::EvaluateTrajectory(
        sfm::RegisteredPosesByName(reconstruction, inputs.sequence->FrameNames()),
        inputs.ground_truth->cams_from_world);
  }
  result.report = sfm::MakeRunReport(result.run, stats, evaluation);

  io::EnsureWritableDirectory(out_dir);
  nlohmann::json json = sfm::RunReportToJson(result.report);
  json["options"] = OptionsToJson(flags, inputs);
  json["camera"] = CameraReport(result.run, inputs);
  const frontend::TrackBuildSummary& building = result.run.track_building;
  result.diagnosis = sfm::DiagnoseReconstruction(result.run.mapping, options.mapper,
                                                 inputs.sequence->FrameNames());
  if (result.diagnosis.failed) {
    const sfm::ReconstructionDiagnosis& d = result.diagnosis;
    json["diagnosis"] = {{"stage", d.stage},
                         {"check", d.check},
                         {"value", d.value},
                         {"needed", d.needed},
                         {"frame1", d.frame1},
                         {"frame2", d.frame2},
                         {"rotation_only", d.rotation_only},
                         {"message", d.message},
                         {"suggestion", d.suggestion}};
  }
  json["track_building"] = {{"matches", building.num_matches},
                            {"tracks", result.run.tracks.tracks.size()},
                            {"conflicting_components_dropped", building.num_conflicting_components},
                            {"features_dropped", building.num_dropped_features},
                            {"matches_refused", building.num_refused_matches}};
  if (sfm::HasModel(result.run.mapping.status)) {
    // Every model in the input's pixels: sparse/<k>/ as COLMAP's mapper numbers its models (where
    // nerfstudio and the Gaussian-splatting tools look for sparse/0), the largest as text on top.
    std::vector<std::string> outputs =
        sfm::WriteModelSet(result.run.mapping, out_dir,
                           {flags.model_format != "bin", flags.model_format != "txt",
                            result.run.input_size.width, result.run.input_size.height});
    std::vector<io::PlyPoint> cloud;
    for (const auto& [point3D_id, point] : reconstruction.points3D()) {
      cloud.push_back({point.xyz, point.color});
    }
    io::WritePly(io::JoinPaths(out_dir, "points.ply"), cloud, io::ParsePlyFormat(flags.ply_format));
    io::WriteImageAtomically(
        io::JoinPaths(out_dir, "trajectory.png"),
        RenderPlot(inputs, reconstruction, evaluation,
                   "comic_sfm --detector " + detector_name + "  " + flags.frames));
    outputs.insert(outputs.end(), {"points.ply", "trajectory.png"});
    json["outputs"] = outputs;
  } else if (inputs.sequence->NumFrames() >= 2 && !result.run.tracks.tracks.empty()) {
    // No model, but never a silent nothing (issue 17): the tracks found, as a COLMAP database
    // (`colmap mapper` or the GUI can be tried on them; docs/footage.md).
    sfm::ExportTracksToColmapDatabase(
        result.run.tracks,
        IntrinsicsKnown(flags, inputs) ? std::optional<sfm::Camera>(inputs.camera) : std::nullopt,
        ExportOptions(flags, inputs), io::JoinPaths(out_dir, "tracks.db"), /*overwrite=*/true);
    json["outputs"] = {"tracks.db"};
    result.wrote_tracks = true;
    if (result.diagnosis.rotation_only) {
      // Panning: no points, but the rotations are observable; a COLMAP model of the cameras
      // alone, all at the origin (sfm/rotation_only_path.h).
      const sfm::RotationOnlyPath path =
          sfm::EstimateRotationOnlyPath(result.run.tracks, inputs.camera);
      result.rotation_only_frames = path.num_registered;
      double mean_rms = 0.0;
      for (double rms : path.rms_error_px) mean_rms += rms / path.rms_error_px.size();
      json["rotation_only_path"] = {{"registered_frames", path.num_registered},
                                    {"frames", inputs.sequence->NumFrames()},
                                    {"mean_rms_error_px", mean_rms}};
      if (path.num_registered >= 2) {
        io::WriteColmapTextModel(sfm::ToColmapTextModel(path.reconstruction),
                                 io::JoinPaths(out_dir, "rotation_only"));
        json["outputs"].push_back("rotation_only/cameras.txt");
        json["outputs"].push_back("rotation_only/images.txt");
        json["outputs"].push_back("rotation_only/points3D.txt");
      }
    }
  }
  io::WriteFileAtomically(io::JoinPaths(out_dir, "report.json"), json.dump(2) + "\n");
  return result;
}

void PrintSummary(const sfm::SfmRunReport& report, const sfm::SequenceReconstruction& run) {
  std::cout << "[" << report.detector << "] " << report.status << ": "
            << report.stats.num_registered << "/" << report.num_frames << " frames registered";
  if (!report.rotation_only_frames.empty() || !report.interpolated_frames.empty()) {
    std::cout << " (" << report.rotation_only_frames.size() << " by rotation only, "
              << report.interpolated_frames.size() << " interpolated)";
  }
  if (report.models.size() > 1) {
    std::cout << " in the largest of " << report.models.size() << " models (";
    for (size_t m = 1; m < report.models.size(); ++m) {
      std::cout << (m > 1 ? ", " : "") << report.models[m].num_registered;
    }
    std::cout << " frames in the others)";
  }
  std::cout << ", " << report.stats.all.num_points << " points, mean track length "
            << report.stats.all.mean_track_length << ", mean reprojection error "
            << report.stats.all.mean_reprojection_error_px << " px";
  if (report.trajectory) {
    std::cout << ", ATE " << report.trajectory->ate_rmse << " ("
              << 100.0 * report.trajectory->ate_fraction_of_path << " % of "
              << report.trajectory->path_length << "), rotation error "
              << report.trajectory->mean_rotation_error_deg << " deg";
  }
  std::cout << ", " << report.wall_time_s << " s";
  const sfm::IncrementalReconstruction& mapping = run.mapping;
  if (mapping.reconstruction.NumRegisteredImages() > 0 &&
      !mapping.reconstruction.cameras().empty()) {
    const sfm::Camera& camera = mapping.reconstruction.cameras().begin()->second;
    std::cout << "; camera "
              << sfm::ResizedCamera(camera, run.input_size.width, run.input_size.height).Describe()
              << (mapping.intrinsics_refined ? " (refined)" : "");
    if (!report.intrinsics_rejection.empty()) {
      std::cout << " (held at the prior: " << report.intrinsics_rejection << ")";
    }
    if (mapping.focal_assessed && !mapping.focal_observability.observable) {
      std::cout << ", focal unobservable (optical axes within "
                << mapping.focal_observability.max_viewing_angle_deg << " deg): prior kept";
    }
  }
  // Frames the largest model could not take, in ranges with the check that failed (e.g.
  // "40-47 registration/visible_points"; report.json words each).
  if (report.stats.num_registered > 0 && !report.unregistered_ranges.empty()) {
    std::cout << "; unregistered frames: "
              << sfm::DescribeUnregisteredRanges(report.unregistered_ranges);
  }
  std::cout << std::endl;
}

// --colmap-db / --compare-colmap: checks that can fail before any work.
void CheckColmapFlags(const Flags& flags) {
  comic::apps::CheckColmapDbFlags(flags.colmap);
  if (flags.compare_colmap_sift) {
    COMIC_CHECK(!flags.compare && io::IsDirectory(flags.frames), kInvalidArgument,
                "--compare-colmap-sift needs FRAMES to be a folder of images and one detector "
                "(not --compare)");
    COMIC_CHECK(sfm::IsColmapAvailable(), kNotFound,
                "--compare-colmap-sift: colmap is not installed (apt-get install colmap)");
    COMIC_CHECK(!io::PathExists(io::JoinPaths(flags.out, "colmap_sift")), kIo,
                io::JoinPaths(flags.out, "colmap_sift")
                    << ": exists from an earlier --compare-colmap-sift; remove it or use another "
                       "--output");
  }
  if (flags.colmap.database.empty() && !flags.compare_colmap) return;
  COMIC_CHECK(!flags.compare, kInvalidArgument,
              "--colmap-db and --compare-colmap work on one detector's run, not with --compare");
  // A folder's frames are COLMAP's images as stored; a video's are written by --write-frames as
  // the model sees them (resized too), so only a folder needs --resize-height 0.
  const bool video = io::PathExists(flags.frames) && !io::IsDirectory(flags.frames);
  COMIC_CHECK(video || flags.sequence.resize_height == 0, kInvalidArgument,
              "--colmap-db and --compare-colmap need --resize-height 0 (COLMAP reads the image "
              "files at their stored size)");
  COMIC_CHECK(!flags.compare_colmap || io::IsDirectory(flags.frames), kInvalidArgument,
              "--compare-colmap needs FRAMES to be a folder of images (for a video use "
              "--colmap-db, which writes the frames, and run COLMAP on it)");
  if (!flags.colmap.database.empty()) {
    io::CheckWritableFile(flags.colmap.database, flags.colmap.overwrite);
  }
  if (flags.compare_colmap) {
    COMIC_CHECK(sfm::IsColmapAvailable(), kNotFound,
                "--compare-colmap: colmap is not installed (apt-get install colmap)");
    const std::string work = io::JoinPaths(flags.out, "colmap");
    COMIC_CHECK(
        !io::PathExists(work), kIo,
        work << ": exists from an earlier --compare-colmap; remove it or use another --output");
  }
}

// The frames' intrinsics are known (not the default guess): COLMAP holds them fixed.
bool IntrinsicsKnown(const Flags& /*flags*/, const Inputs& inputs) {
  return !inputs.self_calibrating;  // --intrinsics, or the ground truth's unless ignored
}

// The export options of --colmap-db and --compare-colmap, as comic_export_colmap sets them.
sfm::ColmapExportOptions ExportOptions(const Flags& flags, const Inputs& inputs) {
  sfm::ColmapExportOptions options = flags.colmap.export_options;
  options.num_threads = flags.threads;
  options.default_camera_model = inputs.camera.model;  // the model of a guessed camera
  return options;
}

// --colmap-db: the tracks of this run as a COLMAP database, and the command to run on it.
// `image_path` holds the frames as files: FRAMES, or for a video where --write-frames puts them.
void WriteColmapDatabase(const Flags& flags, const Inputs& inputs,
                         const sfm::SequenceReconstruction& run, const std::string& image_path) {
  const std::string& database = flags.colmap.database;
  // COLMAP reads a folder's images at their stored size: the tracks in the input's pixels.
  const double to_input = static_cast<double>(run.input_size.height) / run.frame_size.height;
  const bool folder = io::IsDirectory(flags.frames);
  const sfm::ColmapExportSummary summary = sfm::ExportTracksToColmapDatabase(
      folder && to_input != 1.0 ? sfm::ScaleTracks(run.tracks, to_input) : run.tracks,
      IntrinsicsKnown(flags, inputs)
          ? std::optional<sfm::Camera>(
                folder
                    ? sfm::ResizedCamera(inputs.camera, run.input_size.width, run.input_size.height)
                    : inputs.camera)
          : std::nullopt,
      ExportOptions(flags, inputs), database, flags.colmap.overwrite);
  sfm::ColmapMapperOptions mapper = sfm::RecommendedColmapMapperOptions(summary);
  mapper.num_threads = flags.colmap.colmap_threads;
  std::cout << "wrote " << database << " (" << summary.num_images << " images, "
            << summary.num_verified_pairs << " of " << summary.num_matched_pairs
            << " pairs verified); run COLMAP on it with:\n  "
            << sfm::ColmapMapperCommandLine(
                   database, image_path, io::JoinPaths(io::ParentPath(database), "sparse"), mapper)
            << std::endl;
}

// --compare-colmap: COLMAP's mapper on the same tracks, side by side with this run.
void CompareWithColmap(const Flags& flags, const Inputs& inputs,
                       const sfm::SequenceReconstruction& run, const io::StagedFolder& out) {
  sfm::ColmapComparisonOptions options;
  options.export_options = ExportOptions(flags, inputs);
  options.colmap_threads = flags.colmap.colmap_threads;
  const std::vector<std::optional<sfm::Rigid3d>> truth =
      inputs.ground_truth ? inputs.ground_truth->cams_from_world
                          : std::vector<std::optional<sfm::Rigid3d>>();
  // COLMAP reads the folder's images at their stored size: the tracks in the input's pixels.
  const double to_input = static_cast<double>(run.input_size.height) / run.frame_size.height;
  const sfm::ColmapComparison comparison = sfm::CompareWithColmap(
      to_input != 1.0 ? sfm::ScaleTracks(run.tracks, to_input) : run.tracks,
      sfm::ResizedCamera(inputs.camera, run.input_size.width, run.input_size.height),
      IntrinsicsKnown(flags, inputs), truth, flags.frames, io::JoinPaths(out.path(), "colmap"),
      options, &run.mapping);
  const io::ReportTable table = comparison.Table();
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_compare.md"), table.ToMarkdown());
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_compare.csv"), table.ToCsv());
  const nlohmann::json json = {
      {"table", table.ToJson()},
      // Paths as they will be after the outputs move into place, not the staging folder's.
      {"colmap_mapper_command", out.ToTargetPaths(comparison.colmap_mapper_command)},
      {"colmap_model", comparison.colmap_model_path
                           ? nlohmann::json(out.ToTargetPaths(*comparison.colmap_model_path))
                           : nlohmann::json(nullptr)},
      {"colmap_log", out.ToTargetPaths(comparison.log_path)},
      {"export_time_s", comparison.export_time_s},
      {"export",
       {{"images", comparison.export_summary.num_images},
        {"pairs", comparison.export_summary.num_matched_pairs},
        {"verified_pairs", comparison.export_summary.num_verified_pairs},
        {"matches", comparison.export_summary.num_matches},
        {"inlier_matches", comparison.export_summary.num_inlier_matches},
        {"known_intrinsics", comparison.export_summary.known_intrinsics}}}};
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_compare.json"), json.dump(2) + "\n");
  std::cout << out.ToTargetPaths(table.ToMarkdown())
            << "COLMAP ran: " << out.ToTargetPaths(comparison.colmap_mapper_command)
            << "\n(log: " << out.ToTargetPaths(comparison.log_path) << ")" << std::endl;
}

// --compare-colmap-sift: COLMAP's own pipeline (SIFT, matcher, mapper) on the same frames.
void CompareWithColmapSift(const Flags& flags, const Inputs& inputs, const sfm::SfmRunReport& ours,
                           bool threads_set, const io::StagedFolder& out) {
  sfm::ColmapPipelineOptions options;
  options.sequential = inputs.pairing.chosen.mode == frontend::PairingMode::kSequential;
  if (threads_set) options.num_threads = flags.colmap.colmap_threads;
  const sfm::ColmapPipelineRun colmap = sfm::RunColmapPipeline(
      flags.frames, inputs.sequence->FrameNames(), io::JoinPaths(out.path(), "colmap_sift"),
      inputs.ground_truth ? inputs.ground_truth->cams_from_world
                          : std::vector<std::optional<sfm::Rigid3d>>(),
      options);
  const io::ReportTable table = sfm::ColmapPipelineTable(ours, colmap);
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_sift_compare.md"), table.ToMarkdown());
  nlohmann::json json = {{"table", table.ToJson()}, {"commands", nlohmann::json::array()}};
  for (const std::string& command : colmap.commands) {
    json["commands"].push_back(out.ToTargetPaths(command));
  }
  io::WriteFileAtomically(io::JoinPaths(out.path(), "colmap_sift_compare.json"),
                          json.dump(2) + "\n");
  std::cout << table.ToMarkdown() << "COLMAP ran (log: " << out.ToTargetPaths(colmap.log_path)
            << "):\n";
  for (const std::string& command : colmap.commands)
    std::cout << "  " << out.ToTargetPaths(command) << "\n";
  std::cout << std::flush;
}

int Run(int argc, char** argv) {
  Flags flags;
  comic::apps::ArgParser parser(
      "comic_sfm", "FRAMES [options]",
      "Structure from motion on a frame sequence (folder of images or video): tracks features\n"
      "with the chosen detector, reconstructs cameras and points incrementally with Ceres bundle\n"
      "adjustment, and writes into --output: cameras.txt, images.txt, points3D.txt (a COLMAP text\n"
      "model; --model-format), sparse/0/{cameras,images,points3D}.bin (the same model in\n"
      "COLMAP's binary format), points.ply (coloured point cloud; --ply-format), report.json\n"
      "(every number and the options), trajectory.png (top view; with --gt, ours Sim(3)-aligned\n"
      "against the ground truth).");
  parser.AddPositional("FRAMES", "folder of images, or video file", &flags.frames);
  comic::apps::AddDetectorFlag(parser, &flags.detector);
  parser.AddFlag(
      "compare",
      "run every detector of --detectors on the same frames; writes --output/<detector>/ "
      "and the table compare.md, compare.csv, compare.json",
      &flags.compare);
  comic::apps::AddDetectorListFlag(parser, &flags.detectors);
  comic::apps::AddIntrinsicsFlag(parser, &flags.intrinsics);
  parser.AddOption("gt", "PATH",
                   "ground-truth cameras: KITTI poses.txt (calib.txt beside it gives the "
                   "intrinsics; matched by frame index), Middlebury *_par.txt, or a folder of "
                   "Strecha *.camera files (matched by image name)",
                   &flags.gt);
  parser.AddOption("gt-format", "F", "format of --gt: auto, kitti, middlebury or strecha",
                   &flags.gt_format);
  parser.AddFlag("gt-partial",
                 "accept --gt that covers only some frames and evaluate on those (otherwise "
                 "an error)",
                 &flags.gt_partial);
  comic::apps::AddAllowTruncatedFlag(parser, &flags.sequence.allow_truncated);
  comic::apps::AddMaxPixelsFlag(parser, &flags.max_pixels);
  comic::apps::AddOutputFolderFlag(parser, &flags.out);
  parser.AddOption("model-format", "F",
                   "COLMAP model written: txt (cameras.txt ... in --output), bin (cameras.bin ... "
                   "in --output/sparse/0/) or both",
                   &flags.model_format);
  parser.AddOption("ply-format", "F",
                   "points.ply as binary (little-endian, float xyz, uchar rgb) or ascii (exact "
                   "doubles)",
                   &flags.ply_format);
  comic::apps::AddResizeHeightFlag(parser, &flags.sequence.resize_height);
  comic::apps::AddFrameRangeFlags(parser, &flags.sequence);
  comic::apps::AddMatchingFlag(parser, &flags.matching);
  comic::apps::AddTrackerFlags(parser, &flags.tracker);
  parser.AddFlag("no-retriangulate",
                 "do not triangulate a track again from all its registered views when its point "
                 "misses some of them (on by default: the new point must explain more views within "
                 "2 px)",
                 &flags.no_retriangulate);
  parser.AddFlag("two-view-tracks",
                 "also triangulate tracks seen in only two frames in a video (image sets matched "
                 "across several frames always keep them; video leaves them out by default, as "
                 "COLMAP: such a point has no third view to check it)",
                 &flags.two_view_tracks);
  parser.AddFlag("refine-focal",
                 "refine the focal length in the global bundle adjustments (on by default without "
                 "a calibration; kept where the motion leaves it unobservable)",
                 &flags.refine_focal);
  parser.AddFlag("refine-principal-point",
                 "refine the principal point in the global bundle adjustments",
                 &flags.refine_principal_point);
  parser.AddFlag("refine-distortion",
                 "refine the camera model's distortion in the global bundle adjustments (on by "
                 "default without a calibration)",
                 &flags.refine_distortion);
  parser.AddFlag("fixed-intrinsics",
                 "without a calibration, keep the default camera fixed instead of refining its "
                 "focal length and distortion",
                 &flags.fixed_intrinsics);
  comic::apps::AddCameraModelFlag(parser, &flags.camera_model);
  parser.AddFlag("ignore-gt-intrinsics",
                 "use --gt for evaluation only, not as the camera's intrinsics (self-calibration "
                 "measured against the truth)",
                 &flags.ignore_gt_intrinsics);
  parser.AddOption("local-ba-images", "N", "images in each local bundle adjustment",
                   &flags.local_ba_images);
  parser.AddOption("global-ba-growth", "R",
                   "adjust the whole model whenever it has grown by this factor (and at the end)",
                   &flags.global_ba_growth);
  parser.AddOption("init-angle", "DEG",
                   "initial pair: a point's triangulation angle that counts fully towards the "
                   "pair's parallax score",
                   &flags.init_angle);
  parser.AddOption("init-max-gap", "N",
                   "initial pair: frames at most this far apart (0: no limit, the gap grows as "
                   "far as the tracks reach)",
                   &flags.init_max_gap);
  parser.AddOption("min-registered", "F",
                   "exit 1 unless the largest model holds at least this fraction of the frames "
                   "(the models are written either way; 'success' needs 0.95)",
                   &flags.min_registered);
  comic::apps::AddThreadsFlag(parser, &flags.threads);
  comic::apps::AddObjectRegionFlags(parser, &flags.region);
  parser.AddOption("plot-plane", "P",
                   "trajectory plot plane: auto (x-z for KITTI, else the plane of largest "
                   "spread), xz, xy or yz",
                   &flags.plot_plane);
  comic::apps::AddQuietFlag(parser, &flags.quiet);
  comic::apps::AddColmapDbFlags(parser, &flags.colmap);
  parser.AddOptionalValueOption(
      "write-frames", "DIR",
      "video input: write each frame once as DIR/frame_000000.png ..., the names the model and "
      "--colmap-db use, so that COLMAP's image tools find them (alone: images/ in --output)",
      kFramesInOutput, &flags.write_frames);
  parser.AddFlag("compare-colmap",
                 "also run COLMAP's mapper on the same tracks and write the side-by-side table "
                 "--output/colmap_compare.md (.csv, .json); COLMAP's files go to --output/colmap/",
                 &flags.compare_colmap);
  parser.AddFlag(
      "compare-colmap-sift",
      "also run COLMAP's own pipeline on the same frames with its defaults (SIFT, the "
      "sequential or exhaustive matcher as --matching chose, mapper; one thread unless "
      "--colmap-threads) and write the side-by-side table --output/colmap_sift_compare.md; "
      "COLMAP's files go to --output/colmap_sift/",
      &flags.compare_colmap_sift);
  parser.AddEpilog(
      "Example (the bundled KITTI clip, calibrated from its calib.txt, measured against\n"
      "its poses.txt):\n"
      "  comic_sfm examples/data/kitti06_000-011/image_l \\\n"
      "      --gt examples/data/kitti06_000-011/poses.txt --output out/example --compare\n"
      "--regions/--masks add boundary and interior point statistics. --colmap-db writes what\n"
      "comic_export_colmap writes with the same options; for a folder of images it needs\n"
      "--resize-height 0, a video's frames it writes as --write-frames does (the folder given,\n"
      "or images/ in --output), and COLMAP's --image_path is that folder.\n"
      "--threads: detection and the export; the bundle adjustments run on one thread (Ceres'\n"
      "multi-threaded sums are not bit-for-bit repeatable). Progress goes to stdout (-q: off);\n"
      "a failed run writes report.json with a diagnosis, tracks.db and, when the camera only\n"
      "turned, rotation_only/ (a camera path without points).\n"
      "Exit codes: 0 success, 2 usage error, 1 anything else (including a sequence that cannot\n"
      "be reconstructed without --compare).");
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;

  std::vector<std::string> detectors;
  if (flags.compare) {
    COMIC_CHECK(!parser.WasSet("detector"), kInvalidArgument,
                "--detector and --compare exclude each other (use --detectors with --compare)");
    detectors = flags.detectors.empty() ? frontend::DetectorNames()
                                        : frontend::ParseDetectorList(flags.detectors);
  } else {
    COMIC_CHECK(flags.detectors.empty(), kInvalidArgument, "--detectors needs --compare");
    try {
      frontend::CheckDetectorName(flags.detector);
    } catch (const Error& e) {
      throw Error(ErrorKind::kInvalidArgument, std::string("--detector: ") + e.what());
    }
    detectors = {flags.detector};
  }
  comic::apps::CheckThreadCount("--threads", flags.threads);
  io::CheckMaxPixels(flags.max_pixels);
  flags.sequence.max_pixels = flags.max_pixels;
  flags.sequence.Check();
  frontend::ParsePairing(flags.matching);                            // before any work
  MakeOptions(flags, comic::apps::ToTrackerOptions(flags.tracker));  // the numeric options too
  COMIC_CHECK(
      flags.model_format == "txt" || flags.model_format == "bin" || flags.model_format == "both",
      kInvalidArgument,
      "--model-format: unknown format '" << flags.model_format << "' (expected txt, bin or both)");
  COMIC_CHECK(
      flags.ply_format == "binary" || flags.ply_format == "ascii", kInvalidArgument,
      "--ply-format: unknown format '" << flags.ply_format << "' (expected binary or ascii)");
  CheckColmapFlags(flags);
  COMIC_CHECK(flags.min_registered >= 0 && flags.min_registered <= 1, kInvalidArgument,
              "--min-registered must be in [0, 1], got " << flags.min_registered);
  // Frames larger than the working size are tracked and mapped at it, and the models written in
  // the input's pixels (sfm/working_resolution.h), unless --resize-height says otherwise.
  if (!parser.WasSet("resize-height")) {
    flags.sequence.resize_height = sfm::WorkingResizeHeight(
        io::ImageSequence::Open(flags.frames, flags.sequence).SourceFrameSize(),
        sfm::IncrementalPipelineOptions().max_working_image_size);
  }
  // Validate, then write, all or nothing: --out is checked but not created; the outputs go to a
  // staging folder beside it and move into place when the run has succeeded (issue 19).
  io::CheckCreatableFolder(flags.out);
  Inputs inputs = ResolveInputs(flags);
  inputs.pairing = comic::apps::ChooseRunPairing(flags.matching, parser, *inputs.sequence);
  inputs.tracker = comic::apps::TrackerOptionsForRun(
      parser, flags.tracker, inputs.pairing, static_cast<int>(inputs.sequence->NumFrames()));
  if (!inputs.sequence->warning().empty()) {
    std::cerr << "comic_sfm: warning: " << inputs.sequence->warning() << std::endl;
  }
  const bool video = inputs.sequence->IsVideo();
  COMIC_CHECK(flags.write_frames.empty() || video, kInvalidArgument,
              "--write-frames: " << flags.frames
                                 << " is a folder of images already (COLMAP reads them there); "
                                    "--write-frames is for a video");
  // A video's frames as files: asked for, or needed by COLMAP for the database.
  std::string frames_folder = flags.write_frames;
  if (frames_folder.empty() && video && !flags.colmap.database.empty()) {
    frames_folder = kFramesInOutput;
  }
  io::StagedFolder out(flags.out);
  std::unique_ptr<io::StagedFolder> frames_out;  // a --write-frames folder outside --output
  std::string frames_staging;                    // where the frames are written
  std::string frames_target;                     // where they will be after the commit
  if (frames_folder == kFramesInOutput) {
    frames_staging = io::JoinPaths(out.path(), "images");
    frames_target = io::JoinPaths(flags.out, "images");
  } else if (!frames_folder.empty()) {
    frames_out = std::make_unique<io::StagedFolder>(frames_folder);
    frames_staging = frames_out->path();
    frames_target = frames_folder;
  }
  auto write_frames = [&] {
    if (frames_staging.empty()) return;
    comic::apps::ProgressLine progress("comic_sfm: writing frames", flags.quiet);
    io::WriteSequenceFrames(*inputs.sequence, frames_staging, progress.Callback());
    if (!flags.quiet) {
      std::cout << "comic_sfm: " << inputs.sequence->NumFrames() << " frames as PNG in "
                << frames_target << " (COLMAP's --image_path)" << std::endl;
    }
  };
  auto commit = [&] {
    out.Commit();
    if (frames_out) frames_out->Commit();
  };
  // The line saying where the intrinsics came from is printed even with --quiet (issue 17).
  {
    std::cout << "comic_sfm: " << inputs.sequence->NumFrames() << " frames "
              << inputs.sequence->FrameSize().width << "x" << inputs.sequence->FrameSize().height
              << ", camera " << inputs.camera.Describe() << " (" << inputs.intrinsics_source << ")"
              << (inputs.ground_truth
                      ? ", ground truth for " + std::to_string(inputs.ground_truth->num_matched) +
                            " frames"
                      : std::string())
              << std::endl;
    std::cout << "comic_sfm: matching " << frontend::PairingName(inputs.pairing.chosen) << " ("
              << (inputs.pairing.requested.mode == frontend::PairingMode::kAuto ? "auto: " : "")
              << inputs.pairing.reason << ")" << std::endl;
  }

  if (!flags.compare) {
    const DetectorRun result = RunDetector(flags.detector, flags, inputs, out.path());
    PrintSummary(result.report, result.run);
    const bool success = sfm::HasModel(result.run.mapping.status);
    write_frames();
    if (success && !flags.colmap.database.empty()) {
      WriteColmapDatabase(flags, inputs, result.run, video ? frames_target : flags.frames);
    }
    if (success && flags.compare_colmap) CompareWithColmap(flags, inputs, result.run, out);
    if (flags.compare_colmap_sift) {
      CompareWithColmapSift(flags, inputs, result.report, parser.WasSet("colmap-threads"), out);
    }
    // A failed reconstruction commits its report.json (the documented exception): it says why.
    commit();
    // The error line says which check failed, by how much, and what to try (issue 17).
    if (!success && result.wrote_tracks) {
      // What was found, on stdout even with --quiet: the error line stays short.
      std::cout << "comic_sfm: no model; what was found: " << io::JoinPaths(flags.out, "tracks.db")
                << " (the tracks, a COLMAP database)"
                << (result.rotation_only_frames >= 2
                        ? ", " + io::JoinPaths(flags.out, "rotation_only/") +
                              " (a rotation-only camera path of " +
                              std::to_string(result.rotation_only_frames) + " frames)"
                        : std::string())
                << std::endl;
    }
    COMIC_CHECK(success, kInvalidData,
                result.diagnosis.message << "; try " << result.diagnosis.suggestion << " (report: "
                                         << io::JoinPaths(flags.out, "report.json") << ")");
    COMIC_CHECK(result.report.registered_fraction >= flags.min_registered, kInvalidData,
                "partial: the largest model holds "
                    << std::lround(100.0 * result.report.registered_fraction)
                    << " % of the frames, --min-registered asks for "
                    << std::lround(100.0 * flags.min_registered)
                    << " % (every model is written; report: "
                    << io::JoinPaths(flags.out, "report.json") << ")");
    return 0;
  }

  std::vector<sfm::SfmRunReport> reports;
  for (const std::string& name : detectors) {
    const DetectorRun result = RunDetector(name, flags, inputs, io::JoinPaths(out.path(), name));
    PrintSummary(result.report, result.run);
    reports.push_back(result.report);
  }
  const io::ReportTable table = sfm::MakeComparisonTable(reports);
  io::WriteFileAtomically(io::JoinPaths(out.path(), "compare.md"), table.ToMarkdown());
  io::WriteFileAtomically(io::JoinPaths(out.path(), "compare.csv"), table.ToCsv());
  nlohmann::json json = {{"table", table.ToJson()}, {"runs", nlohmann::json::array()}};
  for (const sfm::SfmRunReport& report : reports)
    json["runs"].push_back(sfm::RunReportToJson(report));
  json["options"] = OptionsToJson(flags, inputs);
  io::WriteFileAtomically(io::JoinPaths(out.path(), "compare.json"), json.dump(2) + "\n");
  write_frames();
  commit();
  std::cout << table.ToMarkdown();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Errors go to stderr as one line; Ceres' recoverable-trouble warnings would add noise there.
  comic::sfm::ShowOnlySolverErrors();
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_sfm", [&] { return Run(argc, argv); });
}
