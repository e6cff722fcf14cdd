#include "sfm/loop_closure.h"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>

#include "io/core/error.h"
#include "sfm/bundle_adjuster.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {

void LoopClosureOptions::Check() const {
  COMIC_CHECK(node_stride >= 1 && max_descriptors_per_node >= 1, kInvalidArgument,
              "loop closure: node_stride and max_descriptors_per_node must be >= 1, got "
                  << node_stride << ", " << max_descriptors_per_node);
  COMIC_CHECK(min_inliers >= 3 && ransac_iterations >= 1 && max_shared_tracks >= 0,
              kInvalidArgument,
              "loop closure: min_inliers >= 3, ransac_iterations >= 1, max_shared_tracks >= 0 "
              "needed, got "
                  << min_inliers << ", " << ransac_iterations << ", " << max_shared_tracks);
  COMIC_CHECK(max_move_per_path > 0 && max_scale_change >= 1, kInvalidArgument,
              "loop closure: max_move_per_path must be > 0 and max_scale_change >= 1, got "
                  << max_move_per_path << ", " << max_scale_change);
  COMIC_CHECK(max_reprojection_error_px > 0 && loop_edge_weight > 0, kInvalidArgument,
              "loop closure: max_reprojection_error_px and loop_edge_weight must be > 0, got "
                  << max_reprojection_error_px << ", " << loop_edge_weight);
  COMIC_CHECK(
      min_agreeing_model_links >= 1, kInvalidArgument,
      "loop closure: min_agreeing_model_links must be >= 1, got " << min_agreeing_model_links);
  detection.Check();
  matching.Check();
  pose_graph.Check();
}

namespace {

// A keyframe's features with a 3-D point: their indices and descriptors (at most `limit`, in
// feature order, which is the detector's strongest-first order).
struct MappedFeatures {
  std::vector<point2D_t> point2D_idxs;
  cv::Mat descriptors;
};

MappedFeatures CollectMappedFeatures(const frontend::FeatureTracks& tracks,
                                     const Reconstruction& model, image_t image_id, int limit) {
  MappedFeatures mapped;
  const Image& image = model.image(image_id);
  const cv::Mat& all = tracks.descriptors[IncrementalMapper::FrameOfImageId(image_id)];
  for (point2D_t idx = 0; idx < image.points2D.size(); ++idx) {
    if (!image.points2D[idx].HasPoint3D()) continue;
    if (static_cast<int>(mapped.point2D_idxs.size()) >= limit) break;
    mapped.point2D_idxs.push_back(idx);
    mapped.descriptors.push_back(all.row(static_cast<int>(idx)));
  }
  return mapped;
}

// One match between the mapped features of the query (q) and the earlier frame (m).
struct LoopMatch {
  point2D_t q_idx = 0;
  point2D_t m_idx = 0;
  Eigen::Vector3d q_xyz;
  Eigen::Vector3d m_xyz;
};

struct Verification {
  LoopClosureEdge edge;
  Sim3d m_from_q;  // X_m ≈ m_from_q · X_q
  std::vector<LoopMatch> inliers;
};

bool ProjectsNear(const Reconstruction& model, image_t image_id, const Eigen::Vector3d& xyz,
                  point2D_t idx, double max_error_px) {
  const Image& image = model.image(image_id);
  const auto projection = ProjectPoint(model.camera(image.camera_id), image.cam_from_world, xyz);
  return projection && (*projection - image.points2D[idx].xy).norm() <= max_error_px;
}

// The two frames of a candidate and the models holding them (one model for a loop, two for a
// link between models).
struct FramePair {
  const Reconstruction* query_model = nullptr;
  image_t q = 0;
  const Reconstruction* match_model = nullptr;
  image_t m = 0;
};

std::vector<char> Agreeing(const FramePair& pair, const Sim3d& m_from_q,
                           const std::vector<LoopMatch>& matches, double max_error_px) {
  const Sim3d q_from_m = InverseSim3(m_from_q);
  std::vector<char> agree(matches.size(), 0);
  for (size_t k = 0; k < matches.size(); ++k) {
    agree[k] = ProjectsNear(*pair.match_model, pair.m, m_from_q * matches[k].q_xyz,
                            matches[k].m_idx, max_error_px) &&
               ProjectsNear(*pair.query_model, pair.q, q_from_m * matches[k].m_xyz,
                            matches[k].q_idx, max_error_px);
  }
  return agree;
}

std::optional<Sim3d> FitOn(const std::vector<LoopMatch>& matches, const std::vector<char>& use) {
  std::vector<Eigen::Vector3d> src, dst;
  for (size_t k = 0; k < matches.size(); ++k) {
    if (!use[k]) continue;
    src.push_back(matches[k].q_xyz);
    dst.push_back(matches[k].m_xyz);
  }
  return EstimateSim3dUmeyama(src, dst);
}

int Count(const std::vector<char>& flags) {
  return static_cast<int>(std::count(flags.begin(), flags.end(), 1));
}

// RANSAC over triples with a seed of the pair (the same answer on every run), then a refit on
// the agreeing matches.
std::optional<Verification> Verify(const frontend::FeatureTracks& tracks,
                                   const LoopClosureOptions& options, const FramePair& pair) {
  const int limit = std::numeric_limits<int>::max();
  const image_t q = pair.q;
  const image_t m = pair.m;
  const MappedFeatures query = CollectMappedFeatures(tracks, *pair.query_model, q, limit);
  const MappedFeatures earlier = CollectMappedFeatures(tracks, *pair.match_model, m, limit);
  if (query.descriptors.empty() || earlier.descriptors.empty()) return std::nullopt;
  std::vector<LoopMatch> matches;
  for (const frontend::PatchMatch& match :
       frontend::MatchDescriptors(query.descriptors, earlier.descriptors, options.matching)) {
    LoopMatch loop_match;
    loop_match.q_idx = query.point2D_idxs[match.index1];
    loop_match.m_idx = earlier.point2D_idxs[match.index2];
    loop_match.q_xyz =
        pair.query_model->point3D(pair.query_model->image(q).points2D[loop_match.q_idx].point3D_id)
            .xyz;
    loop_match.m_xyz =
        pair.match_model->point3D(pair.match_model->image(m).points2D[loop_match.m_idx].point3D_id)
            .xyz;
    matches.push_back(loop_match);
  }
  const int n = static_cast<int>(matches.size());
  if (n < options.min_inliers) return std::nullopt;
  std::mt19937 rng(static_cast<uint32_t>(q) * 7919u + static_cast<uint32_t>(m));
  std::vector<char> best;
  int best_count = 0;
  for (int it = 0; it < options.ransac_iterations; ++it) {
    const int a = static_cast<int>(rng() % n);
    const int b = static_cast<int>(rng() % n);
    const int c = static_cast<int>(rng() % n);
    if (a == b || b == c || a == c) continue;
    std::vector<char> sample(matches.size(), 0);
    sample[a] = sample[b] = sample[c] = 1;
    const std::optional<Sim3d> model_from_sample = FitOn(matches, sample);
    if (!model_from_sample || model_from_sample->scale <= 0) continue;
    std::vector<char> agree =
        Agreeing(pair, *model_from_sample, matches, options.max_reprojection_error_px);
    const int count = Count(agree);
    if (count > best_count) {
      best_count = count;
      best = std::move(agree);
    }
  }
  if (best_count < options.min_inliers) return std::nullopt;
  const std::optional<Sim3d> refit = FitOn(matches, best);
  if (!refit || refit->scale <= 0) return std::nullopt;
  const std::vector<char> agree =
      Agreeing(pair, *refit, matches, options.max_reprojection_error_px);
  if (Count(agree) < options.min_inliers) return std::nullopt;
  Verification verification;
  verification.m_from_q = *refit;
  for (size_t k = 0; k < matches.size(); ++k) {
    if (agree[k]) verification.inliers.push_back(matches[k]);
  }
  verification.edge.query_frame = IncrementalMapper::FrameOfImageId(q);
  verification.edge.match_frame = IncrementalMapper::FrameOfImageId(m);
  verification.edge.num_matches = n;
  verification.edge.num_inliers = static_cast<int>(verification.inliers.size());
  verification.edge.scale = refit->scale;
  return verification;
}

// The appearance search's nodes: every node_stride-th registered keyframe with mapped features.
std::vector<image_t> Nodes(const LoopClosureOptions& options, const IncrementalMapper& mapper) {
  std::vector<image_t> keyframes;
  const Reconstruction& model = mapper.reconstruction();
  for (image_t image_id : model.RegisteredImageIds()) {
    if (mapper.IsKeyframe(image_id) && model.image(image_id).NumPoints3D() > 0) {
      keyframes.push_back(image_id);
    }
  }
  std::vector<image_t> nodes;
  for (size_t k = 0; k < keyframes.size(); k += options.node_stride) nodes.push_back(keyframes[k]);
  return nodes;
}

// The pose graph over every registered frame: consecutive frames (their present relative poses)
// and the loops (the query posed where the similarity puts it against the earlier frame). The
// first frame of the initial pair stays, as in the bundle adjustments.
std::map<image_t, Sim3d> CorrectedPoses(const LoopClosureOptions& options,
                                        const IncrementalMapper& mapper,
                                        const std::vector<Verification>& loops,
                                        PoseGraphSummary* summary) {
  const Reconstruction& model = mapper.reconstruction();
  const std::vector<image_t> frames = model.RegisteredImageIds();
  std::map<image_t, int> node_of;
  std::vector<Sim3d> poses;
  for (image_t image_id : frames) {
    node_of[image_id] = static_cast<int>(poses.size());
    poses.push_back(Sim3FromRigid(model.image(image_id).cam_from_world));
  }
  std::vector<PoseGraphEdge> edges;
  for (size_t k = 1; k < poses.size(); ++k) {
    PoseGraphEdge edge;
    edge.i = static_cast<int>(k) - 1;
    edge.j = static_cast<int>(k);
    edge.j_from_i = ComposeSim3(poses[k], InverseSim3(poses[k - 1]));
    edges.push_back(edge);
  }
  for (const Verification& loop : loops) {
    const image_t q = IncrementalMapper::ImageIdOfFrame(loop.edge.query_frame);
    const image_t m = IncrementalMapper::ImageIdOfFrame(loop.edge.match_frame);
    // P'_q = P_q ∘ S⁻¹ sees X_m where P_q saw X_q.
    const Sim3d corrected_q = ComposeSim3(poses[node_of.at(q)], InverseSim3(loop.m_from_q));
    PoseGraphEdge edge;
    edge.i = node_of.at(m);
    edge.j = node_of.at(q);
    edge.j_from_i = ComposeSim3(corrected_q, InverseSim3(poses[node_of.at(m)]));
    edge.weight = options.loop_edge_weight;
    edges.push_back(edge);
  }
  const image_t gauge =
      mapper.registration_order().empty() ? frames.front() : mapper.registration_order().front();
  *summary = OptimizePoseGraph(options.pose_graph, edges, {node_of.at(gauge)}, &poses);
  std::map<image_t, Sim3d> corrected;
  for (image_t image_id : frames) corrected[image_id] = poses[node_of.at(image_id)];
  return corrected;
}

Eigen::Vector3d SimCenter(const Sim3d& cam_from_world) {
  return -(cam_from_world.rotation.conjugate() * cam_from_world.translation) / cam_from_world.scale;
}

// The length of the path through the registered frames' camera centres, in frame order, up to
// each frame.
std::map<int, double> PathLengthByFrame(const Reconstruction& model) {
  std::map<int, Eigen::Vector3d> centers;
  for (image_t image_id : model.RegisteredImageIds()) {
    centers[IncrementalMapper::FrameOfImageId(image_id)] =
        ProjectionCenter(model.image(image_id).cam_from_world);
  }
  std::map<int, double> path;
  const Eigen::Vector3d* previous = nullptr;
  double length = 0.0;
  for (const auto& [frame, center] : centers) {
    if (previous != nullptr) length += (center - *previous).norm();
    path[frame] = length;
    previous = &center;
  }
  return path;
}

// Fills the loop's path and move, and says whether the odometry allows it (see the header).
bool ConsistentWithOdometry(const LoopClosureOptions& options, const Reconstruction& model,
                            const std::map<int, double>& path, Verification* loop) {
  LoopClosureEdge& edge = loop->edge;
  const Eigen::Vector3d center = ProjectionCenter(
      model.image(IncrementalMapper::ImageIdOfFrame(edge.query_frame)).cam_from_world);
  // P'_q = P_q ∘ S⁻¹ has its centre at S(C_q).
  edge.loop_move = (loop->m_from_q * center - center).norm();
  edge.path_length = std::abs(path.at(edge.query_frame) - path.at(edge.match_frame));
  return edge.loop_move <= options.max_move_per_path * edge.path_length &&
         edge.scale <= options.max_scale_change && edge.scale * options.max_scale_change >= 1.0;
}

// Every node_stride-th registered frame of `model` with mapped features (the frames outside
// the map have none), for the appearance search between models.
std::vector<image_t> ModelNodes(const LoopClosureOptions& options, const Reconstruction& model) {
  std::vector<image_t> mapped;
  for (image_t image_id : model.RegisteredImageIds()) {
    if (model.image(image_id).NumPoints3D() > 0) mapped.push_back(image_id);
  }
  std::vector<image_t> nodes;
  for (size_t k = 0; k < mapped.size(); k += options.node_stride) nodes.push_back(mapped[k]);
  return nodes;
}

// How many of `other`'s inliers the similarity of `one` also explains.
int NumExplained(const Verification& one, const FramePair& other_pair, const Verification& other,
                 double max_error_px) {
  return Count(Agreeing(other_pair, one.m_from_q, other.inliers, max_error_px));
}

}  // namespace

ModelLinks LinkModelsByAppearance(const frontend::FeatureTracks& tracks,
                                  const LoopClosureOptions& options, const Reconstruction& current,
                                  const Reconstruction& earlier) {
  options.Check();
  COMIC_CHECK(tracks.HasDescriptors(), kInvalidArgument,
              "linking models: the tracks have no descriptors");
  ModelLinks result;
  // Stage 1: candidates by appearance over the nodes of both models in frame order; only pairs
  // across the two models compete.
  std::vector<std::pair<int, const Reconstruction*>> nodes;  // (frame, model), frame order
  for (const Reconstruction* model : {&current, &earlier}) {
    for (image_t image_id : ModelNodes(options, *model)) {
      nodes.emplace_back(IncrementalMapper::FrameOfImageId(image_id), model);
    }
  }
  std::sort(nodes.begin(), nodes.end());
  for (size_t k = 1; k < nodes.size(); ++k) {
    // Models of one run hold disjoint frames; a frame in both is linked by MergeModel already.
    if (nodes[k].first == nodes[k - 1].first) return result;
  }
  std::vector<cv::Mat> node_descriptors;
  std::vector<int> node_frames;
  for (const auto& [frame, model] : nodes) {
    node_descriptors.push_back(CollectMappedFeatures(tracks, *model,
                                                     IncrementalMapper::ImageIdOfFrame(frame),
                                                     options.max_descriptors_per_node)
                                   .descriptors);
    node_frames.push_back(frame);
  }
  const RevisitPrior across = [&](int query, int match) {
    return nodes[query].second != nodes[match].second;
  };
  const std::vector<LoopCandidate> candidates =
      nodes.size() >= 2
          ? DetectLoopCandidates(node_descriptors, node_frames, options.detection, across)
          : std::vector<LoopCandidate>();
  result.num_candidates = static_cast<int>(candidates.size());

  // Stage 2: each candidate verified as a loop is, oriented current -> earlier (X_earlier ≈
  // S X_current), whichever of its frames came first.
  std::vector<FramePair> pairs;
  std::vector<Verification> verified;
  for (const LoopCandidate& candidate : candidates) {
    int c = candidate.query;
    int e = candidate.match;
    if (nodes[c].second != &current) std::swap(c, e);
    const FramePair pair{&current, IncrementalMapper::ImageIdOfFrame(nodes[c].first), &earlier,
                         IncrementalMapper::ImageIdOfFrame(nodes[e].first)};
    std::optional<Verification> verification = Verify(tracks, options, pair);
    if (!verification) continue;
    pairs.push_back(pair);
    verified.push_back(std::move(*verification));
  }
  result.num_verified = static_cast<int>(verified.size());

  // Stage 3: the largest group of verified pairs that one similarity explains (each explaining
  // at least half of the others' inliers); a single look-alike on a repeated texture is a
  // consistent similarity too, so one pair alone links nothing.
  std::vector<size_t> best_group;
  for (size_t i = 0; i < verified.size(); ++i) {
    std::vector<size_t> group;
    for (size_t j = 0; j < verified.size(); ++j) {
      const int explained =
          NumExplained(verified[i], pairs[j], verified[j], options.max_reprojection_error_px);
      if (2 * explained >= static_cast<int>(verified[j].inliers.size())) group.push_back(j);
    }
    if (group.size() > best_group.size()) best_group = std::move(group);
  }
  result.num_agreeing = static_cast<int>(best_group.size());
  if (result.num_agreeing < options.min_agreeing_model_links) return result;
  for (size_t j : best_group) {
    for (const LoopMatch& match : verified[j].inliers) {
      result.links.push_back({pairs[j].q, match.q_idx, pairs[j].m, match.m_idx});
    }
  }
  return result;
}

LoopClosureSummary CloseLoops(const frontend::FeatureTracks& tracks,
                              const LoopClosureOptions& options, IncrementalMapper* mapper) {
  options.Check();
  COMIC_CHECK(mapper != nullptr, kInvalidArgument, "loop closure: mapper is null");
  COMIC_CHECK(tracks.HasDescriptors(), kInvalidArgument,
              "loop closure: the tracks have no descriptors");
  const double cpu_start = ProcessCpuSeconds();
  LoopClosureSummary summary;
  const Reconstruction& model = mapper->reconstruction();

  // Stage 1: candidates by appearance.
  const std::vector<image_t> nodes = Nodes(options, *mapper);
  summary.num_nodes = static_cast<int>(nodes.size());
  std::vector<cv::Mat> node_descriptors;
  std::vector<int> node_frames;
  for (image_t image_id : nodes) {
    node_descriptors.push_back(
        CollectMappedFeatures(tracks, model, image_id, options.max_descriptors_per_node)
            .descriptors);
    node_frames.push_back(IncrementalMapper::FrameOfImageId(image_id));
  }
  const std::map<int, double> path = PathLengthByFrame(model);
  RevisitPrior near_by_odometry;
  if (options.odometry_prior) {
    std::vector<Eigen::Vector3d> node_centers;
    for (image_t image_id : nodes) {
      node_centers.push_back(ProjectionCenter(model.image(image_id).cam_from_world));
    }
    near_by_odometry = [&, node_centers](int query, int match) {
      const double distance = (node_centers[query] - node_centers[match]).norm();
      const bool near =
          distance <= options.max_move_per_path *
                          std::abs(path.at(node_frames[query]) - path.at(node_frames[match]));
      summary.num_ruled_out_by_odometry += !near;
      return near;
    };
  }
  const std::vector<LoopCandidate> candidates =
      nodes.size() >= 2
          ? DetectLoopCandidates(node_descriptors, node_frames, options.detection, near_by_odometry)
          : std::vector<LoopCandidate>();
  summary.num_candidates = static_cast<int>(candidates.size());

  // Stage 2: geometric verification of each candidate the tracks do not already link, then
  // consistency with the odometry.
  std::vector<Verification> loops;
  for (const LoopCandidate& candidate : candidates) {
    const image_t q = nodes[candidate.query];
    const image_t m = nodes[candidate.match];
    // Tracks, not points: after a merge by appearance (LinkModelsByAppearance) the two sides of
    // the seam share the linked points but no track, and their loops are still to close.
    if (mapper->NumSharedTracks(IncrementalMapper::FrameOfImageId(q),
                                IncrementalMapper::FrameOfImageId(m)) >=
        static_cast<size_t>(options.max_shared_tracks)) {
      continue;
    }
    std::optional<Verification> verified = Verify(tracks, options, {&model, q, &model, m});
    if (!verified) continue;
    ++summary.num_verified;
    verified->edge.similarity = candidate.similarity;
    if (ConsistentWithOdometry(options, model, path, &*verified)) {
      loops.push_back(std::move(*verified));
    } else {
      summary.rejected.push_back(verified->edge);
    }
  }
  if (loops.empty()) {
    summary.cpu_time_s = ProcessCpuSeconds() - cpu_start;
    return summary;
  }

  // Stage 3: the pose graph spreads the loops' drift over the path; the points follow.
  const std::map<image_t, Sim3d> corrected =
      CorrectedPoses(options, *mapper, loops, &summary.pose_graph);
  std::map<image_t, Eigen::Vector3d> centers_before;
  for (const auto& [image_id, pose] : corrected) {
    centers_before[image_id] = ProjectionCenter(model.image(image_id).cam_from_world);
    summary.max_correction =
        std::max(summary.max_correction, (SimCenter(pose) - centers_before[image_id]).norm());
  }
  mapper->CorrectPoses(corrected);

  // Stage 4: the points at both ends of each loop become one.
  std::vector<IncrementalMapper::FeatureLink>& links = summary.links;
  for (Verification& loop : loops) {
    const image_t q = IncrementalMapper::ImageIdOfFrame(loop.edge.query_frame);
    const image_t m = IncrementalMapper::ImageIdOfFrame(loop.edge.match_frame);
    loop.edge.correction =
        (ProjectionCenter(model.image(q).cam_from_world) - centers_before.at(q)).norm();
    for (const LoopMatch& match : loop.inliers) links.push_back({m, match.m_idx, q, match.q_idx});
    summary.loops.push_back(loop.edge);
  }
  summary.num_points_fused = mapper->FuseLinkedPoints(links, /*keep_unexplained=*/true);
  summary.cpu_time_s = ProcessCpuSeconds() - cpu_start;
  return summary;
}

}  // namespace comic::sfm
