#include "sfm/track_drift.h"

#include <cmath>

#include "sfm/triangulation.h"

namespace comic::sfm {

namespace {

std::optional<double> DriftOf(const frontend::FeatureTracks& tracks, const frontend::Track& track,
                              const Reconstruction& model, int min_views) {
  std::vector<const Camera*> cameras;
  std::vector<Rigid3d> cams_from_world;
  std::vector<Eigen::Vector2d> pixels, normalized;
  for (const frontend::TrackObservation& obs : track.observations) {
    const image_t image_id = static_cast<image_t>(obs.frame + 1);
    if (!model.ExistsImage(image_id) || !model.image(image_id).registered) continue;
    const Image& image = model.image(image_id);
    const frontend::Feature& feature = tracks.FeatureOf(obs);
    cameras.push_back(&model.camera(image.camera_id));
    cams_from_world.push_back(image.cam_from_world);
    pixels.emplace_back(feature.x, feature.y);
    normalized.push_back(cameras.back()->CamFromImage(pixels.back()));
  }
  if (static_cast<int>(pixels.size()) < min_views) return std::nullopt;
  const std::optional<Eigen::Vector3d> point = TriangulatePointDlt(cams_from_world, normalized);
  if (!point) return std::nullopt;
  double sum_squared = 0.0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const std::optional<Eigen::Vector2d> projected =
        ProjectPoint(*cameras[i], cams_from_world[i], *point);
    if (!projected) return std::nullopt;
    sum_squared += (*projected - pixels[i]).squaredNorm();
  }
  return std::sqrt(sum_squared / static_cast<double>(pixels.size()));
}

}  // namespace

std::vector<std::optional<double>> MeasureTrackDrift(const frontend::FeatureTracks& tracks,
                                                     const Reconstruction& model, int min_views) {
  std::vector<std::optional<double>> drift;
  drift.reserve(tracks.tracks.size());
  for (const frontend::Track& track : tracks.tracks) {
    drift.push_back(DriftOf(tracks, track, model, min_views));
  }
  return drift;
}

}  // namespace comic::sfm
