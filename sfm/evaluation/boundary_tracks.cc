#include "sfm/evaluation/boundary_tracks.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/core/error.h"
#include "sfm/triangulation.h"

namespace comic::sfm {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Metres along a ray that stand for infinity (the paths are a few kilometres at most).
constexpr double kFarAway = 1e7;

// The RMS and largest distances between the observations of `track` and the projections of
// `point` (infinite when the point is behind one of the cameras).
std::pair<double, double> Reprojection(const frontend::Track& track,
                                       const frontend::FeatureTracks& tracks, const Camera& camera,
                                       const std::vector<Rigid3d>& cams_from_world,
                                       const Eigen::Vector3d& point) {
  double squares = 0.0;
  double worst = 0.0;
  for (const frontend::TrackObservation& obs : track.observations) {
    const Eigen::Vector3d c = cams_from_world[obs.frame] * point;
    if (!(c.z() > 0.0)) return {kInfinity, kInfinity};
    const Eigen::Vector2d projected = camera.ImageFromCam({c.x() / c.z(), c.y() / c.z()});
    const frontend::Feature& f = tracks.FeatureOf(obs);
    const double error = (projected - Eigen::Vector2d(f.x, f.y)).norm();
    squares += error * error;
    worst = std::max(worst, error);
  }
  return {std::sqrt(squares / track.observations.size()), worst};
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  return values[middle];
}

bool Known(float z) { return std::isfinite(z) && z > 0.0f; }

// The surfaces seen around an observation at (x, y), as 3-D points in the camera's frame along
// the observed ray: the plane through the four pixel centres around it (inverse depth is affine
// on a plane, so interpolating it bilinearly is exact there), and each nearby pixel's own depth
// (the candidates on either side of a discontinuity).
std::vector<Eigen::Vector3d> SurfaceCandidates(const cv::Mat& depth, const Camera& camera, double x,
                                               double y, int radius, bool* unknown) {
  const Eigen::Vector2d uv = camera.CamFromImage({x, y});
  const Eigen::Vector3d ray(uv.x(), uv.y(), 1.0);
  std::vector<Eigen::Vector3d> points;
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < depth.cols && y0 + 1 < depth.rows) {
    const float d[4] = {depth.at<float>(y0, x0), depth.at<float>(y0, x0 + 1),
                        depth.at<float>(y0 + 1, x0), depth.at<float>(y0 + 1, x0 + 1)};
    if (Known(d[0]) && Known(d[1]) && Known(d[2]) && Known(d[3])) {
      const double fx = x - x0;
      const double fy = y - y0;
      const double inverse =
          (1 - fy) * ((1 - fx) / d[0] + fx / d[1]) + fy * ((1 - fx) / d[2] + fx / d[3]);
      points.push_back(ray / inverse);
    }
  }
  const int cx = static_cast<int>(std::lround(x));
  const int cy = static_cast<int>(std::lround(y));
  bool sky = false;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const int px = cx + dx;
      const int py = cy + dy;
      if (px < 0 || py < 0 || px >= depth.cols || py >= depth.rows) continue;
      const float z = depth.at<float>(py, px);
      if (Known(z)) points.push_back(ray * z);
      sky |= z == 0.0f || z == std::numeric_limits<float>::infinity();
      *unknown |= std::isnan(z);
    }
  }
  // Nothing drawn there (0), or beyond what a PNG depth holds (+inf): a point as good as at
  // infinity, which only the cameras' rotations move. Unknown depth (NaN) gives no candidate.
  if (sky) points.push_back(ray * kFarAway);
  return points;
}

}  // namespace

void BoundaryTrackOptions::Check() const {
  COMIC_CHECK(follow_tolerance_px > 0, kInvalidArgument,
              "follow tolerance must be > 0 px, got " << follow_tolerance_px);
  COMIC_CHECK(min_track_length >= 2, kInvalidArgument,
              "minimum track length must be >= 2, got " << min_track_length);
  COMIC_CHECK(neighbourhood_px >= 0 && neighbourhood_px <= 5, kInvalidArgument,
              "depth neighbourhood must be in 0..5 px, got " << neighbourhood_px);
}

TrackSetSummary SummarizeTracks(const frontend::FeatureTracks& tracks,
                                const std::vector<TrackTruth>& truth,
                                const std::function<bool(size_t)>& pick) {
  TrackSetSummary summary;
  std::vector<double> lengths, drifts;
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    if (!pick(t)) continue;
    ++summary.num_tracks;
    lengths.push_back(static_cast<double>(tracks.tracks[t].Length()));
    if (!truth[t].classified) continue;
    ++summary.num_classified;
    summary.num_following += truth[t].follows;
    drifts.push_back(truth[t].drift_px);
  }
  for (double length : lengths) summary.mean_length += length / lengths.size();
  summary.median_length = Median(lengths);
  summary.median_drift_px = Median(drifts);
  return summary;
}

BoundaryTrackEvaluation EvaluateBoundaryTracks(const frontend::FeatureTracks& tracks,
                                               const Camera& camera,
                                               const std::vector<Rigid3d>& cams_from_world,
                                               const FrameTruthFn& truth,
                                               const BoundaryTrackOptions& options) {
  options.Check();
  const int num_frames = static_cast<int>(tracks.NumFrames());
  COMIC_CHECK(cams_from_world.size() == tracks.NumFrames(), kInvalidArgument,
              "boundary tracks: " << cams_from_world.size() << " true poses for " << num_frames
                                  << " frames");
  BoundaryTrackEvaluation result;
  result.tracks.resize(tracks.tracks.size());
  // The anchors of each long enough track (its first, middle and last observations), by frame.
  std::vector<std::vector<std::pair<size_t, size_t>>> anchors(num_frames);
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    const frontend::Track& track = tracks.tracks[t];
    if (static_cast<int>(track.Length()) < options.min_track_length) continue;
    for (size_t k : {size_t{0}, track.Length() / 2, track.Length() - 1}) {
      anchors[track.observations[k].frame].emplace_back(t, k);
    }
  }
  // One pass over the frames: label every feature, and gather the candidate points of the
  // tracks anchored in each frame (the frame's depth is read once).
  std::vector<std::vector<uint8_t>> on_band(num_frames);
  std::vector<std::vector<Eigen::Vector3d>> candidates(tracks.tracks.size());
  std::vector<uint8_t> unknown_depth(tracks.tracks.size(), 0);
  for (int f = 0; f < num_frames; ++f) {
    const FrameTruth frame = truth(f);
    COMIC_CHECK(frame.band.type() == CV_8UC1 && frame.depth.type() == CV_32FC1 &&
                    frame.band.size() == frame.depth.size(),
                kInvalidArgument, "boundary tracks: frame " << f << ": bad band or depth map");
    result.boundary_area_fraction +=
        cv::countNonZero(frame.band) / static_cast<double>(frame.band.total()) / num_frames;
    for (const frontend::Feature& feature : tracks.features[f]) {
      const int x = static_cast<int>(std::lround(feature.x));
      const int y = static_cast<int>(std::lround(feature.y));
      const bool in = x >= 0 && y >= 0 && x < frame.band.cols && y < frame.band.rows &&
                      frame.band.at<uint8_t>(y, x) != 0;
      on_band[f].push_back(in);
      ++result.num_features;
      result.num_boundary_features += in;
    }
    const Rigid3d world_from_cam = cams_from_world[f].Inverse();
    for (const auto& [t, k] : anchors[f]) {
      const frontend::Feature& anchor = tracks.FeatureOf(tracks.tracks[t].observations[k]);
      bool unknown = false;
      for (const Eigen::Vector3d& point : SurfaceCandidates(frame.depth, camera, anchor.x, anchor.y,
                                                            options.neighbourhood_px, &unknown)) {
        candidates[t].push_back(world_from_cam * point);
      }
      unknown_depth[t] |= unknown;
    }
  }
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    const frontend::Track& track = tracks.tracks[t];
    TrackTruth& truth_t = result.tracks[t];
    size_t in_band = 0;
    for (const frontend::TrackObservation& obs : track.observations) {
      in_band += on_band[obs.frame][obs.feature];
    }
    truth_t.boundary = track.Length() > 0 && 2 * in_band >= track.Length();
    if (static_cast<int>(track.Length()) < options.min_track_length) continue;
    if (candidates[t].empty() || unknown_depth[t]) {
      // Depth unknown at an anchor (a composited object): also the point its observations
      // triangulate.
      std::vector<Rigid3d> poses;
      std::vector<Eigen::Vector2d> normalized;
      for (const frontend::TrackObservation& obs : track.observations) {
        poses.push_back(cams_from_world[obs.frame]);
        const frontend::Feature& f = tracks.FeatureOf(obs);
        normalized.push_back(camera.CamFromImage({f.x, f.y}));
      }
      if (const auto point = TriangulatePointDlt(poses, normalized))
        candidates[t].push_back(*point);
    }
    if (candidates[t].empty()) continue;
    truth_t.classified = true;
    truth_t.drift_px = truth_t.worst_px = kInfinity;
    for (const Eigen::Vector3d& point : candidates[t]) {
      const auto [rms, worst] = Reprojection(track, tracks, camera, cams_from_world, point);
      if (rms < truth_t.drift_px) {
        truth_t.drift_px = rms;
        truth_t.worst_px = worst;
      }
    }
    truth_t.follows = truth_t.drift_px <= options.follow_tolerance_px;
  }
  result.boundary =
      SummarizeTracks(tracks, result.tracks, [&](size_t t) { return result.tracks[t].boundary; });
  result.other =
      SummarizeTracks(tracks, result.tracks, [&](size_t t) { return !result.tracks[t].boundary; });
  return result;
}

}  // namespace comic::sfm
