#include "sfm/run/run_page_scene.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "io/datasets/ground_truth_cameras.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/run/run_page_timeline.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {

namespace {

const char kTruthColor[] = "#3aa655";
const char kUnregisteredColor[] = "#f0a000";
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string TruthUnit(const RunInputs& inputs) {
  const std::string unit = io::GroundTruthLengthUnit(inputs.gt_format);
  return unit.empty() ? "ground-truth units" : unit;
}

// Frames with a true pose that no model holds.
std::vector<int> UnregisteredWithTruth(const RunInputs& inputs, const DetectorRun& run) {
  std::vector<int> frames;
  if (!inputs.ground_truth) return frames;
  std::vector<bool> held(inputs.sequence->NumFrames(), false);
  for (const Reconstruction* model : RunModels(run)) {
    for (int f : RegisteredFramesOf(*model)) {
      if (f >= 0 && f < static_cast<int>(held.size())) held[f] = true;
    }
  }
  for (size_t f = 0; f < held.size(); ++f) {
    if (!held[f] && inputs.ground_truth->cams_from_world[f]) frames.push_back(static_cast<int>(f));
  }
  return frames;
}

Eigen::Vector3d TrueCenter(const RunInputs& inputs, int frame) {
  return ProjectionCenter(*inputs.ground_truth->cams_from_world[frame]);
}

io::SceneCameras PlacedCameras(const PlacedModel& placed, const Camera& camera) {
  io::SceneCameras cameras;
  cameras.name = ModelName(placed.index);
  cameras.color = ModelColor(placed.index);
  cameras.aspect = static_cast<double>(camera.width) / std::max(1, camera.height);
  cameras.focal_over_width = camera.fx / std::max(1, camera.width);
  for (const image_t id : placed.model->RegisteredImageIds()) {
    const Rigid3d& cam_from_world = placed.model->image(id).cam_from_world;
    cameras.centers.push_back(placed.world_from_model * ProjectionCenter(cam_from_world));
    cameras.rotations.push_back(placed.world_from_model.rotation *
                                cam_from_world.rotation.inverse());
    cameras.frames.push_back(static_cast<int>(id) - 1);
  }
  return cameras;
}

// Up on the page: against the cameras' mean y axis (image rows run down).
Eigen::Vector3d SceneUp(const std::vector<io::SceneCameras>& cameras) {
  Eigen::Vector3d down = Eigen::Vector3d::Zero();
  for (const io::SceneCameras& set : cameras) {
    for (const Eigen::Quaterniond& q : set.rotations) down += q * Eigen::Vector3d::UnitY();
  }
  return -down;
}

// The similarity that draws `model` in the truth's world: the rotation of the evaluation's
// orientation alignment (on a straight path, KITTI's, the centres alone leave the roll about the
// path free, and the view would show the model rolled), then scale and shift fitted to the
// centres with that rotation held.
Sim3d ViewAlignment(const TrajectoryEvaluation& evaluation, const Reconstruction& model,
                    const FrameGroundTruth& truth) {
  std::vector<Eigen::Vector3d> rotated, centers;
  for (int frame : evaluation.frames) {
    const image_t id = static_cast<image_t>(frame) + 1;
    if (!model.ExistsImage(id) || !truth.cams_from_world[frame]) continue;
    rotated.push_back(evaluation.gt_from_estimated_rotation *
                      ProjectionCenter(model.image(id).cam_from_world));
    centers.push_back(ProjectionCenter(*truth.cams_from_world[frame]));
  }
  if (rotated.size() < 2) return evaluation.gt_from_estimated;
  Eigen::Vector3d mean_rotated = Eigen::Vector3d::Zero(), mean_center = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < rotated.size(); ++i) {
    mean_rotated += rotated[i];
    mean_center += centers[i];
  }
  mean_rotated /= static_cast<double>(rotated.size());
  mean_center /= static_cast<double>(centers.size());
  double cross = 0.0, spread = 0.0;
  for (size_t i = 0; i < rotated.size(); ++i) {
    cross += (rotated[i] - mean_rotated).dot(centers[i] - mean_center);
    spread += (rotated[i] - mean_rotated).squaredNorm();
  }
  if (spread <= 0.0 || cross <= 0.0) return evaluation.gt_from_estimated;
  Sim3d alignment;
  alignment.scale = cross / spread;
  alignment.rotation = evaluation.gt_from_estimated_rotation;
  alignment.translation = mean_center - alignment.scale * mean_rotated;
  return alignment;
}

}  // namespace

PlacedModels PlaceModels(const DetectorRun& run, const RunInputs& inputs) {
  PlacedModels placed;
  const std::vector<const Reconstruction*> models = RunModels(run);
  placed.aligned = run.evaluation.has_value();
  placed.unit = placed.aligned ? TruthUnit(inputs) : "model units";
  for (size_t m = 0; m < models.size(); ++m) {
    PlacedModel model{static_cast<int>(m), models[m], Sim3d(), Sim3d()};
    if (placed.aligned && m == 0) {
      model.world_from_model = ViewAlignment(*run.evaluation, *models[m], *inputs.ground_truth);
      model.centers_from_model = run.evaluation->gt_from_estimated;
    } else if (placed.aligned) {
      // Another model has its own alignment to the truth (the run's evaluation is the largest's).
      const auto evaluation =
          EvaluateTrajectory(RegisteredPosesByName(*models[m], inputs.sequence->FrameNames()),
                             inputs.ground_truth->cams_from_world);
      if (!evaluation) {
        placed.note += ModelName(model.index) +
                       " is left out: too few of its frames have ground "
                       "truth to place it. ";
        continue;
      }
      model.world_from_model = ViewAlignment(*evaluation, *models[m], *inputs.ground_truth);
      model.centers_from_model = evaluation->gt_from_estimated;
    } else if (m > 0) {
      placed.note += ModelName(model.index) +
                     " is left out: without ground truth each model "
                     "has its own frame and scale. ";
      continue;
    }
    placed.models.push_back(model);
  }
  return placed;
}

io::Scene RunScene(const PlacedModels& placed, const RunInputs& inputs, size_t max_points) {
  io::Scene scene;
  scene.title = "3-D view";
  scene.max_points = max_points;
  scene.unit = placed.unit;
  for (const PlacedModel& model : placed.models) {
    for (const auto& [id, point] : model.model->points3D()) {
      scene.points.push_back(model.world_from_model * point.xyz);
      scene.colors.push_back(point.color);
    }
    const Camera& camera = model.model->cameras().empty() ? inputs.camera.camera
                                                          : model.model->cameras().begin()->second;
    scene.cameras.push_back(PlacedCameras(model, camera));
  }
  if (placed.aligned) {
    io::ScenePath truth{"ground truth", kTruthColor, {}, false};
    for (size_t f = 0; f < inputs.sequence->NumFrames(); ++f) {
      truth.points.push_back(inputs.ground_truth->cams_from_world[f]
                                 ? TrueCenter(inputs, static_cast<int>(f))
                                 : Eigen::Vector3d::Constant(kNaN));
    }
    scene.paths.push_back(truth);
  }
  scene.up = SceneUp(scene.cameras);
  scene.note = (placed.aligned ? "Models are drawn in the ground truth's world (Sim(3)-aligned). "
                               : "The model is drawn in its own frame. ") +
               placed.note;
  return scene;
}

io::TopView RunTopView(const PlacedModels& placed, const DetectorRun& run,
                       const RunInputs& inputs) {
  const size_t num_frames = inputs.sequence->NumFrames();
  std::vector<Eigen::Vector3d> all_centers;
  std::vector<std::vector<std::optional<Eigen::Vector3d>>> model_centers;
  for (const PlacedModel& model : placed.models) {
    std::vector<std::optional<Eigen::Vector3d>> centers(num_frames);
    for (const image_t id : model.model->RegisteredImageIds()) {
      const size_t f = id - 1;
      if (f >= num_frames) continue;
      centers[f] =
          model.centers_from_model * ProjectionCenter(model.model->image(id).cam_from_world);
      all_centers.push_back(*centers[f]);
    }
    model_centers.push_back(centers);
  }
  const PlotPlane plane = inputs.plot_plane_from_estimate && !placed.aligned
                              ? PlotPlaneFromCenters(all_centers)
                              : inputs.plot_plane;
  const auto on_plane = [&](const std::optional<Eigen::Vector3d>& p) -> io::TopViewPoint {
    if (!p) return {kNaN, kNaN};
    return {plane.right.dot(*p), plane.up.dot(*p)};
  };
  io::TopView view;
  view.title = "Top view of the camera path";
  view.right_label = plane.right_label;
  view.up_label = plane.up_label;
  view.unit = placed.unit;
  if (placed.aligned) {
    io::TopViewSeries truth{"ground truth", kTruthColor, {}, true, 5.0, "none"};
    for (size_t f = 0; f < num_frames; ++f) {
      truth.points.push_back(inputs.ground_truth->cams_from_world[f]
                                 ? on_plane(TrueCenter(inputs, static_cast<int>(f)))
                                 : io::TopViewPoint{kNaN, kNaN});
    }
    view.series.push_back(truth);
  }
  for (size_t m = 0; m < placed.models.size(); ++m) {
    io::TopViewSeries series{
        ModelName(placed.models[m].index) + (placed.aligned ? ", Sim(3)-aligned" : ""),
        ModelColor(placed.models[m].index),
        {},
        true,
        1.6,
        "dot"};
    for (const auto& center : model_centers[m]) series.points.push_back(on_plane(center));
    view.series.push_back(series);
  }
  if (placed.aligned && !placed.models.empty()) view.links = {0, 1};
  const std::vector<int> unregistered = UnregisteredWithTruth(inputs, run);
  if (!unregistered.empty()) {
    io::TopViewSeries missing{
        "not registered (true position)", kUnregisteredColor, {}, false, 4.0, "cross"};
    missing.points.assign(num_frames, {kNaN, kNaN});
    for (int f : unregistered) missing.points[f] = on_plane(TrueCenter(inputs, f));
    view.series.push_back(missing);
  }
  if (run.evaluation) {
    char words[200];
    std::snprintf(words, sizeof(words),
                  "ATE RMSE %.4g %s (%.3g %% of the %.4g %s path) over %zu frames; the ring marks "
                  "the first frame.",
                  run.evaluation->ate_rmse, placed.unit.c_str(),
                  100.0 * run.evaluation->ate_fraction_of_path, run.evaluation->path_length,
                  placed.unit.c_str(), run.evaluation->frames.size());
    view.note = words;
  } else {
    view.note =
        "Without ground truth the scale is the model's own (arbitrary); the ring marks "
        "the first frame.";
  }
  return view;
}

std::vector<io::LineChart> RunErrorCharts(const DetectorRun& run, const RunInputs& inputs) {
  if (!run.evaluation) return {};
  const TrajectoryEvaluation& evaluation = *run.evaluation;
  const std::string unit = TruthUnit(inputs);
  std::vector<double> frames(evaluation.frames.begin(), evaluation.frames.end());
  std::vector<double> unregistered;
  for (int f : run.report.unregistered_frames) unregistered.push_back(f);
  io::LineChart position;
  position.title = "Position error of each camera";
  position.x_label = "frame";
  position.y_label = "position error (" + unit + ")";
  position.series.push_back({ModelName(0), ModelColor(0), frames, evaluation.position_errors});
  position.note =
      "Distance from each camera centre to the true one after the Sim(3) alignment "
      "of all centres (Umeyama); ATE RMSE is the root mean square of these.";
  io::LineChart rotation;
  rotation.title = "Rotation error of each camera";
  rotation.x_label = "frame";
  rotation.y_label = "rotation error (deg)";
  rotation.series.push_back({ModelName(0), ModelColor(0), frames, evaluation.rotation_errors_deg});
  rotation.note =
      "Angle between each camera's orientation and the true one after the mean "
      "rotation between the two worlds is removed.";
  if (!unregistered.empty()) {
    for (io::LineChart* chart : {&position, &rotation}) {
      chart->marks.push_back({"not registered", kUnregisteredColor, unregistered});
    }
  }
  return {position, rotation};
}

}  // namespace comic::sfm
