#include "sfm/incremental_mapper.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "io/core/error.h"
#include "sfm/similarity_ransac.h"

namespace comic::sfm {

void IncrementalMapper::Options::Check() const {
  planar_ambiguity.Check();
  COMIC_CHECK(init_min_num_matches >= 5, kInvalidArgument,
              "mapper init_min_num_matches must be >= 5, got " << init_min_num_matches);
  COMIC_CHECK(init_min_num_inliers >= 5, kInvalidArgument,
              "mapper init_min_num_inliers must be >= 5, got " << init_min_num_inliers);
  COMIC_CHECK(init_tri_angle_deg > 0 && init_tri_angle_deg < 90, kInvalidArgument,
              "mapper init_tri_angle_deg must be in (0, 90)");
  COMIC_CHECK(init_min_score >= 0, kInvalidArgument, "mapper init_min_score must be >= 0");
  COMIC_CHECK(init_num_anchors >= 1, kInvalidArgument, "mapper init_num_anchors must be >= 1");
  COMIC_CHECK(init_max_frame_gap >= 0, kInvalidArgument,
              "mapper init_max_frame_gap must be >= 0 (0: no limit)");
  COMIC_CHECK(init_linear_gap >= 1, kInvalidArgument, "mapper init_linear_gap must be >= 1");
  COMIC_CHECK(init_gap_growth > 1.0, kInvalidArgument, "mapper init_gap_growth must be > 1");
  COMIC_CHECK(init_anchor_spacing >= 1, kInvalidArgument,
              "mapper init_anchor_spacing must be >= 1");
  COMIC_CHECK(init_max_num_trials >= 1, kInvalidArgument,
              "mapper init_max_num_trials must be >= 1");
  COMIC_CHECK(init_trials_per_frame >= 0, kInvalidArgument,
              "mapper init_trials_per_frame must be >= 0");
  two_view.Check();
  absolute_pose.Check();
  triangulation.Check();
  COMIC_CHECK(complete_max_reprojection_error_px > 0, kInvalidArgument,
              "mapper complete_max_reprojection_error_px must be > 0");
  COMIC_CHECK(retriangulate_max_reprojection_error_px > 0, kInvalidArgument,
              "mapper retriangulate_max_reprojection_error_px must be > 0");
  COMIC_CHECK(filter_max_reprojection_error_px > 0, kInvalidArgument,
              "mapper filter_max_reprojection_error_px must be > 0");
  COMIC_CHECK(filter_min_tri_angle_deg >= 0, kInvalidArgument,
              "mapper filter_min_tri_angle_deg must be >= 0");
  COMIC_CHECK(merge_max_relative_distance > 0, kInvalidArgument,
              "mapper merge_max_relative_distance must be > 0");
  COMIC_CHECK(merge_min_num_inliers >= 3, kInvalidArgument,
              "mapper merge_min_num_inliers must be >= 3, got " << merge_min_num_inliers);
  COMIC_CHECK(merge_min_inlier_ratio >= 0 && merge_min_inlier_ratio <= 1, kInvalidArgument,
              "mapper merge_min_inlier_ratio must be in [0, 1]");
}

IncrementalMapper::IncrementalMapper(const frontend::FeatureTracks& tracks, const Camera& camera,
                                     const Options& options)
    : tracks_(&tracks), options_(options) {
  options_.Check();
  tracks.Check();
  camera.Check();
  camera_id_ = reconstruction_.AddCamera(camera);
  track_of_feature_.resize(tracks.NumFrames());
  best_failed_pose_inliers_.assign(tracks.NumFrames(), -1);
  for (size_t frame = 0; frame < tracks.NumFrames(); ++frame) {
    Image image;
    image.image_id = ImageIdOfFrame(static_cast<int>(frame));
    image.camera_id = camera_id_;
    if (!tracks.frame_names.empty()) {
      image.name = tracks.frame_names[frame];
    } else {
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%06zu", frame);
      image.name = name;
    }
    image.points2D.reserve(tracks.features[frame].size());
    for (const frontend::Feature& feature : tracks.features[frame]) {
      Point2D point2D;
      point2D.xy = Eigen::Vector2d(feature.x, feature.y);
      image.points2D.push_back(point2D);
    }
    reconstruction_.AddImage(std::move(image));
    track_of_feature_[frame].assign(tracks.features[frame].size(), -1);
  }
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : tracks.tracks[t].observations) {
      track_of_feature_[obs.frame][obs.feature] = static_cast<int>(t);
    }
  }
  track_num_linked_features_.assign(tracks.tracks.size(), 0);
  frame_num_tracks_with_points_.assign(tracks.NumFrames(), 0);
  track_touched_.assign(tracks.tracks.size(), 0);
  reconstruction_.RecordLinkChanges(true);  // the model has no point yet: the counts are all 0
}

namespace {

// An initial pair's parallax score: Σ over its inliers of min(angle / full_angle_deg, 1).
double ParallaxScore(const TwoViewGeometry& geometry, double full_angle_deg) {
  double score = 0.0;
  for (double angle : geometry.triangulation_angles_deg) {
    score += std::min(angle / full_angle_deg, 1.0);
  }
  return score;
}

// The frames (not excluded) ordered by tracked features, most first, ties by frame index.
std::vector<int> ByTrackedFeatures(const std::vector<int>& num_tracked,
                                   const std::set<image_t>& excluded) {
  std::vector<int> frames;
  for (int frame = 0; frame < static_cast<int>(num_tracked.size()); ++frame) {
    if (!excluded.count(IncrementalMapper::ImageIdOfFrame(frame))) frames.push_back(frame);
  }
  std::stable_sort(frames.begin(), frames.end(),
                   [&](int a, int b) { return num_tracked[a] > num_tracked[b]; });
  return frames;
}

// The initial pair search's first anchors: the `count` most tracked frames.
std::vector<int> MostTrackedFrames(const std::vector<int>& num_tracked,
                                   const std::set<image_t>& excluded, int count) {
  std::vector<int> frames = ByTrackedFeatures(num_tracked, excluded);
  if (static_cast<int>(frames.size()) > count) frames.resize(count);
  return frames;
}

// Anchors over the whole clip: the most tracked frame of every stretch of `spacing` frames, most
// tracked first.
std::vector<int> SpreadAnchors(const std::vector<int>& num_tracked,
                               const std::set<image_t>& excluded, int spacing) {
  std::vector<int> best_of_stretch((num_tracked.size() + spacing - 1) / spacing, -1);
  std::vector<int> anchors;
  for (int frame : ByTrackedFeatures(num_tracked, excluded)) {
    int& best = best_of_stretch[frame / spacing];
    if (best >= 0) continue;
    best = frame;
    anchors.push_back(frame);
  }
  return anchors;
}

// The next frame gap an anchor is paired at: one more up to init_linear_gap, then growing by
// init_gap_growth (the number of gaps tried grows with the logarithm of the clip's length).
int NextGap(int gap, const IncrementalMapper::Options& options) {
  if (gap < options.init_linear_gap) return gap + 1;
  return std::max(gap + 1, static_cast<int>(std::lround(gap * options.init_gap_growth)));
}

// MergeModel's point pairs: the points two models give to one physical point.
struct ModelPointPair {
  image_t image_id;           // a frame of this model observing it
  Eigen::Vector2d xy;         // the feature in that frame
  Eigen::Vector3d other_xyz;  // the point of the other model
  Eigen::Vector3d xyz;        // the point of this model
};

}  // namespace

std::optional<IncrementalMapper::InitialPair> IncrementalMapper::FindInitialPair(
    const std::set<image_t>& excluded) const {
  std::vector<InitialPair> pairs = FindInitialPairs(excluded);
  if (pairs.empty()) return std::nullopt;
  return std::move(pairs.front());
}

IncrementalMapper::InitialPairSearch IncrementalMapper::EvaluateInitialPair(
    int frame1, int frame2, const std::vector<int>& anchor_tracks, InitialPair* pair,
    double* measure) const {
  using Stage = InitialPairSearch::Stage;
  pair->image_id1 = ImageIdOfFrame(frame1);
  pair->image_id2 = ImageIdOfFrame(frame2);
  std::vector<Eigen::Vector2d> points1, points2;
  for (int t : anchor_tracks) {
    const int feature2 = tracks_->tracks[t].FeatureInFrame(frame2);
    if (feature2 < 0) continue;
    const int feature1 = tracks_->tracks[t].FeatureInFrame(frame1);
    pair->track_ids.push_back(t);
    pair->point2D_idxs1.push_back(static_cast<point2D_t>(feature1));
    pair->point2D_idxs2.push_back(static_cast<point2D_t>(feature2));
    const frontend::Feature& f1 = tracks_->features[frame1][feature1];
    const frontend::Feature& f2 = tracks_->features[frame2][feature2];
    points1.emplace_back(f1.x, f1.y);
    points2.emplace_back(f2.x, f2.y);
  }
  InitialPairSearch candidate;
  candidate.image_id1 = pair->image_id1;
  candidate.image_id2 = pair->image_id2;
  candidate.num_shared_tracks = static_cast<int>(pair->track_ids.size());
  *measure = candidate.num_shared_tracks;
  if (candidate.num_shared_tracks < options_.init_min_num_matches) {
    candidate.stage = Stage::kSharedTracks;
    return candidate;
  }
  const Camera& camera = reconstruction_.camera(camera_id_);
  pair->geometry =
      EstimateCalibratedTwoViewGeometry(camera, camera, points1, points2, options_.two_view);
  candidate.configuration = pair->geometry.configuration;
  candidate.num_inliers = pair->geometry.num_inliers;
  candidate.num_essential_inliers = pair->geometry.num_essential_inliers;
  candidate.num_homography_inliers = pair->geometry.num_homography_inliers;
  candidate.median_triangulation_angle_deg = pair->geometry.median_triangulation_angle_deg;
  const bool planar_with_parallax =
      options_.init_accept_planar &&
      pair->geometry.configuration == TwoViewConfiguration::kPlanarOrPanoramic &&
      pair->geometry.median_triangulation_angle_deg >= options_.init_tri_angle_deg;
  if (pair->geometry.configuration != TwoViewConfiguration::kCalibrated && !planar_with_parallax) {
    candidate.stage = Stage::kGeometry;
    // Closest to a general pose: the smallest share of inliers a homography explains; a
    // degenerate pair (too few inliers for any pose) comes after every such pair.
    const double homography_share = static_cast<double>(candidate.num_homography_inliers) /
                                    std::max(candidate.num_essential_inliers, 1);
    *measure = candidate.configuration == TwoViewConfiguration::kPlanarOrPanoramic
                   ? 1.0 - homography_share
                   : -1.0 + 1e-9 * candidate.num_essential_inliers;
    return candidate;
  }
  if (pair->geometry.num_inliers < options_.init_min_num_inliers) {
    candidate.stage = Stage::kInliers;
    *measure = candidate.num_inliers;
    return candidate;
  }
  const double score = ParallaxScore(pair->geometry, options_.init_tri_angle_deg);
  pair->score = score;
  candidate.score = score;
  candidate.stage = score >= options_.init_min_score ? Stage::kQualified : Stage::kParallax;
  *measure = score;
  if (candidate.stage == Stage::kQualified && options_.init_find_planar_alternative) {
    pair->planar_alternative =
        OtherPlanarPose(camera, camera, points1, points2, pair->geometry,
                        options_.two_view.max_error_px, options_.planar_ambiguity);
    // The alternative must qualify as the pair did: a pose whose points lie nearly at infinity
    // (little parallax) triangulates none, and would explain the third frames as turns alone.
    if (pair->planar_alternative &&
        (pair->planar_alternative->num_inliers < options_.init_min_num_inliers ||
         ParallaxScore(*pair->planar_alternative, options_.init_tri_angle_deg) <
             options_.init_min_score)) {
      pair->planar_alternative.reset();
    }
  }
  return candidate;
}

std::vector<IncrementalMapper::InitialPair> IncrementalMapper::FindInitialPairs(
    const std::set<image_t>& excluded, InitialPairSearch* search) const {
  using Stage = InitialPairSearch::Stage;
  InitialPairSearch seen;
  double seen_measure = -1.0;
  // Keeps `candidate` if it came closer than the pair kept so far (InitialPairSearch).
  const auto consider = [&](const InitialPairSearch& candidate, double measure) {
    if (candidate.stage > seen.stage || (candidate.stage == seen.stage && measure > seen_measure)) {
      const int verified = seen.num_pairs_verified, qualified = seen.num_pairs_qualified;
      seen = candidate;
      seen.num_pairs_verified = verified;
      seen.num_pairs_qualified = qualified;
      seen_measure = measure;
    }
  };
  std::vector<InitialPair> pairs;
  const int num_frames = static_cast<int>(tracks_->NumFrames());
  std::vector<int> num_tracked(num_frames, 0);
  for (const frontend::Track& track : tracks_->tracks) {
    if (track.Length() < 2) continue;
    for (const frontend::TrackObservation& obs : track.observations) ++num_tracked[obs.frame];
  }
  int num_trials = 0;
  const int max_num_trials =
      std::max(options_.init_max_num_trials, options_.init_trials_per_frame * num_frames);
  // Pairs `frame1` with the frames after it at growing gaps: parallax grows with the gap while
  // the shared tracks dwindle, so the score rises to a peak and falls again.
  const auto search_anchor = [&](int frame1) {
    std::vector<int> anchor_tracks;
    for (int t : track_of_feature_[frame1]) {
      if (t >= 0 && tracks_->tracks[t].Length() >= 2) anchor_tracks.push_back(t);
    }
    double anchor_best_score = 0.0;
    for (int gap = 1; frame1 + gap < num_frames &&
                      (options_.init_max_frame_gap == 0 || gap <= options_.init_max_frame_gap);
         gap = NextGap(gap, options_)) {
      const int frame2 = frame1 + gap;
      if (excluded.count(ImageIdOfFrame(frame2))) continue;
      // Tracks only end as the gap grows, so past too few shared tracks larger gaps will not do
      // better; a pair with enough of them costs a trial.
      if (num_trials >= max_num_trials) return;
      InitialPair pair;
      double measure = 0.0;
      const InitialPairSearch candidate =
          EvaluateInitialPair(frame1, frame2, anchor_tracks, &pair, &measure);
      if (candidate.stage == Stage::kSharedTracks) {
        if (candidate.num_shared_tracks > 0) consider(candidate, measure);
        return;
      }
      ++num_trials;
      ++seen.num_pairs_verified;
      consider(candidate, measure);
      if (candidate.stage < Stage::kParallax) continue;
      const bool saturated =
          pair.geometry.median_triangulation_angle_deg >= options_.init_tri_angle_deg;
      if (candidate.stage == Stage::kQualified) {
        ++seen.num_pairs_qualified;
        pairs.push_back(std::move(pair));
      }
      // Past this anchor's peak, or most inliers already count fully so that larger gaps can
      // only lose matches.
      if (candidate.score < 0.5 * anchor_best_score || saturated) return;
      anchor_best_score = std::max(anchor_best_score, candidate.score);
    }
  };
  // First the most tracked frames (for a video, the middle frames, whose tracks run both ways),
  // then anchors over the whole clip, so that later models find their pairs in this list; the
  // pairs of the first anchors come first, each group best score first.
  std::vector<char> searched(num_frames, 0);
  size_t num_first = 0;
  bool first_group = true;
  for (const std::vector<int>& anchors :
       {MostTrackedFrames(num_tracked, excluded, options_.init_num_anchors),
        SpreadAnchors(num_tracked, excluded, options_.init_anchor_spacing)}) {
    for (size_t a = 0; a < anchors.size() && num_trials < max_num_trials; ++a) {
      const int frame1 = anchors[a];
      // (The first anchor is looked at anyway, so that a search that fails says how many tracks
      // its best pair shared; it cannot qualify.)
      if (num_tracked[frame1] < options_.init_min_num_matches && a > 0) break;
      if (searched[frame1]) continue;
      searched[frame1] = 1;
      search_anchor(frame1);
    }
    if (first_group) {
      num_first = pairs.size();
      for (InitialPair& pair : pairs) pair.most_tracked_anchor = true;
    }
    first_group = false;
  }
  const auto by_score = [](const InitialPair& a, const InitialPair& b) {
    return a.score > b.score;
  };
  std::stable_sort(pairs.begin(), pairs.begin() + static_cast<long>(num_first), by_score);
  std::stable_sort(pairs.begin() + static_cast<long>(num_first), pairs.end(), by_score);
  if (search) *search = seen;
  return pairs;
}

size_t IncrementalMapper::RegisterInitialPair(const InitialPair& pair) {
  COMIC_CHECK(reconstruction_.NumRegisteredImages() == 0, kInvalidArgument,
              "mapper: the initial pair must be registered first");
  COMIC_CHECK(pair.track_ids.size() == pair.geometry.inlier_mask.size() &&
                  pair.point2D_idxs1.size() == pair.track_ids.size() &&
                  pair.point2D_idxs2.size() == pair.track_ids.size(),
              kInvalidArgument, "mapper: inconsistent initial pair");
  Image& image1 = reconstruction_.image(pair.image_id1);
  Image& image2 = reconstruction_.image(pair.image_id2);
  image1.cam_from_world = Rigid3d();
  image2.cam_from_world = pair.geometry.cam2_from_cam1;
  reconstruction_.RegisterImage(pair.image_id1);
  reconstruction_.RegisterImage(pair.image_id2);
  registration_order_ = {pair.image_id1, pair.image_id2};
  // A model's first two frames are its first keyframes, whatever the selection said.
  if (!is_keyframe_.empty()) {
    is_keyframe_[FrameOfImageId(pair.image_id1)] = 1;
    is_keyframe_[FrameOfImageId(pair.image_id2)] = 1;
  }
  init_image_id1_ = pair.image_id1;
  init_image_id2_ = pair.image_id2;

  const Camera& camera = reconstruction_.camera(camera_id_);
  size_t num_points = 0;
  for (size_t i = 0; i < pair.track_ids.size(); ++i) {
    if (!pair.geometry.inlier_mask[i]) continue;
    TriangulationView view1{&camera, image1.cam_from_world,
                            image1.points2D[pair.point2D_idxs1[i]].xy};
    TriangulationView view2{&camera, image2.cam_from_world,
                            image2.points2D[pair.point2D_idxs2[i]].xy};
    const auto point = TriangulateMultiView({view1, view2}, options_.triangulation);
    if (!point) continue;
    reconstruction_.AddPoint3D(point->xyz, {{pair.image_id1, pair.point2D_idxs1[i]},
                                            {pair.image_id2, pair.point2D_idxs2[i]}});
    ++num_points;
  }
  return num_points;
}

point3D_t IncrementalMapper::TrackPoint(int track_id) const {
  for (const frontend::TrackObservation& obs : tracks_->tracks[track_id].observations) {
    const Point2D& point2D = reconstruction_.image(ImageIdOfFrame(obs.frame)).points2D[obs.feature];
    if (point2D.HasPoint3D()) return point2D.point3D_id;
  }
  return kInvalidPoint3DId;
}

void IncrementalMapper::CountTracksWithPoints() {
  // Net change per track first: a re-triangulated point is unlinked and linked again, and its
  // frames' counts need not move.
  std::vector<std::pair<int, bool>> touched;  // track, whether it had a point before
  for (const Reconstruction::LinkChange& change : reconstruction_.TakeLinkChanges()) {
    const int t =
        track_of_feature_[FrameOfImageId(change.element.image_id)][change.element.point2D_idx];
    if (t < 0) continue;
    if (!track_touched_[t]) {
      track_touched_[t] = 1;
      touched.emplace_back(t, track_num_linked_features_[t] > 0);
    }
    track_num_linked_features_[t] += change.linked ? 1 : -1;
  }
  for (const auto& [t, had_point] : touched) {
    track_touched_[t] = 0;
    const bool has_point = track_num_linked_features_[t] > 0;
    if (has_point == had_point) continue;
    for (const frontend::TrackObservation& obs : tracks_->tracks[t].observations) {
      frame_num_tracks_with_points_[obs.frame] += has_point ? 1 : -1;
    }
  }
}

int IncrementalMapper::NumTracksWithPoints(image_t image_id) {
  COMIC_CHECK(reconstruction_.ExistsImage(image_id), kInvalidArgument,
              "mapper: unknown image " << image_id);
  CountTracksWithPoints();
  return frame_num_tracks_with_points_[FrameOfImageId(image_id)];
}

std::vector<image_t> IncrementalMapper::NextImageCandidates() {
  CountTracksWithPoints();
  std::vector<std::pair<int, image_t>> candidates;
  for (const auto& [image_id, image] : reconstruction_.images()) {
    if (image.registered) continue;
    const int num_visible = frame_num_tracks_with_points_[FrameOfImageId(image_id)];
    if (num_visible >= options_.absolute_pose.min_num_inliers) {
      candidates.emplace_back(num_visible, image_id);
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<image_t> ids;
  for (const auto& candidate : candidates) ids.push_back(candidate.second);
  return ids;
}

IncrementalMapper::MapPose IncrementalMapper::EstimatePoseAgainstMap(image_t image_id) const {
  const Image& image = reconstruction_.image(image_id);
  const int frame = FrameOfImageId(image_id);
  MapPose result;
  std::vector<Eigen::Vector2d> points2D;
  std::vector<Eigen::Vector3d> points3D;
  for (point2D_t idx = 0; idx < image.points2D.size(); ++idx) {
    const int t = track_of_feature_[frame][idx];
    if (t < 0) continue;
    const point3D_t point3D_id = TrackPoint(t);
    if (point3D_id == kInvalidPoint3DId) continue;
    result.point2D_idxs.push_back(idx);
    result.point3D_ids.push_back(point3D_id);
    points2D.push_back(image.points2D[idx].xy);
    points3D.push_back(reconstruction_.point3D(point3D_id).xyz);
  }
  result.pose = EstimateAbsolutePose(reconstruction_.camera(image.camera_id), points2D, points3D,
                                     options_.absolute_pose, &result.num_inliers_found);
  return result;
}

bool IncrementalMapper::RegisterNextImage(image_t image_id) {
  Image& image = reconstruction_.image(image_id);
  COMIC_CHECK(!image.registered, kInvalidArgument,
              "mapper: image " << image_id << " is already registered");
  const int frame = FrameOfImageId(image_id);
  const MapPose found = EstimatePoseAgainstMap(image_id);
  if (!found.pose) {
    best_failed_pose_inliers_[frame] =
        std::max(best_failed_pose_inliers_[frame], found.num_inliers_found);
    return false;
  }
  image.cam_from_world = found.pose->cam_from_world;
  reconstruction_.RegisterImage(image_id);
  registration_order_.push_back(image_id);
  last_num_pose_inliers_ = found.pose->num_inliers;
  // A frame that is not a keyframe keeps its pose out of the map (SetKeyframes).
  if (!IsKeyframe(image_id)) return true;
  for (size_t i = 0; i < found.point2D_idxs.size(); ++i) {
    // Two features of one frame can reach one point only through fused points (a merge or a
    // loop): the first inlier wins.
    if (found.pose->inlier_mask[i] && !Observes(found.point3D_ids[i], image_id)) {
      reconstruction_.AddObservation(found.point3D_ids[i], {image_id, found.point2D_idxs[i]});
    }
  }
  return true;
}

void IncrementalMapper::SetKeyframes(std::vector<char> is_keyframe) {
  COMIC_CHECK(is_keyframe.empty() || is_keyframe.size() == tracks_->NumFrames(), kInvalidArgument,
              "mapper: " << is_keyframe.size() << " keyframe flags for " << tracks_->NumFrames()
                         << " frames");
  COMIC_CHECK(reconstruction_.NumRegisteredImages() == 0, kInvalidArgument,
              "mapper: keyframes must be set before any frame is registered");
  is_keyframe_ = std::move(is_keyframe);
}

bool IncrementalMapper::IsKeyframe(image_t image_id) const {
  return is_keyframe_.empty() || is_keyframe_[FrameOfImageId(image_id)];
}

void IncrementalMapper::PromoteToKeyframe(image_t image_id) {
  COMIC_CHECK(!reconstruction_.image(image_id).registered, kInvalidArgument,
              "mapper: image " << image_id << " is registered; only an unregistered frame may "
                               << "become a keyframe");
  if (!is_keyframe_.empty()) is_keyframe_[FrameOfImageId(image_id)] = 1;
}

std::vector<image_t> IncrementalMapper::LocalizeNonKeyframes() {
  std::vector<image_t> lost;
  if (is_keyframe_.empty()) return lost;
  for (image_t image_id : reconstruction_.RegisteredImageIds()) {
    if (IsKeyframe(image_id)) continue;
    const MapPose found = EstimatePoseAgainstMap(image_id);
    if (!found.pose) {
      reconstruction_.DeRegisterImage(image_id);
      lost.push_back(image_id);
      continue;
    }
    Image& image = reconstruction_.image(image_id);
    image.cam_from_world = found.pose->cam_from_world;
    for (size_t i = 0; i < found.point2D_idxs.size(); ++i) {
      // One observation per point and image: a track may hold two features of one frame only
      // through a wrong match, and two tracks reach one point only through fused points (a
      // merge or a loop); the first inlier wins.
      if (!found.pose->inlier_mask[i] || image.points2D[found.point2D_idxs[i]].HasPoint3D() ||
          Observes(found.point3D_ids[i], image_id)) {
        continue;
      }
      reconstruction_.AddObservation(found.point3D_ids[i], {image_id, found.point2D_idxs[i]});
    }
  }
  return lost;
}

bool IncrementalMapper::TriangulateOrCompleteTrack(int track_id, bool retriangulate) {
  const frontend::Track& track = tracks_->tracks[track_id];
  const point3D_t point3D_id = TrackPoint(track_id);
  // The track's registered views.
  std::vector<TriangulationView> views;
  std::vector<TrackElement> elements;
  for (const frontend::TrackObservation& obs : track.observations) {
    const image_t image_id = ImageIdOfFrame(obs.frame);
    const Image& image = reconstruction_.image(image_id);
    // Frames that are not keyframes stay out of the map (SetKeyframes).
    if (!image.registered || !IsKeyframe(image_id)) continue;
    views.push_back({&reconstruction_.camera(image.camera_id), image.cam_from_world,
                     image.points2D[obs.feature].xy});
    elements.push_back({image_id, static_cast<point2D_t>(obs.feature)});
  }
  if (point3D_id != kInvalidPoint3DId) {
    // Complete: add registered views the point misses if they agree with it.
    const Eigen::Vector3d xyz = reconstruction_.point3D(point3D_id).xyz;
    for (size_t i = 0; i < elements.size(); ++i) {
      const Image& image = reconstruction_.image(elements[i].image_id);
      // The point may see the frame through another track already (fused points).
      if (image.points2D[elements[i].point2D_idx].HasPoint3D() ||
          Observes(point3D_id, elements[i].image_id)) {
        continue;
      }
      const auto projection =
          ProjectPoint(reconstruction_.camera(image.camera_id), image.cam_from_world, xyz);
      if (projection &&
          (*projection - views[i].point2D).norm() <= options_.complete_max_reprojection_error_px) {
        reconstruction_.AddObservation(point3D_id, elements[i]);
      }
    }
    // Re-triangulate: a point made early from a few close views can lie so far off that the
    // track's later views miss it by more than complete_max_reprojection_error_px, and then the
    // track never gets the baseline that would fix the point. A hypothesis from all registered
    // views of the track replaces the point if it explains more of them.
    const size_t num_observations = reconstruction_.point3D(point3D_id).track.size();
    if (!options_.retriangulate_incomplete_tracks || num_observations >= elements.size()) {
      return false;
    }
    if (!retriangulate) return false;
    TriangulationOptions retriangulation = options_.triangulation;
    retriangulation.max_reprojection_error_px = options_.retriangulate_max_reprojection_error_px;
    const auto point = TriangulateMultiView(views, retriangulation);
    if (!point) return false;
    std::vector<TrackElement> inlier_elements;
    for (int i : point->inlier_views) {
      // A feature of the track may belong to another point (the track was split by fusing
      // points: sfm/loop_closure.h); it stays there.
      const point3D_t owner =
          reconstruction_.image(elements[i].image_id).points2D[elements[i].point2D_idx].point3D_id;
      if (owner == kInvalidPoint3DId || owner == point3D_id) inlier_elements.push_back(elements[i]);
    }
    if (inlier_elements.size() <= num_observations) return false;
    reconstruction_.DeletePoint3D(point3D_id);
    reconstruction_.AddPoint3D(point->xyz, inlier_elements);
    return false;
  }
  if (views.size() < 2) return false;
  // A track of two frames gives a point no third view checks (COLMAP's
  // tri_ignore_two_view_tracks): on KITTI and the dino ring such points were a third of the
  // model, slowed every adjustment and pulled the poses (docs/sfm.md "Two-view tracks").
  if (options_.ignore_two_view_tracks && track.Length() < 3) return false;
  const auto point = TriangulateMultiView(views, options_.triangulation);
  if (!point) return false;
  std::vector<TrackElement> inlier_elements;
  for (int i : point->inlier_views) inlier_elements.push_back(elements[i]);
  reconstruction_.AddPoint3D(point->xyz, inlier_elements);
  return true;
}

size_t IncrementalMapper::TriangulateImage(image_t image_id) {
  const Image& image = reconstruction_.image(image_id);
  COMIC_CHECK(image.registered, kInvalidArgument,
              "mapper: image " << image_id << " is not registered");
  size_t num_new = 0;
  if (!IsKeyframe(image_id)) return num_new;  // outside the map (SetKeyframes)
  for (int t : track_of_feature_[FrameOfImageId(image_id)]) {
    if (t >= 0) num_new += TriangulateOrCompleteTrack(t, options_.retriangulate_on_registration);
  }
  return num_new;
}

size_t IncrementalMapper::TriangulateTracksOf(const std::set<image_t>& image_ids) {
  std::set<int> track_ids;
  for (image_t image_id : image_ids) {
    for (int t : track_of_feature_[FrameOfImageId(image_id)]) {
      if (t >= 0) track_ids.insert(t);
    }
  }
  size_t num_new = 0;
  for (int t : track_ids) num_new += TriangulateOrCompleteTrack(t, /*retriangulate=*/true);
  return num_new;
}

std::set<image_t> IncrementalMapper::NewestKeyframes(int num_images) const {
  std::set<image_t> image_ids;
  for (auto it = registration_order_.rbegin(); it != registration_order_.rend(); ++it) {
    if (static_cast<int>(image_ids.size()) >= num_images) break;
    if (reconstruction_.image(*it).registered && IsKeyframe(*it)) image_ids.insert(*it);
  }
  return image_ids;
}

size_t IncrementalMapper::TriangulateAllTracks() {
  size_t num_new = 0;
  for (size_t t = 0; t < tracks_->tracks.size(); ++t) {
    num_new += TriangulateOrCompleteTrack(static_cast<int>(t), /*retriangulate=*/true);
  }
  return num_new;
}

size_t IncrementalMapper::MergeModel(const Reconstruction& other,
                                     const std::vector<FeatureLink>& links) {
  // Point pairs: the points the two models give to one physical point.
  std::vector<ModelPointPair> pairs;
  std::set<std::pair<point3D_t, point3D_t>> paired;  // (this, other) point ids
  const auto add_pair = [&](image_t image_id, point2D_t idx, point3D_t other_point3D_id) {
    const Point2D& point2D = reconstruction_.image(image_id).points2D[idx];
    if (!point2D.HasPoint3D() || other_point3D_id == kInvalidPoint3DId) return;
    if (!paired.insert({point2D.point3D_id, other_point3D_id}).second) return;
    pairs.push_back({image_id, point2D.xy, other.point3D(other_point3D_id).xyz,
                     reconstruction_.point3D(point2D.point3D_id).xyz});
  };
  const auto other_point = [&](image_t image_id, point2D_t idx) {
    if (!other.ExistsImage(image_id)) return kInvalidPoint3DId;
    const Image& image = other.image(image_id);
    return image.registered && idx < image.points2D.size() ? image.points2D[idx].point3D_id
                                                           : kInvalidPoint3DId;
  };
  std::vector<image_t> new_image_ids;
  for (const auto& [image_id, other_image] : other.images()) {
    if (!other_image.registered || !reconstruction_.ExistsImage(image_id)) continue;
    const Image& image = reconstruction_.image(image_id);
    if (!image.registered) {
      new_image_ids.push_back(image_id);
      continue;
    }
    // A frame registered in both.
    const size_t n = std::min(image.points2D.size(), other_image.points2D.size());
    for (size_t idx = 0; idx < n; ++idx) {
      add_pair(image_id, static_cast<point2D_t>(idx), other_image.points2D[idx].point3D_id);
    }
  }
  if (new_image_ids.empty()) return 0;
  // A track with a point in both (its frames may be registered in one model each).
  for (const auto& [point3D_id, point] : reconstruction_.points3D()) {
    const TrackElement& element = point.track.front();
    const int t = track_of_feature_[FrameOfImageId(element.image_id)][element.point2D_idx];
    if (t < 0) continue;
    for (const frontend::TrackObservation& obs : tracks_->tracks[t].observations) {
      const point3D_t other_id = other_point(ImageIdOfFrame(obs.frame), obs.feature);
      if (other_id == kInvalidPoint3DId) continue;
      add_pair(element.image_id, element.point2D_idx, other_id);
      break;
    }
  }
  // The two ends of a link.
  for (const FeatureLink& link : links) {
    if (!reconstruction_.ExistsImage(link.image_id) ||
        !reconstruction_.image(link.image_id).registered ||
        link.point2D_idx >= reconstruction_.image(link.image_id).points2D.size()) {
      continue;
    }
    add_pair(link.image_id, link.point2D_idx,
             other_point(link.other_image_id, link.other_point2D_idx));
  }
  if (static_cast<int>(pairs.size()) < options_.merge_min_num_inliers) return 0;

  const auto consistent = [&](const Sim3d& sim, const ModelPointPair& pair) {
    const Image& image = reconstruction_.image(pair.image_id);
    const Eigen::Vector3d mapped = sim * pair.other_xyz;
    const double depth = (image.cam_from_world * pair.xyz).z();
    if (depth <= 0 || (mapped - pair.xyz).norm() > options_.merge_max_relative_distance * depth) {
      return false;
    }
    const auto projection =
        ProjectPoint(reconstruction_.camera(image.camera_id), image.cam_from_world, mapped);
    return projection &&
           (*projection - pair.xy).norm() <= options_.filter_max_reprojection_error_px;
  };
  std::vector<Eigen::Vector3d> other_points, points;
  for (const ModelPointPair& pair : pairs) {
    other_points.push_back(pair.other_xyz);
    points.push_back(pair.xyz);
  }
  const std::optional<Sim3d> sim = EstimateSim3dRansac(
      other_points, points, [&](const Sim3d& s, size_t i) { return consistent(s, pairs[i]); },
      options_.merge_min_num_inliers, options_.merge_min_inlier_ratio);
  if (!sim) return 0;
  for (image_t image_id : new_image_ids) {
    Image& image = reconstruction_.image(image_id);
    image.cam_from_world = sim->TransformPose(other.image(image_id).cam_from_world);
    reconstruction_.RegisterImage(image_id);
    registration_order_.push_back(image_id);
  }
  TriangulateAllTracks();
  FuseLinkedPoints(links);
  return new_image_ids.size();
}

bool IncrementalMapper::Observes(point3D_t point3D_id, image_t image_id) const {
  for (const TrackElement& element : reconstruction_.point3D(point3D_id).track) {
    if (element.image_id == image_id) return true;
  }
  return false;
}

size_t IncrementalMapper::FuseLinkedPoints(const std::vector<FeatureLink>& links,
                                           bool keep_unexplained) {
  // The tracks do not know that the two ends of a link are one point: tell the model.
  size_t num_fused = 0;
  for (const FeatureLink& link : links) {
    if (!reconstruction_.ExistsImage(link.image_id) ||
        !reconstruction_.ExistsImage(link.other_image_id)) {
      continue;
    }
    const Image& image = reconstruction_.image(link.image_id);
    const Image& other_image = reconstruction_.image(link.other_image_id);
    if (!image.registered || !other_image.registered || link.point2D_idx >= image.points2D.size() ||
        link.other_point2D_idx >= other_image.points2D.size()) {
      continue;
    }
    const point3D_t a = image.points2D[link.point2D_idx].point3D_id;
    const point3D_t b = other_image.points2D[link.other_point2D_idx].point3D_id;
    if (a != kInvalidPoint3DId && b != kInvalidPoint3DId && a != b) {
      num_fused += FusePoints(a, b, keep_unexplained);
    }
  }
  return num_fused;
}

void IncrementalMapper::CorrectPoses(const std::map<image_t, Sim3d>& corrected_cams_from_world) {
  for (const auto& [image_id, pose] : corrected_cams_from_world) {
    COMIC_CHECK(reconstruction_.ExistsImage(image_id) && reconstruction_.image(image_id).registered,
                kInvalidArgument, "correct poses: image " << image_id << " is not registered");
    COMIC_CHECK(pose.scale > 0, kInvalidArgument,
                "correct poses: image " << image_id << " has scale " << pose.scale);
  }
  // A point keeps its coordinates in its first observer's camera (scaled by that camera's
  // similarity): x_cam = R X + t before, and x_cam = s' R' X' + t' after.
  for (const auto& [point3D_id, point] : reconstruction_.points3D()) {
    image_t reference = 0;
    for (const TrackElement& element : point.track) {
      if (corrected_cams_from_world.count(element.image_id) &&
          (reference == 0 || element.image_id < reference)) {
        reference = element.image_id;
      }
    }
    if (reference == 0) continue;
    const Sim3d& corrected = corrected_cams_from_world.at(reference);
    const Eigen::Vector3d in_camera = reconstruction_.image(reference).cam_from_world * point.xyz;
    reconstruction_.point3D(point3D_id).xyz =
        corrected.rotation.conjugate() * (in_camera - corrected.translation) / corrected.scale;
  }
  // A similarity pose as the rigid pose with the same centre and orientation.
  for (const auto& [image_id, pose] : corrected_cams_from_world) {
    reconstruction_.image(image_id).cam_from_world =
        Rigid3d(pose.rotation, pose.translation / pose.scale);
  }
}

bool IncrementalMapper::FusePoints(point3D_t a, point3D_t b, bool keep_unexplained) {
  const Eigen::Vector3d xyz = reconstruction_.point3D(a).xyz;
  std::set<image_t> seen;
  for (const TrackElement& element : reconstruction_.point3D(a).track) {
    seen.insert(element.image_id);
  }
  std::vector<TrackElement> moved;
  for (const TrackElement& element : reconstruction_.point3D(b).track) {
    if (seen.count(element.image_id)) continue;
    const Image& image = reconstruction_.image(element.image_id);
    const auto projection =
        ProjectPoint(reconstruction_.camera(image.camera_id), image.cam_from_world, xyz);
    if (projection && (*projection - image.points2D[element.point2D_idx].xy).norm() <=
                          options_.complete_max_reprojection_error_px) {
      moved.push_back(element);
    }
  }
  if (moved.empty()) return false;
  if (keep_unexplained && reconstruction_.point3D(b).track.size() >= moved.size() + 2) {
    // b keeps the rest (at least two observations): they still tie its frames together.
    for (const TrackElement& element : moved) {
      reconstruction_.DeleteObservation(element.image_id, element.point2D_idx);
    }
  } else {
    reconstruction_.DeletePoint3D(b);
  }
  for (const TrackElement& element : moved) reconstruction_.AddObservation(a, element);
  return true;
}

void IncrementalMapper::ResetCamera(const Camera& camera) {
  camera.Check();
  reconstruction_.camera(camera_id_) = camera;
}

void IncrementalMapper::FixGauge(BundleAdjustmentConfig* config) const {
  if (config->image_ids.count(init_image_id1_)) config->constant_pose_ids.insert(init_image_id1_);
  if (config->image_ids.count(init_image_id2_) &&
      !config->constant_pose_ids.count(init_image_id2_)) {
    config->fixed_scale_image_ids.insert(init_image_id2_);
  }
}

BundleAdjustmentSummary IncrementalMapper::AdjustLocalBundle(
    image_t image_id, const BundleAdjustmentOptions& ba_options, int num_images) {
  COMIC_CHECK(num_images >= 2, kInvalidArgument,
              "mapper: local bundle adjustment needs num_images >= 2");
  const Image& image = reconstruction_.image(image_id);
  COMIC_CHECK(image.registered, kInvalidArgument,
              "mapper: image " << image_id << " is not registered");
  // Registered images sharing the most points with the new one (ties: nearest frame).
  std::map<image_t, int> num_shared;
  for (const Point2D& point2D : image.points2D) {
    if (!point2D.HasPoint3D()) continue;
    for (const TrackElement& element : reconstruction_.point3D(point2D.point3D_id).track) {
      if (element.image_id != image_id) ++num_shared[element.image_id];
    }
  }
  std::vector<std::pair<int, image_t>> neighbours;
  for (const auto& [other_id, count] : num_shared) neighbours.emplace_back(count, other_id);
  std::stable_sort(neighbours.begin(), neighbours.end(), [&](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first > b.first;
    const auto distance = [&](image_t id) {
      return std::abs(static_cast<long>(id) - static_cast<long>(image_id));
    };
    return distance(a.second) < distance(b.second);
  });
  std::set<image_t> variable = {image_id};
  for (const auto& [count, other_id] : neighbours) {
    if (static_cast<int>(variable.size()) >= num_images) break;
    variable.insert(other_id);
  }

  const std::set<point3D_t> point_ids = PointsSeenBy(reconstruction_, variable);
  // Registered images outside the window that see its points: the adjuster holds them constant.
  const size_t num_constant_neighbours =
      ConstantNeighbourImages(reconstruction_, variable, point_ids).size();
  BundleAdjustmentConfig config;
  config.image_ids = variable;
  FixGauge(&config);
  // Without the initial pair and with fewer than two constant neighbours the window would float
  // freely: hold its earliest-registered images fixed until two poses anchor it.
  for (image_t id : registration_order_) {
    if (num_constant_neighbours + config.constant_pose_ids.size() +
            config.fixed_scale_image_ids.size() >=
        2) {
      break;
    }
    if (id != image_id && variable.count(id) && !config.constant_pose_ids.count(id)) {
      config.fixed_scale_image_ids.erase(id);
      config.constant_pose_ids.insert(id);
    }
  }
  const BundleAdjustmentSummary summary =
      BundleAdjuster(ba_options, config).Solve(&reconstruction_);
  FilterPoints(point_ids);
  return summary;
}

BundleAdjustmentSummary IncrementalMapper::AdjustGlobalBundle(
    const BundleAdjustmentOptions& ba_options, int max_num_images) {
  COMIC_CHECK(max_num_images >= 0, kInvalidArgument,
              "mapper: max_num_images must be >= 0 (0: every image), got " << max_num_images);
  BundleAdjustmentConfig config;
  config.image_ids = NewestKeyframes(
      max_num_images > 0 ? max_num_images : static_cast<int>(registration_order_.size()));
  FixGauge(&config);
  // A bounded adjustment moves only the points its frames see: only those are filtered (a walk
  // over the whole model after each would grow with it).
  const std::set<point3D_t> point_ids =
      max_num_images > 0 ? PointsSeenBy(reconstruction_, config.image_ids) : std::set<point3D_t>();
  if (max_num_images > 0 && config.constant_pose_ids.empty() &&
      config.fixed_scale_image_ids.empty() &&
      ConstantNeighbourImages(reconstruction_, config.image_ids, point_ids).size() < 2) {
    // Without the initial pair the frames outside the window fix the gauge; a window that shares
    // no point with them (a merged model's separate part) would float: adjust everything.
    return AdjustGlobalBundle(ba_options, 0);
  }
  const BundleAdjustmentSummary summary =
      BundleAdjuster(ba_options, config).Solve(&reconstruction_);
  if (max_num_images == 0) {
    FilterPoints();
  } else if (!point_ids.empty()) {
    FilterPoints(point_ids);
  }
  return summary;
}

std::vector<BundleAdjustmentSummary> IncrementalMapper::AdjustGlobalBundleInWindows(
    const BundleAdjustmentOptions& ba_options, int window_num_images) {
  COMIC_CHECK(window_num_images >= 2, kInvalidArgument,
              "mapper: windows of at least 2 images, got " << window_num_images);
  // The registered keyframes in the order they were registered (a frame registered again after
  // losing its pose counts where it first was).
  std::vector<image_t> keyframes;
  std::set<image_t> seen;
  for (image_t id : registration_order_) {
    if (reconstruction_.image(id).registered && IsKeyframe(id) && seen.insert(id).second) {
      keyframes.push_back(id);
    }
  }
  const size_t window = static_cast<size_t>(window_num_images);
  const size_t step = std::max<size_t>(1, window / 2);
  std::vector<BundleAdjustmentSummary> summaries;
  for (size_t begin = 0; begin < keyframes.size(); begin += step) {
    const size_t end = std::min(keyframes.size(), begin + window);
    BundleAdjustmentConfig config;
    config.image_ids.insert(keyframes.begin() + begin, keyframes.begin() + end);
    FixGauge(&config);
    const std::set<point3D_t> point_ids = PointsSeenBy(reconstruction_, config.image_ids);
    if (config.constant_pose_ids.empty() && config.fixed_scale_image_ids.empty() &&
        ConstantNeighbourImages(reconstruction_, config.image_ids, point_ids).size() < 2) {
      config.constant_pose_ids.insert(keyframes[begin]);
      if (end - begin >= 2) config.fixed_scale_image_ids.insert(keyframes[begin + 1]);
    }
    summaries.push_back(BundleAdjuster(ba_options, config).Solve(&reconstruction_));
    if (!point_ids.empty()) FilterPoints(point_ids);
    if (end == keyframes.size()) break;
  }
  return summaries;
}

size_t IncrementalMapper::FilterPoints(const std::set<point3D_t>& point3D_ids) {
  std::vector<point3D_t> ids;
  if (point3D_ids.empty()) {
    for (const auto& [id, point] : reconstruction_.points3D()) ids.push_back(id);
  } else {
    ids.assign(point3D_ids.begin(), point3D_ids.end());
  }
  size_t num_removed = 0;
  for (point3D_t point3D_id : ids) {
    if (!reconstruction_.ExistsPoint3D(point3D_id)) continue;
    // Copy: deleting observations edits the track.
    const std::vector<TrackElement> track = reconstruction_.point3D(point3D_id).track;
    for (const TrackElement& element : track) {
      if (!reconstruction_.ExistsPoint3D(point3D_id)) break;
      if (reconstruction_.ReprojectionError(element.image_id, element.point2D_idx) >
          options_.filter_max_reprojection_error_px) {
        // Deleting one of the last two observations deletes the point with both.
        const size_t track_length = reconstruction_.point3D(point3D_id).track.size();
        reconstruction_.DeleteObservation(element.image_id, element.point2D_idx);
        num_removed += reconstruction_.ExistsPoint3D(point3D_id) ? 1 : track_length;
      }
    }
    if (!reconstruction_.ExistsPoint3D(point3D_id)) continue;
    const Point3D& point = reconstruction_.point3D(point3D_id);
    std::vector<Eigen::Vector3d> centers;
    for (const TrackElement& element : point.track) {
      centers.push_back(ProjectionCenter(reconstruction_.image(element.image_id).cam_from_world));
    }
    double max_angle = 0.0;
    for (size_t a = 0; a < centers.size() && max_angle < options_.filter_min_tri_angle_deg; ++a) {
      for (size_t b = a + 1; b < centers.size(); ++b) {
        max_angle = std::max(max_angle, TriangulationAngleDeg(centers[a], centers[b], point.xyz));
      }
    }
    if (max_angle < options_.filter_min_tri_angle_deg) {
      num_removed += point.track.size();
      reconstruction_.DeletePoint3D(point3D_id);
    }
  }
  return num_removed;
}

size_t IncrementalMapper::NumSharedTracks(int frame1, int frame2) const {
  std::vector<int> tracks1;
  for (int t : track_of_feature_.at(frame1)) {
    if (t >= 0) tracks1.push_back(t);
  }
  std::sort(tracks1.begin(), tracks1.end());
  size_t shared = 0;
  for (int t : track_of_feature_.at(frame2)) {
    shared += t >= 0 && std::binary_search(tracks1.begin(), tracks1.end(), t);
  }
  return shared;
}

}  // namespace comic::sfm
