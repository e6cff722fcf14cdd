// A near-planar pair's second relative pose. Two views of a plane determine the relative pose only
// up to a two-fold ambiguity: the homography between them decomposes into two physically valid
// (rotation, translation, plane normal) triples, and both explain every point on the plane. The
// essential matrix of a scene that is nearly flat inherits the ambiguity: the five-point solver
// and RANSAC pick one of the two by the few points off the plane, and a model grown from the
// wrong one stays consistent (every later frame registers, every pair fits) while its cameras are
// turned degrees away from the truth. The other solution is returned here, and the clip's other
// frames choose between the two (CompareByThirdViews; IncrementalPipelineOptions::
// choose_planar_pose).
//
//   if (const auto other = OtherPlanarPose(camera, camera, points1, points2, geometry, 4.0, {}))
//     if (CompareByThirdViews(tracks, camera, f1, f2, track_ids, geometry, *other, {})
//             .prefers_second) ... start from *other ...
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "frontend/matching/track.h"
#include "sfm/camera.h"
#include "sfm/two_view_geometry.h"

namespace comic::sfm {

struct PlanarAmbiguityOptions {
  // Only a pair whose homography explains at least this share of the essential matrix's inliers
  // is near-planar enough to be ambiguous (a general scene's homography fits a few points).
  double min_homography_share = 0.5;
  // The other decomposition counts only when its rotation differs at least this much (degrees)
  // from the pose the essential matrix gave: otherwise the two poses are one.
  double min_rotation_difference_deg = 1.0;
  // The other pose must keep at least this share of the essential pose's inliers (in front of
  // both cameras, reprojecting within the two-view threshold).
  double min_inlier_share = 0.5;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The other physically valid pose of `geometry`'s homography decomposition, with its inliers
// among `points1`/`points2` (pixels; those `geometry` was estimated from) triangulated as
// EstimateCalibratedTwoViewGeometry does; nullopt when the pair is not near-planar, has no
// homography, or the other pose is the same as or worse supported than `geometry`'s.
// `max_error_px` is the two-view inlier threshold. Deterministic.
std::optional<TwoViewGeometry> OtherPlanarPose(const Camera& camera1, const Camera& camera2,
                                               const std::vector<Eigen::Vector2d>& points1,
                                               const std::vector<Eigen::Vector2d>& points2,
                                               const TwoViewGeometry& geometry, double max_error_px,
                                               const PlanarAmbiguityOptions& options);

// Which of a near-planar pair's two poses the other frames of the clip side with. Each pose's
// points (triangulated from the pair alone, never adjusted) locate every third frame that sees
// enough of them (PnP RANSAC, then the reprojection error of every shared point). A view of a
// plane from a third place is the pair's first view mapped by a homography whose decomposition
// shares only the true plane normal, so the wrong pose's plane leaves the third frames'
// features off their reprojections, more so the farther the frame is from the pair; the points
// off the plane add to it. The points are fixed, so no adjustment can bend a wrong start into
// agreement (growing a model from each pose and counting what it holds could, and did).
struct ThirdViewOptions {
  // A third frame takes part when it sees at least this many of the points both poses
  // triangulated.
  int min_shared_points = 30;
  // At most this many third frames, those sharing the most points (ties: the earlier frame).
  int max_views = 20;
  // Inlier threshold of the third frames' PnP, pixels.
  double max_error_px = 4.0;
  // Two judgements, each clear or silent. (1) The pooled median reprojection error of one pose
  // is below the other's by at least min_pooled_error_reduction of it (weighs the frames by
  // the points they see). (2) A sign test over the third frames: a frame votes for the pose
  // whose median error there is lower by at least min_frame_error_reduction of the other's (a
  // frame near the pair, which both poses explain alike, abstains), and the votes are clear
  // with at least min_votes for one pose and min_vote_ratio times the other's (weighs every
  // frame alike; their errors differ in scale with the two-view points' depth noise). The
  // second pose is preferred when either judgement is clear for it and neither for the first.
  double min_pooled_error_reduction = 0.1;
  double min_frame_error_reduction = 0.05;
  int min_votes = 3;
  double min_vote_ratio = 2.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct ThirdViewComparison {
  int num_points = 0;       // points both poses triangulated (the comparison's points)
  std::vector<int> frames;  // the third frames used
  // Per pose and third frame (in the order of `frames`), the median reprojection error of the
  // frame's shared points after its PnP; -1 where the pose cannot locate the frame.
  std::vector<double> frame_median_error_first_px;
  std::vector<double> frame_median_error_second_px;
  // Per pose, the median reprojection error of every shared point in every third frame after
  // that frame's PnP (a frame the pose cannot locate counts its points as unexplained).
  double median_error_first_px = 0.0;
  double median_error_second_px = 0.0;
  // Third frames voting for each pose (min_frame_error_reduction).
  int votes_first = 0;
  int votes_second = 0;
  // Whether the third frames side with `second` (the two judgements above).
  bool prefers_second = false;
};

// What the mapper decided for one near-planar initial pair (report.json's
// mapping.planar_pose_choices).
struct PlanarPoseChoice {
  int frame1 = -1;
  int frame2 = -1;
  int num_points = 0;        // ThirdViewComparison::num_points
  int num_third_frames = 0;  // ThirdViewComparison::frames.size()
  double median_error_essential_px = 0.0;
  double median_error_alternative_px = 0.0;
  int votes_essential = 0;  // third frames voting for each pose
  int votes_alternative = 0;
  bool kept_alternative = false;
};

// Compares two relative poses of the pair (frame1, frame2) of `tracks` by the third frames, as
// above. `track_ids` are the pair's correspondences in the order of both geometries'
// inlier_mask; each geometry's points3D are in frame1's camera frame. Deterministic.
ThirdViewComparison CompareByThirdViews(const frontend::FeatureTracks& tracks, const Camera& camera,
                                        int frame1, int frame2, const std::vector<int>& track_ids,
                                        const TwoViewGeometry& first, const TwoViewGeometry& second,
                                        const ThirdViewOptions& options);

}  // namespace comic::sfm
