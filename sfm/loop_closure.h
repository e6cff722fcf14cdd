// Loop closure in a model: places the camera revisits are found by appearance
// (sfm/loop_detection.h, over the descriptors of the registered keyframes' mapped features),
// verified geometrically, and closed: a Sim(3) pose graph over every registered frame
// (sfm/pose_graph.h; consecutive frames and the verified loops) spreads the drift the loop
// reveals over the path, every point moves with its first observer, and the points seen at both
// ends of a loop become one where the corrected poses agree on them, so that the global
// adjustment that follows holds the loop closed (the caller fuses the rest after it: `links`).
// This is ORB-SLAM's loop closing (Mur-Artal & Tardós 2017, §VI), run once at the end of a
// model's growth, before its final adjustment: an offline mapper has every frame already.
//
// Verification of a candidate (query keyframe q, earlier keyframe m): the descriptors of the
// features of q and m that have 3-D points are matched (COLMAP's matching: nearest by angle,
// ratio test, cross check); the similarity S taking q's points onto m's (X_m ≈ S X_q: the drift
// between the two ends) is found by RANSAC over triples (Umeyama), a match agreeing when S X_q
// projects into m and S⁻¹ X_m into q within max_reprojection_error_px (ORB-SLAM's two-way test,
// free of the map's scale). Pairs whose frames already share points are not loops: the tracks
// link them.
//
// A verified loop must also be consistent with the odometry before it is closed, because
// geometry between two frames cannot tell a revisit from a second place that looks the same
// (perceptual aliasing: a repeated facade is a consistent similarity too). Drift grows with the
// path, so the move the loop asks of the query's camera (S applied to its centre) must be a
// small fraction of the path between the two frames, and the scale drift it reveals must be
// moderate; a look-alike elsewhere asks for a move as long as the way between the two places.
// Loops failing this are reported as rejected and leave the model as it is.
//
//   LoopClosureSummary s = CloseLoops(tracks, LoopClosureOptions(), &mapper);
//   // s.loops: the loops closed; mapper.reconstruction() corrected, ready for a global adjustment
#pragma once

#include <vector>

#include "frontend/matching/descriptor_matcher.h"
#include "frontend/matching/track.h"
#include "sfm/incremental_mapper.h"
#include "sfm/loop_detection.h"
#include "sfm/pose_graph.h"

namespace comic::sfm {

struct LoopClosureOptions {
  // Every node_stride-th registered keyframe (in frame order) is a node of the appearance
  // search, described by at most max_descriptors_per_node of its features with a 3-D point.
  int node_stride = 3;
  int max_descriptors_per_node = 600;
  LoopDetectionOptions detection;
  frontend::DescriptorMatchOptions matching;
  // A loop needs this many matches agreeing with one similarity.
  int min_inliers = 30;
  double max_reprojection_error_px = 4.0;
  int ransac_iterations = 400;
  // A candidate whose two frames already share this many tracks is not a loop (the tracks link
  // them; points would not do: after a merge by appearance the two sides share linked points).
  int max_shared_tracks = 10;
  PoseGraphOptions pose_graph;
  // Weight of a loop edge against a consecutive one.
  double loop_edge_weight = 1.0;
  // Consistency with the odometry: the loop may move the query's camera centre by at most this
  // fraction of the path between the two frames (drift of a few per cent of the path is what
  // incremental mapping accumulates; docs/long_video.md), and its similarity's scale must lie
  // within [1 / max_scale_change, max_scale_change].
  double max_move_per_path = 0.1;
  double max_scale_change = 1.8;
  // The same bound as a prior, before appearance: a keyframe's revisit candidates are only the
  // earlier keyframes whose camera centre lies within max_move_per_path of the path between
  // them. On a route of look-alike places the bag of words alone ranks far places above the true
  // revisit; with the prior the rendered loop drive's end verifies against its start, but those
  // similarities ask for moves 2-5x the drift and closing them made the model worse
  // (docs/long_video.md), so it is off until verification is stricter.
  bool odometry_prior = false;
  // Linking two models by appearance (LinkModelsByAppearance): the verified frame pairs one
  // similarity must explain before their matches link the models.
  int min_agreeing_model_links = 2;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct LoopClosureEdge {
  int query_frame = -1;     // the later frame
  int match_frame = -1;     // the earlier frame it revisits
  double similarity = 0.0;  // of their bags of words
  int num_matches = 0;      // descriptor matches between their mapped features
  int num_inliers = 0;      // of those, agreeing with the similarity
  double scale = 1.0;       // of the similarity: the scale drift between the two ends
  // The path between the two frames' camera centres through every registered frame between
  // them, and how far the similarity alone would move the query's centre (model units).
  double path_length = 0.0;
  double loop_move = 0.0;
  // How far the pose graph moved the query's camera centre (model units; 0 for a rejected loop).
  double correction = 0.0;
};

struct LoopClosureSummary {
  int num_nodes = 0;       // keyframes described
  int num_candidates = 0;  // appearance candidates
  int num_verified = 0;    // of those, verified geometrically
  // Keyframe pairs alike enough to be candidates but too far apart for the odometry
  // (odometry_prior): look-alike places ruled out before verification.
  int num_ruled_out_by_odometry = 0;
  // The verified loops consistent with the odometry, closed...
  std::vector<LoopClosureEdge> loops;
  // ... and those that are not (a move too long for their path, or a scale too far from 1).
  std::vector<LoopClosureEdge> rejected;
  // Points seen at both ends made one (the observations of the later point that the earlier
  // one's position explains move to it), now and again after the final adjustment.
  size_t num_points_fused = 0;
  // The verified matches as links (earlier frame first), fused again after the final adjustment
  // (IncrementalMapper::FuseLinkedPoints).
  std::vector<IncrementalMapper::FeatureLink> links;
  // The largest move of a camera centre by the pose graph (model units; 0 without a loop).
  double max_correction = 0.0;
  PoseGraphSummary pose_graph;
  double cpu_time_s = 0.0;
};

// Links between two models of one video that share no frame, track or seam: the camera came
// back to a place the earlier model holds after something broke the tracks (a blurred frame on
// the way back of the bag clip played forwards then backwards). The frames of the two models
// that look alike (the appearance search above, over both models' nodes, only pairs across
// them) are verified as loops are; the matches of the largest group of verified pairs that one
// similarity explains become links for IncrementalMapper::MergeModel (in `current` first). Fewer
// than min_agreeing_model_links agreeing pairs link nothing: one pair alone can be a look-alike.
struct ModelLinks {
  std::vector<IncrementalMapper::FeatureLink> links;
  int num_candidates = 0;  // appearance candidates across the two models
  int num_verified = 0;    // of those, verified geometrically
  int num_agreeing = 0;    // of those, in the largest group one similarity explains
};
ModelLinks LinkModelsByAppearance(const frontend::FeatureTracks& tracks,
                                  const LoopClosureOptions& options, const Reconstruction& current,
                                  const Reconstruction& earlier);

// Finds, verifies and closes the loops of the model `mapper` holds (see above); nothing changes
// when none is verified. `tracks` are the mapper's, with descriptors (frontend::FeatureTracks::
// descriptors). Throws comic::Error(kInvalidArgument) for tracks without descriptors or bad
// options.
LoopClosureSummary CloseLoops(const frontend::FeatureTracks& tracks,
                              const LoopClosureOptions& options, IncrementalMapper* mapper);

}  // namespace comic::sfm
