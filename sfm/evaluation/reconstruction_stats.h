// The numbers a reconstruction is judged by without ground truth: registered images, 3-D points,
// mean track length, mean reprojection error; and the same for the points on an object's boundary
// and in its interior when the object's region is known (masks or boxes, labelled by
// frontend/evaluation/region_labels.h).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>

#include "frontend/evaluation/region_labels.h"
#include "sfm/reconstruction.h"

namespace comic::sfm {

struct PointSetStats {
  size_t num_points = 0;
  size_t num_observations = 0;
  double mean_track_length = 0.0;           // observations per point
  double mean_reprojection_error_px = 0.0;  // over the observations
};

struct ReconstructionStats {
  size_t num_images = 0;      // images (frames) in the reconstruction
  size_t num_registered = 0;  // of which registered
  PointSetStats all;
  // With region labels: points whose observations are mostly (at least half) labelled
  // kBoundary, and points mostly labelled kInterior.
  std::optional<PointSetStats> boundary;
  std::optional<PointSetStats> interior;
};

// The region label of a 2-D point of an image (e.g. from a per-frame frontend::LabelRegion map).
using RegionLabelFn =
    std::function<frontend::RegionLabel(const Image& image, const Eigen::Vector2d& xy)>;

ReconstructionStats ComputeReconstructionStats(const Reconstruction& reconstruction,
                                               const RegionLabelFn& region_label = {});

}  // namespace comic::sfm
