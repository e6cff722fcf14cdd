#include "sfm/evaluation/reconstruction_stats.h"

namespace comic::sfm {
namespace {

struct Accumulator {
  size_t num_points = 0;
  size_t num_observations = 0;
  double error_sum = 0.0;

  PointSetStats Stats() const {
    PointSetStats stats;
    stats.num_points = num_points;
    stats.num_observations = num_observations;
    if (num_points > 0) {
      stats.mean_track_length =
          static_cast<double>(num_observations) / static_cast<double>(num_points);
    }
    if (num_observations > 0) {
      stats.mean_reprojection_error_px = error_sum / static_cast<double>(num_observations);
    }
    return stats;
  }
};

}  // namespace

ReconstructionStats ComputeReconstructionStats(const Reconstruction& reconstruction,
                                               const RegionLabelFn& region_label) {
  ReconstructionStats stats;
  stats.num_images = reconstruction.NumImages();
  stats.num_registered = reconstruction.NumRegisteredImages();
  Accumulator all, boundary, interior;
  for (const auto& point3D_entry : reconstruction.points3D()) {
    // A named reference, not a structured binding: the lambda below captures it (C++17).
    const Point3D& point = point3D_entry.second;
    double error_sum = 0.0;
    size_t num_boundary = 0, num_interior = 0;
    for (const TrackElement& element : point.track) {
      error_sum += reconstruction.ReprojectionError(element.image_id, element.point2D_idx);
      if (region_label) {
        const Image& image = reconstruction.image(element.image_id);
        const frontend::RegionLabel label =
            region_label(image, image.points2D[element.point2D_idx].xy);
        num_boundary += label == frontend::RegionLabel::kBoundary;
        num_interior += label == frontend::RegionLabel::kInterior;
      }
    }
    const auto add = [&](Accumulator* accumulator) {
      ++accumulator->num_points;
      accumulator->num_observations += point.track.size();
      accumulator->error_sum += error_sum;
    };
    add(&all);
    if (2 * num_boundary >= point.track.size() && num_boundary > 0) {
      add(&boundary);
    } else if (2 * num_interior >= point.track.size() && num_interior > 0) {
      add(&interior);
    }
  }
  stats.all = all.Stats();
  if (region_label) {
    stats.boundary = boundary.Stats();
    stats.interior = interior.Stats();
  }
  return stats;
}

}  // namespace comic::sfm
