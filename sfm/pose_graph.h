// A Sim(3) pose graph on Ceres: keyframe poses adjusted so that the relative motions measured
// between them (consecutive keyframes, and loop closures found later) agree as well as they can.
// This is how ORB-SLAM closes a loop in monocular video (Strasdat et al., RSS 2010): the scale of a
// monocular map drifts along the path, so an edge measures a similarity, and the error a loop
// reveals is spread over the whole path before a global adjustment polishes the points.
//
//   std::vector<Sim3d> poses = ...;           // cam_from_world of each keyframe
//   std::vector<PoseGraphEdge> edges = ...;   // j_from_i measured, consecutive and loop
//   const PoseGraphSummary s = OptimizePoseGraph(PoseGraphOptions(), edges, {0}, &poses);
#pragma once

#include <set>
#include <string>
#include <vector>

#include "sfm/rigid3d.h"

namespace comic::sfm {

// A measured relative similarity between two nodes: poses[j] ≈ j_from_i * poses[i], poses being
// cam_from_world similarities.
struct PoseGraphEdge {
  int i = 0;
  int j = 0;
  Sim3d j_from_i;
  // Weight of the edge relative to the others (a loop edge verified by many points may weigh as a
  // consecutive one; a weak one less).
  double weight = 1.0;
};

struct PoseGraphOptions {
  // Relative weights of the residual's parts: translation (in the scene's units, per unit of
  // the measured baseline), rotation (radians) and log-scale.
  double translation_weight = 1.0;
  double rotation_weight = 1.0;
  double scale_weight = 1.0;
  // Keep every node's scale at 1 (an SE(3) graph: stereo or metric video).
  bool fix_scale = false;
  int max_num_iterations = 100;

  void Check() const;
};

struct PoseGraphSummary {
  bool converged = false;
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
};

// The composition and inverse of similarities (Sim3d in rigid3d.h maps points; these are the
// group operations the graph needs).
Sim3d ComposeSim3(const Sim3d& c_from_b, const Sim3d& b_from_a);
Sim3d InverseSim3(const Sim3d& b_from_a);
// A rigid pose as a similarity of scale 1, and back (the scale divides the translation out, so
// that the camera centre is kept: a node's position is what the graph moves).
Sim3d Sim3FromRigid(const Rigid3d& cam_from_world);

// Adjusts `poses` (cam_from_world of every node) to the edges; nodes in `fixed_nodes` stay
// (at least one: the gauge). Throws comic::Error on an edge naming a missing node, a non-positive
// scale or weight, or no fixed node. Runs Ceres on one thread (same result bit for bit).
PoseGraphSummary OptimizePoseGraph(const PoseGraphOptions& options,
                                   const std::vector<PoseGraphEdge>& edges,
                                   const std::set<int>& fixed_nodes, std::vector<Sim3d>* poses);

}  // namespace comic::sfm
