// The Sim(3) pose graph: a loop of keyframes integrated from drifting relative motions (scale and
// heading drift, as monocular odometry has) is closed by one loop edge with the true relative
// motion; the end-to-start gap and the path's error fall, bit for bit on every run.
#include "sfm/pose_graph.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

// cam_from_world of n cameras on a circle of radius 10, each looking along the path.
std::vector<Sim3d> TrueLoop(int n) {
  std::vector<Sim3d> poses;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    const Eigen::Vector3d center(10.0 * std::cos(a), 0.0, 10.0 * std::sin(a));
    // World from camera: z along the tangent, y down.
    const Eigen::Vector3d z(-std::sin(a), 0.0, std::cos(a));
    const Eigen::Vector3d y(0.0, 1.0, 0.0);
    Eigen::Matrix3d world_from_cam;
    world_from_cam << y.cross(z), y, z;
    Sim3d pose;
    pose.rotation = Eigen::Quaterniond(world_from_cam.transpose());
    pose.translation = -(world_from_cam.transpose() * center);
    poses.push_back(pose);
  }
  return poses;
}

Eigen::Vector3d Center(const Sim3d& cam_from_world) {
  return -(cam_from_world.rotation.conjugate() * cam_from_world.translation) / cam_from_world.scale;
}

// Odometry with 1 % scale drift and 0.4° of extra yaw per step, integrated from the first pose.
struct DriftingOdometry {
  std::vector<PoseGraphEdge> edges;
  std::vector<Sim3d> integrated;
};

DriftingOdometry Integrate(const std::vector<Sim3d>& truth) {
  DriftingOdometry odometry;
  odometry.integrated.push_back(truth[0]);
  Sim3d drift;
  drift.scale = 1.01;
  drift.rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4 * M_PI / 180, Eigen::Vector3d::UnitY()));
  for (size_t k = 0; k + 1 < truth.size(); ++k) {
    PoseGraphEdge edge;
    edge.i = static_cast<int>(k);
    edge.j = static_cast<int>(k + 1);
    edge.j_from_i = ComposeSim3(drift, ComposeSim3(truth[k + 1], InverseSim3(truth[k])));
    odometry.integrated.push_back(ComposeSim3(edge.j_from_i, odometry.integrated.back()));
    odometry.edges.push_back(edge);
  }
  return odometry;
}

double EndToStartGap(const std::vector<Sim3d>& poses, const std::vector<Sim3d>& truth) {
  // The last camera's position relative to the first, against the truth's, in the first
  // camera's frame and scale-free (ratio to the true distance).
  const Eigen::Vector3d ours = Center(poses.back()) - Center(poses.front());
  const Eigen::Vector3d true_offset = Center(truth.back()) - Center(truth.front());
  return (ours - true_offset).norm() / true_offset.norm();
}

TEST(PoseGraph, GroupOperations) {
  Sim3d a;
  a.scale = 2.0;
  a.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  a.translation = {1, -2, 0.5};
  Sim3d b;
  b.scale = 0.7;
  b.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitY()));
  b.translation = {0.2, 0.1, 4};
  const Eigen::Vector3d x(0.7, -1.3, 2.2);
  EXPECT_TRUE((ComposeSim3(a, b) * x).isApprox(a * (b * x), 1e-12));
  EXPECT_TRUE((InverseSim3(a) * (a * x)).isApprox(x, 1e-12));
}

TEST(PoseGraph, LoopEdgeClosesTheDriftedLoop) {
  const std::vector<Sim3d> truth = TrueLoop(60);
  DriftingOdometry odometry = Integrate(truth);
  const double gap_before = EndToStartGap(odometry.integrated, truth);
  EXPECT_GT(gap_before, 0.5);  // the drift opens the loop wide

  std::vector<PoseGraphEdge> edges = odometry.edges;
  PoseGraphEdge loop;  // last -> first, measured exactly (a verified revisit)
  loop.i = 59;
  loop.j = 0;
  loop.j_from_i = ComposeSim3(truth[0], InverseSim3(truth[59]));
  edges.push_back(loop);
  std::vector<Sim3d> poses = odometry.integrated;
  const PoseGraphSummary summary = OptimizePoseGraph(PoseGraphOptions(), edges, {0}, &poses);
  EXPECT_LT(summary.final_cost, 0.1 * summary.initial_cost);
  const double gap_after = EndToStartGap(poses, truth);
  EXPECT_LT(gap_after, 0.2 * gap_before);
  EXPECT_LT(gap_after, 0.05);

  // The first node is the gauge; the same input gives the same bytes.
  EXPECT_EQ(poses[0].translation, truth[0].translation);
  std::vector<Sim3d> again = odometry.integrated;
  OptimizePoseGraph(PoseGraphOptions(), edges, {0}, &again);
  for (size_t k = 0; k < poses.size(); ++k) {
    EXPECT_EQ(poses[k].translation, again[k].translation);
    EXPECT_EQ(poses[k].rotation.coeffs(), again[k].rotation.coeffs());
    EXPECT_EQ(poses[k].scale, again[k].scale);
  }
}

TEST(PoseGraph, WithoutALoopEdgeTheOdometryStands) {
  const std::vector<Sim3d> truth = TrueLoop(20);
  const DriftingOdometry odometry = Integrate(truth);
  std::vector<Sim3d> poses = odometry.integrated;
  const PoseGraphSummary summary =
      OptimizePoseGraph(PoseGraphOptions(), odometry.edges, {0}, &poses);
  EXPECT_LT(summary.final_cost, 1e-12);
  for (size_t k = 0; k < poses.size(); ++k) {
    EXPECT_LT((Center(poses[k]) - Center(odometry.integrated[k])).norm(), 1e-6) << k;
  }
}

TEST(PoseGraph, RejectsBadGraphs) {
  std::vector<Sim3d> poses = TrueLoop(4);
  PoseGraphEdge edge;
  edge.i = 0;
  edge.j = 7;
  EXPECT_THROW(OptimizePoseGraph(PoseGraphOptions(), {edge}, {0}, &poses), Error);
  edge.j = 1;
  EXPECT_THROW(OptimizePoseGraph(PoseGraphOptions(), {edge}, {}, &poses), Error);
  edge.j_from_i.scale = 0.0;
  EXPECT_THROW(OptimizePoseGraph(PoseGraphOptions(), {edge}, {0}, &poses), Error);
  PoseGraphOptions options;
  options.rotation_weight = -1;
  EXPECT_THROW(OptimizePoseGraph(options, {}, {0}, &poses), Error);
}

}  // namespace
}  // namespace comic::sfm
