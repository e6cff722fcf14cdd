// Export of feature tracks to a COLMAP 3.8 database, so that `colmap mapper` reconstructs from our
// features: one image per frame with all its features as keypoints (and their descriptors, when
// the tracks carry them: COLMAP's matchers can then extend the database), and for every pair of
// frames at most `pair_window` apart that share tracks, the raw matches (one per shared track) and
// the matches verified by two-view geometry (`two_view_geometries`, which is what the mapper
// uses).
//
//   comic::sfm::ColmapExportOptions options;   // pair_window = 5
//   const auto summary = comic::sfm::ExportTracksToColmapDatabase(tracks, camera, options,
//                                                                 "out.db", /*overwrite=*/false);
//   std::cout << comic::sfm::ColmapMapperCommandLine(
//       "out.db", "frames/", "sparse/", RecommendColmapMapperOptions(summary));
//
// With known intrinsics the camera is PINHOLE (fx, fy, cx, cy) with prior_focal_length = 1 and
// pairs are verified with the essential matrix (config CALIBRATED); without, it is COLMAP's own
// default guess, SIMPLE_RADIAL (f = 1.2 · max(w, h), principal point at the centre, k = 0), and
// pairs are verified with the fundamental matrix (config UNCALIBRATED). Coordinates get +0.5
// (COLMAP's pixel-centre convention).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "frontend/matching/track.h"
#include "io/colmap/colmap_database.h"
#include "sfm/camera.h"
#include "sfm/two_view_geometry.h"

namespace comic::sfm {

struct ColmapExportOptions {
  // Frames i < j form a pair when j − i <= pair_window and they share at least one track (K;
  // consecutive pairs alone leave COLMAP without an initial pair with enough baseline).
  int pair_window = 5;
  // Two-view verification of each pair (RANSAC threshold in pixels, confidence, iterations, and
  // the minimum number of inliers below which a pair is written as DEGENERATE).
  TwoViewGeometryOptions two_view;
  // Prepended to every frame name to form COLMAP's image names, which are paths relative to
  // `colmap mapper --image_path` (e.g. "image_l/" when the image path is the folder above).
  std::string image_name_prefix;
  // Threads verifying pairs (0: one per core). The database does not depend on it.
  int num_threads = 0;
  // Write the tracks' descriptors (when they have them) into COLMAP's descriptors table, one row
  // per keypoint in the keypoints' order, so that COLMAP's matchers (exhaustive_matcher, ...)
  // can add pairs to the database; without them COLMAP matches nothing, and its
  // feature_extractor replaces them with a different number of its own (then its matchers crash).
  bool write_descriptors = true;
  // The camera model written when no intrinsics are known (COLMAP's feature extractor default:
  // SIMPLE_RADIAL, f = 1.2 max(w, h), principal point at the centre, no distortion).
  CameraModelId default_camera_model = CameraModelId::kSimpleRadial;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct ColmapExportSummary {
  int num_images = 0;
  int64_t num_keypoints = 0;
  int64_t num_descriptors = 0;     // rows of `descriptors` written (0: the tracks had none)
  int num_matched_pairs = 0;       // pairs with raw matches (rows of `matches`)
  int num_verified_pairs = 0;      // pairs whose two-view geometry is not DEGENERATE
  int64_t num_matches = 0;         // raw matches over all pairs
  int64_t num_inlier_matches = 0;  // verified matches over all pairs
  bool known_intrinsics = false;   // camera written as PINHOLE with a prior focal length
  // Verified pairs that COLMAP 3.8 could start from with its default
  // --Mapper.init_max_forward_motion 0.95 (|t_z| of the unit translation below 0.95) and at least
  // its default --Mapper.init_min_num_inliers 100 inliers; 0 means the motion is forward and
  // COLMAP needs init_max_forward_motion 1.0.
  int num_pairs_allowing_default_init = 0;
  // The largest median triangulation angle (degrees) of the inliers of a calibrated pair with at
  // least 100 inliers: COLMAP's --Mapper.init_min_tri_angle (default 16) must lie below it for
  // that pair to start a model. 0 if no such pair.
  double max_init_triangulation_angle_deg = 0.0;
};

// Writes the tracks into `database` (which must be empty of cameras and images) in one
// transaction: nothing is written if anything fails. `camera` holds the known intrinsics in
// OpenCV's pixel convention, std::nullopt if unknown. The frames need names (tracks.frame_names).
// Throws comic::Error: kInvalidArgument for bad options, missing frame names or a non-empty
// database; kInvalidData for inconsistent tracks. Deterministic.
ColmapExportSummary WriteTracksToColmapDatabase(const frontend::FeatureTracks& tracks,
                                                const std::optional<Camera>& camera,
                                                const ColmapExportOptions& options,
                                                io::ColmapDatabase* database);

// Checks, before any work, that ExportTracksToColmapDatabase can write `path`: its folder is
// writable, `path` is not a folder, and an existing file is refused unless `overwrite`; an
// existing database must not be held by another program, and no stale journal may lie beside it
// (io/colmap/sqlite_file.h; a hot journal is rolled back). Throws comic::Error(kIo) naming `path`.
void CheckColmapDatabaseOutput(const std::string& path, bool overwrite);

// Creates the database file `path`: built in a temporary file in the same folder, checked with
// SQLite's integrity check and renamed into place only when complete, so a failed export leaves
// no file behind. An existing `path` is refused (comic::Error(kIo)) unless `overwrite`, and is then
// replaced as a whole, under the guard of io/colmap/sqlite_file.h: never while another program
// holds it, never beside a stale journal.
ColmapExportSummary ExportTracksToColmapDatabase(const frontend::FeatureTracks& tracks,
                                                 const std::optional<Camera>& camera,
                                                 const ColmapExportOptions& options,
                                                 const std::string& path, bool overwrite);

// The camera row we write: the known camera's model and parameters (+0.5 on the principal point,
// prior focal length), else COLMAP's default for an image of `image_size` in `default_model`.
io::ColmapDatabaseCamera ToColmapDatabaseCamera(
    const std::optional<Camera>& camera, const cv::Size& image_size,
    CameraModelId default_model = CameraModelId::kSimpleRadial);

}  // namespace comic::sfm
