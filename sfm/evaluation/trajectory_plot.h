// A top view of camera trajectories as an image: the estimated centres (aligned into the
// ground-truth world by the Sim(3) of the evaluation) against the true ones, with equal scale on
// both axes, axes with ticks and a grid in the world's unit, a scale bar, the frames that were
// not registered marked where they truly were, a wrapped title and a legend.
//
//   const PlotPlane plane = PlotPlaneFromAxes(0, 2);  // x right, z up the page: KITTI's top view
//   cv::Mat image = RenderTrajectoryPlot(aligned_centers, true_centers, plane, {});
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace comic::sfm {

// The plane the centres are projected on: world directions drawn right and up the page.
struct PlotPlane {
  Eigen::Vector3d right = Eigen::Vector3d::UnitX();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  std::string right_label = "x";
  std::string up_label = "z";
};

// Two world axes (0 = x, 1 = y, 2 = z) drawn right and up, e.g. (0, 2) for the top view of a
// camera with y pointing down (KITTI).
PlotPlane PlotPlaneFromAxes(int right_axis, int up_axis);

// The plane of largest spread of `centers` (their two principal directions), for trajectories
// whose world has no known up direction (turntable rings). Falls back to x–z when fewer than
// three centres are given.
PlotPlane PlotPlaneFromCenters(const std::vector<Eigen::Vector3d>& centers);

struct TrajectoryPlotOptions {
  int width = 900;    // pixels
  int height = 900;   // pixels
  std::string title;  // wrapped to the width
  // The length unit of the centres: "m" with metric ground truth; "units" when the scale is the
  // model's own.
  std::string unit = "units";
  std::string note;  // a line under the legend, e.g. the ATE (may be empty)
  void Check() const;
};

// Draws per frame the estimated centre (red, joined in frame order), the true centre (green)
// and a grey line between the two; either may be missing for a frame: a frame with a true centre
// and no estimate (not registered) is an amber cross. With no true centres it draws the estimate
// alone and counts the frames without one in the legend. Deterministic.
cv::Mat RenderTrajectoryPlot(const std::vector<std::optional<Eigen::Vector3d>>& estimated_centers,
                             const std::vector<std::optional<Eigen::Vector3d>>& true_centers,
                             const PlotPlane& plane, const TrajectoryPlotOptions& options);

}  // namespace comic::sfm
