// The incremental mapping engine: holds a growing Reconstruction built from feature tracks and
// offers the steps a pipeline strings together (COLMAP's IncrementalMapper structure). Every
// geometric step is a stateless function elsewhere in sfm/ (two-view geometry, absolute pose,
// triangulation, bundle adjustment); this class only keeps the state between them.
//
//   IncrementalMapper mapper(tracks, camera, options);
//   const auto pair = mapper.FindInitialPair();           // std::nullopt: no usable pair
//   mapper.RegisterInitialPair(*pair);
//   mapper.AdjustGlobalBundle(ba_options);
//   for (image_t image_id : mapper.NextImageCandidates()) {
//     if (!mapper.RegisterNextImage(image_id)) continue;  // not fatal: try another frame
//     mapper.TriangulateImage(image_id);
//     mapper.AdjustLocalBundle(image_id, ba_options, /*num_images=*/8);
//     break;
//   }
//   mapper.AdjustGlobalBundle(ba_options);
//   Reconstruction reconstruction = mapper.TakeReconstruction();
//
// Images are the frames of the tracks: image_id = frame index + 1.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/absolute_pose.h"
#include "sfm/bundle_adjuster.h"
#include "sfm/camera.h"
#include "sfm/planar_pose_ambiguity.h"
#include "sfm/reconstruction.h"
#include "sfm/triangulation.h"
#include "sfm/two_view_geometry.h"

namespace comic::sfm {

class IncrementalMapper {
 public:
  struct Options {
    // Initial pair: at least this many tracks shared by the two frames.
    int init_min_num_matches = 100;
    // Initial pair: at least this many essential-matrix inliers in front of both cameras.
    int init_min_num_inliers = 60;
    // Initial pair: an inlier counts fully towards the pair's score when its triangulation angle
    // reaches this (degrees), proportionally below. The score, Σ min(angle / this, 1), rewards
    // parallax without requiring it of every point: under forward motion the points near the
    // epipole never have any, so a median-angle test (COLMAP's) rejects every pair.
    double init_tri_angle_deg = 4.0;
    // Initial pair: the best pair must score at least this.
    double init_min_score = 30.0;
    // Initial pair: also a pair a homography explains (kPlanarOrPanoramic) when its median
    // triangulation angle reaches init_tri_angle_deg: a flat scene seen from two places, not a
    // camera turning on the spot, which gives no parallax at all. COLMAP's mapper starts from
    // such pairs (its pose from the homography's decomposition); ours keeps the essential
    // matrix's pose, which a plane does not make degenerate for the five-point solver. Off in the
    // first searches, so a general pose is always preferred.
    bool init_accept_planar = false;
    // Initial pair: a near-planar qualified pair also keeps the other pose its homography allows
    // (InitialPair::planar_alternative, sfm/planar_pose_ambiguity.h), so that the pipeline can
    // choose between the two (IncrementalPipelineOptions::choose_planar_pose).
    bool init_find_planar_alternative = true;
    PlanarAmbiguityOptions planar_ambiguity;
    // Initial pair: frames at most this far apart (in frame index); 0 = no limit: each anchor's
    // gap grows (one frame at a time up to init_linear_gap, then by init_gap_growth) until the
    // anchor's tracks have ended, its score has passed its peak or its parallax saturates. A
    // fixed limit of 20 left the bag clip (handheld, mostly turning) without a pair: it needs
    // gaps near 40 (docs/sfm.md "Initial pair over the whole clip").
    int init_max_frame_gap = 0;
    int init_linear_gap = 10;
    double init_gap_growth = 1.4;
    // Initial pair: anchor frames are paired with the frames after them. First the
    // init_num_anchors frames with the most tracked features, then anchors over the whole clip,
    // one per stretch of init_anchor_spacing frames (the most tracked there), so that every part
    // of the clip can start a model. Anchors are visited most tracked first; the first group's
    // pairs are preferred.
    int init_num_anchors = 6;
    int init_anchor_spacing = 8;
    // Initial pair: at most max(init_max_num_trials, init_trials_per_frame x frames) pairs are
    // verified geometrically per search, so the search stays linear in the clip's length.
    int init_max_num_trials = 100;
    int init_trials_per_frame = 2;
    // Initial pair: essential matrix RANSAC and homography check.
    TwoViewGeometryOptions two_view;
    // Registration of a new frame: PnP RANSAC on its tracks that have 3-D points.
    AbsolutePoseOptions absolute_pose;
    // Triangulation of new tracks (angle, depth and reprojection checks).
    TriangulationOptions triangulation;
    // When a track's point misses some of the track's registered views (beyond
    // complete_max_reprojection_error_px), the track is triangulated again from all of them
    // (TriangulateMultiView) and the new point replaces the old one if it has more inlier views
    // within retriangulate_max_reprojection_error_px (it may leave out a wrong observation the old
    // point was made from). Without this,
    // a point made early from a few close frames and lying off keeps later views out, which would
    // give it the baseline to be corrected. On KITTI 06 (docs/sfm.md "Re-triangulation"): CoMIC
    // ATE 0.061 -> 0.056 m, Harris 0.0284 -> 0.0280 m, MSER 0.0654 -> 0.0660 m.
    bool retriangulate_incomplete_tracks = true;
    // Re-triangulate also in TriangulateImage, right after a frame's registration (its pose is
    // then PnP's, not yet adjusted); otherwise only in TriangulateAllTracks, after a global
    // bundle adjustment (COLMAP re-triangulates there).
    bool retriangulate_on_registration = true;
    // A re-triangulated point's views must reproject within this distance (pixels). With the 4 px
    // of first triangulation MSER's tracks on KITTI went from 0.065 to 0.154 m ATE (3 px: 0.073;
    // 2 px: 0.066): an MSER region's centre slides along the track as the region changes shape,
    // and a point fitted to all of a sliding track within 4 px joins what are really different
    // points, with errors that all lean one way. CoMIC gains more at 3 px (0.053 m), but only
    // 2 px is safe for every detector.
    double retriangulate_max_reprojection_error_px = 2.0;
    // Tracks seen in only two frames are not triangulated (except by the initial pair, whose
    // points start the model): such a point has no third view to check it, and a wrong or
    // sliding match makes a wrong point that still fits its two views exactly. COLMAP's
    // tri_ignore_two_view_tracks. On KITTI 06 and the dino ring (docs/sfm.md "Two-view tracks
    // and the global loss") it removed a third of the points, cut the adjustments' time and
    // lowered the ATE for most detectors (not MSER on KITTI, 0.054 -> 0.060 m, nor Hessian there,
    // +0.0002 m). Sparse image sets need them: on the temple ring CoMIC's ATE went from 0.0095 to
    // 0.030 m without them (comic_sfm keeps them for image sets).
    bool ignore_two_view_tracks = true;
    // Extend an existing point to a newly registered view whose observation reprojects within
    // this distance (pixels).
    double complete_max_reprojection_error_px = 4.0;
    // Filtering: observations reprojecting farther than this are removed (pixels).
    double filter_max_reprojection_error_px = 4.0;
    // Filtering: points whose largest triangulation angle is below this are removed (degrees).
    double filter_min_tri_angle_deg = 1.5;
    // Merging another model (MergeModel): a 3-D point pair is consistent with a similarity when
    // the mapped point reprojects within filter_max_reprojection_error_px in the shared frame and
    // lies within this fraction of its depth from this model's point (reprojection alone leaves
    // the scale free when the models share a single frame).
    double merge_max_relative_distance = 0.05;
    // Merging: at least this many consistent point pairs, and at least this fraction of them.
    int merge_min_num_inliers = 15;
    double merge_min_inlier_ratio = 0.25;

    // Throws comic::Error(kInvalidArgument) naming the bad field.
    void Check() const;
  };

  struct InitialPair {
    image_t image_id1 = 0;
    image_t image_id2 = 0;
    TwoViewGeometry geometry;  // relative pose and inliers
    // The shared tracks and their features in the two frames, in the order of
    // geometry.inlier_mask.
    std::vector<int> track_ids;
    std::vector<point2D_t> point2D_idxs1;
    std::vector<point2D_t> point2D_idxs2;
    // Parallax score, Σ over inliers of min(angle / init_tri_angle_deg, 1).
    double score = 0.0;
    // Found from one of the init_num_anchors most tracked frames (the preferred group), not from
    // the anchors over the whole clip.
    bool most_tracked_anchor = false;
    // A near-planar pair's other pose and its inliers (init_find_planar_alternative).
    std::optional<TwoViewGeometry> planar_alternative;
  };

  // What an initial pair search saw, so that a failure can say which check failed and by how
  // much (issue 17). The pair reported is the one that came closest: the search's checks are
  // stages (shared tracks >= init_min_num_matches, a general relative pose that a homography
  // does not explain, inliers >= init_min_num_inliers, parallax score >= init_min_score) and the
  // pair that passed the most of them wins, ties by its measure at the stage it failed.
  struct InitialPairSearch {
    enum class Stage {
      kNone,          // no two frames share a track
      kSharedTracks,  // failed: too few shared tracks
      kGeometry,      // failed: no general relative pose (degenerate, or a homography explains it)
      kInliers,       // failed: too few inliers of the relative pose
      kParallax,      // failed: parallax score too low
      kQualified,     // passed every check
    };
    Stage stage = Stage::kNone;
    image_t image_id1 = 0;
    image_t image_id2 = 0;
    int num_shared_tracks = 0;
    // From the two-view geometry (stages after kSharedTracks).
    TwoViewConfiguration configuration = TwoViewConfiguration::kDegenerate;
    int num_inliers = 0;
    int num_essential_inliers = 0;
    int num_homography_inliers = 0;
    double median_triangulation_angle_deg = 0.0;
    double score = 0.0;
    int num_pairs_verified = 0;   // pairs whose two-view geometry was estimated
    int num_pairs_qualified = 0;  // pairs that passed every check
  };

  // Builds an empty reconstruction with one camera and one unregistered image per frame of
  // `tracks` (which must outlive the mapper). Throws comic::Error for invalid tracks, camera or
  // options.
  IncrementalMapper(const frontend::FeatureTracks& tracks, const Camera& camera,
                    const Options& options);

  // Searches frame pairs (anchors with the most tracks first, growing frame gaps) for the one
  // with the highest parallax score among those with enough matches and inliers whose matches a
  // homography does not explain. std::nullopt if no pair qualifies (pure rotation, too few
  // tracks, too little parallax).
  // Frames (image ids) in `excluded` take no part.
  std::optional<InitialPair> FindInitialPair(const std::set<image_t>& excluded = {}) const;
  // Every qualifying pair the search verified: those of the most tracked anchors, then those of
  // the anchors over the whole clip, each group best score first (FindInitialPair returns the
  // first). Pairs are independent of the mapper's state, so a pipeline may compute them once and
  // start several models from them.
  // With `search`, also says what the search saw (InitialPairSearch).
  std::vector<InitialPair> FindInitialPairs(const std::set<image_t>& excluded = {},
                                            InitialPairSearch* search = nullptr) const;

  // Sets the pair's poses (first at the origin, unit baseline), registers both and triangulates
  // their inlier tracks. Returns the number of 3-D points created (0: the pair is unusable).
  size_t RegisterInitialPair(const InitialPair& pair);

  // Unregistered images ordered by how many of their tracks already have 3-D points (most
  // first, ties by frame), keeping those with at least absolute_pose.min_num_inliers of them.
  // A track has a point when any of its features observes one. Not const: it first brings the
  // per-frame counts up to date with the model's changes since the last call.
  std::vector<image_t> NextImageCandidates();
  // How many of the frame's tracks have a 3-D point (what NextImageCandidates ranks by).
  int NumTracksWithPoints(image_t image_id);

  // PnP RANSAC on the image's tracks that have 3-D points; on success sets its pose, registers
  // it and adds its inlier observations (none for a frame that is not a keyframe). Returns false
  // (not an error) if no pose was found.
  bool RegisterNextImage(image_t image_id);

  // Keyframes (sfm/keyframe_selection.h), one entry per frame: only keyframes add observations
  // and points to the map, so only they enter bundle adjustments. A frame that is not one is
  // registered by PnP like any other (it keeps a pose) but stays outside the map until
  // LocalizeNonKeyframes. Empty (the default): every frame is a keyframe. The initial pair's
  // frames are made keyframes when registered.
  void SetKeyframes(std::vector<char> is_keyframe);
  bool IsKeyframe(image_t image_id) const;
  // Makes an unregistered frame a keyframe (e.g. when the keyframes next to it did not register).
  void PromoteToKeyframe(image_t image_id);
  // The registered frames that are not keyframes, posed again by PnP against the map as it is now
  // (their poses from registration predate the adjustments since) with their inlier observations
  // added; a frame whose PnP now fails is deregistered. For the end of a model's growth: the
  // points do not move afterwards. Returns the frames deregistered.
  std::vector<image_t> LocalizeNonKeyframes();

  // For every track seen in the (registered) image: triangulates it from all registered views if
  // it has no point yet, or extends its point to registered views it misses (and re-triangulates
  // it if views still disagree; see retriangulate_incomplete_tracks). Returns the number of new
  // points. Nothing for a frame that is not a keyframe.
  size_t TriangulateImage(image_t image_id);

  // Triangulates and completes every track (e.g. after a global bundle adjustment). Returns the
  // number of new points.
  size_t TriangulateAllTracks();
  // The same for the tracks that `image_ids` observe, in track order (after an adjustment of
  // those images only: the other tracks' views did not move).
  size_t TriangulateTracksOf(const std::set<image_t>& image_ids);

  // The `num_images` most recently registered keyframes: the variable images of
  // AdjustGlobalBundle(ba_options, num_images).
  std::set<image_t> NewestKeyframes(int num_images) const;

  // A correspondence between a feature of this model's frame and one of another model's frame
  // that the tracks do not hold (e.g. found by matching the frames at the seam between two
  // models).
  struct FeatureLink {
    image_t image_id = 0;  // in this model
    point2D_t point2D_idx = 0;
    image_t other_image_id = 0;  // in the other model
    point2D_t other_point2D_idx = 0;
  };

  // Model merging: `other` is a model of the same tracks (e.g. an earlier model of the
  // pipeline). The similarity mapping it into this model is estimated from the point pairs the
  // two models give to one physical point: one feature of a frame registered in both, one track
  // with a point in both, or the two ends of a link (RANSAC over triples with a fixed seed,
  // Umeyama, refitted on the consistent pairs; see merge_max_relative_distance). The frames only
  // `other` registered are then registered here with their poses mapped by it, every track is
  // triangulated or completed, and the points at the two ends of a link become one. Returns the
  // number of frames added (0: nothing to add, or too few consistent pairs). The gauge stays
  // this model's.
  size_t MergeModel(const Reconstruction& other, const std::vector<FeatureLink>& links = {});

  // The tracks do not know that the two ends of a link are one point: fuses the points of each
  // link whose two frames are registered (after a merge, or a loop closure where both frames are
  // this model's). The point of `image_id`'s feature stays; the other's observations its
  // position explains join it, and the rest are dropped with the other point; with
  // `keep_unexplained` the other point keeps the rest when at least two remain, so that a link
  // between two ends not yet well aligned costs no observation (loop closure). Returns the
  // number of pairs fused.
  size_t FuseLinkedPoints(const std::vector<FeatureLink>& links, bool keep_unexplained = false);

  // Loop closure (sfm/loop_closure.h): sets the pose of every registered image of
  // `corrected_cams_from_world` (similarities: a pose graph moves the scale too) and moves every
  // point with the correction of the first registered image observing it, so that it keeps its
  // place in that image's camera frame (up to the image's scale). Images not given keep their
  // poses. Throws comic::Error for an image that is not registered or a non-positive scale.
  void CorrectPoses(const std::map<image_t, Sim3d>& corrected_cams_from_world);

  // Bundle adjustment of the image and the num_images − 1 registered images sharing most points
  // with it; other images seeing those points are held constant. Filters the adjusted points.
  BundleAdjustmentSummary AdjustLocalBundle(image_t image_id,
                                            const BundleAdjustmentOptions& ba_options,
                                            int num_images);

  // Bundle adjustment of every registered image and point; the gauge is fixed by the initial
  // pair (first pose constant, scale of the second). Filters all points afterwards. With
  // `max_num_images` > 0 only that many of the most recently registered keyframes are variable
  // (with every point they see; the other registered frames seeing those points are held
  // constant and anchor the gauge), so that its cost stops growing with the model.
  BundleAdjustmentSummary AdjustGlobalBundle(const BundleAdjustmentOptions& ba_options,
                                             int max_num_images = 0);

  // Bundle adjustment of every registered keyframe in windows, so that neither its cost per
  // frame nor its memory grows with the model: windows of `window_num_images` keyframes in
  // registration order, from the oldest, each starting half a window after the one before, so
  // that every keyframe is variable in one or two of them. The frames outside a window that see
  // its points are held constant and fix its gauge (the initial pair fixes the first window's;
  // a window that shares no point with the rest keeps its own first pose and second scale).
  // Filters each window's points. Returns one summary per window, oldest first.
  std::vector<BundleAdjustmentSummary> AdjustGlobalBundleInWindows(
      const BundleAdjustmentOptions& ba_options, int window_num_images);

  // Removes observations with large reprojection error or negative depth and points with too
  // small a triangulation angle among `point3D_ids` (all points if empty). Returns the number of
  // observations removed.
  size_t FilterPoints(const std::set<point3D_t>& point3D_ids = {});

  // Replaces the model's camera (e.g. a self-calibrated one by its prior); poses and points
  // stay. Throws comic::Error for an invalid camera.
  void ResetCamera(const Camera& camera);

  const Reconstruction& reconstruction() const { return reconstruction_; }
  // The model, without the journal of changes the mapper kept (the mapper is spent after this).
  Reconstruction TakeReconstruction() {
    reconstruction_.RecordLinkChanges(false);
    return std::move(reconstruction_);
  }
  // The tracks frames `frame1` and `frame2` both have a feature in.
  size_t NumSharedTracks(int frame1, int frame2) const;
  // Image id of frame index `frame` and back.
  static image_t ImageIdOfFrame(int frame) { return static_cast<image_t>(frame + 1); }
  static int FrameOfImageId(image_t image_id) { return static_cast<int>(image_id) - 1; }
  // Images in the order they were registered.
  const std::vector<image_t>& registration_order() const { return registration_order_; }
  // Inliers of the last successful RegisterNextImage.
  int last_num_pose_inliers() const { return last_num_pose_inliers_; }
  // Per frame: the most PnP inliers a failed RegisterNextImage found (-1: never failed there).
  const std::vector<int>& best_failed_pose_inliers() const { return best_failed_pose_inliers_; }

 private:
  // One initial pair candidate: the tracks of `anchor_tracks` shared by the two frames, their
  // relative pose and parallax score; returns how far it got (its stage) and the measure that
  // ranks it among candidates of that stage (InitialPairSearch).
  InitialPairSearch EvaluateInitialPair(int frame1, int frame2,
                                        const std::vector<int>& anchor_tracks, InitialPair* pair,
                                        double* measure) const;
  // The 3-D point of a track, or kInvalidPoint3DId.
  point3D_t TrackPoint(int track_id) const;
  // PnP RANSAC on the image's features whose tracks have points; the pose, and per
  // correspondence its feature, point and whether it is an inlier.
  struct MapPose {
    std::optional<AbsolutePose> pose;
    int num_inliers_found = 0;
    std::vector<point2D_t> point2D_idxs;
    std::vector<point3D_t> point3D_ids;
  };
  MapPose EstimatePoseAgainstMap(image_t image_id) const;
  // Triangulates a track without point, or completes the point of a track with one.
  // `retriangulate`: also re-triangulate incomplete tracks (if retriangulate_incomplete_tracks).
  bool TriangulateOrCompleteTrack(int track_id, bool retriangulate);
  // Whether the point has an observation in the image.
  bool Observes(point3D_t point3D_id, image_t image_id) const;
  // Makes the points `a` and `b` (of one physical point) one: b's observations that a's position
  // explains (within complete_max_reprojection_error_px) move to a, and b is deleted; nothing
  // changes if none is explained. With keep_unexplained, b stays with the observations a does not
  // explain if at least two are left. Returns whether observations moved.
  bool FusePoints(point3D_t a, point3D_t b, bool keep_unexplained);
  // Sets the gauge of a problem: the first initial image constant, the second's scale fixed.
  void FixGauge(BundleAdjustmentConfig* config) const;

  const frontend::FeatureTracks* tracks_;
  Options options_;
  Reconstruction reconstruction_;
  camera_t camera_id_ = 0;
  // Per frame, per feature: the track it belongs to (−1: none).
  std::vector<std::vector<int>> track_of_feature_;
  image_t init_image_id1_ = 0;
  image_t init_image_id2_ = 0;
  std::vector<image_t> registration_order_;
  int last_num_pose_inliers_ = 0;
  std::vector<int> best_failed_pose_inliers_;
  std::vector<char> is_keyframe_;  // per frame; empty: every frame
  // Kept current from the model's link changes (Reconstruction::TakeLinkChanges) by
  // CountTracksWithPoints, so that choosing the next frame does not walk every point after
  // every registration (a cost that grew with the video: docs/long_video.md).
  std::vector<int> track_num_linked_features_;     // per track: features observing a 3-D point
  std::vector<int> frame_num_tracks_with_points_;  // per frame: its tracks with a linked feature
  std::vector<char> track_touched_;                // scratch of CountTracksWithPoints, all 0

  // Applies the model's link changes since the last call to the two counts above.
  void CountTracksWithPoints();
};

}  // namespace comic::sfm
