#include "sfm/colmap/colmap_export.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <thread>
#include <utility>
#include <vector>

#include "io/colmap/sqlite_file.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::sfm {
namespace {

// COLMAP 3.8's defaults for choosing an initial pair (IncrementalMapper::Options).
constexpr double kColmapDefaultInitMaxForwardMotion = 0.95;
constexpr int kColmapDefaultInitMinNumInliers = 100;

using FramePair = std::pair<int, int>;  // (earlier frame, later frame), 0-based

// One raw match per track seen by both frames of a pair within the window. A track holds at most
// one feature per frame and a feature belongs to at most one track (FeatureTracks::Check), so the
// matches of a pair are one-to-one. std::map keeps the pairs, and the track order the matches, so
// the output is a function of the tracks alone.
std::map<FramePair, io::ColmapFeatureMatches> CollectPairMatches(
    const frontend::FeatureTracks& tracks, int pair_window) {
  std::map<FramePair, io::ColmapFeatureMatches> pairs;
  for (const frontend::Track& track : tracks.tracks) {
    const auto& obs = track.observations;
    for (size_t a = 0; a < obs.size(); ++a) {
      for (size_t b = a + 1; b < obs.size() && obs[b].frame - obs[a].frame <= pair_window; ++b) {
        pairs[{obs[a].frame, obs[b].frame}].push_back(
            {static_cast<uint32_t>(obs[a].feature), static_cast<uint32_t>(obs[b].feature)});
      }
    }
  }
  return pairs;
}

Eigen::Matrix3d CrossProductMatrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// K in COLMAP's pixel convention (principal point + 0.5).
Eigen::Matrix3d ColmapK(const Camera& camera) {
  Eigen::Matrix3d k = camera.K();
  k(0, 2) = io::ToColmapPixel(camera.cx);
  k(1, 2) = io::ToColmapPixel(camera.cy);
  return k;
}

// OpenCV pixel coordinates from COLMAP's: x_cv = T · x_colmap.
Eigen::Matrix3d FromColmapPixelsTransform() {
  Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
  t(0, 2) = t(1, 2) = -0.5;
  return t;
}

struct VerifiedPair {
  io::ColmapTwoViewGeometry geometry;
  bool allows_default_init = false;
  double init_triangulation_angle_deg = 0.0;  // median angle if >= 100 inliers, else 0
};

VerifiedPair VerifyCalibrated(const Camera& camera, const std::vector<Eigen::Vector2d>& points1,
                              const std::vector<Eigen::Vector2d>& points2,
                              const io::ColmapFeatureMatches& matches,
                              const ColmapExportOptions& options) {
  VerifiedPair verified;
  verified.geometry.config = io::kColmapDegenerate;
  const TwoViewGeometry estimate =
      EstimateCalibratedTwoViewGeometry(camera, camera, points1, points2, options.two_view);
  if (estimate.configuration == TwoViewConfiguration::kDegenerate) return verified;
  io::ColmapTwoViewGeometry& geometry = verified.geometry;
  geometry.config = estimate.configuration == TwoViewConfiguration::kCalibrated
                        ? io::kColmapCalibrated
                        : io::kColmapPlanarOrPanoramic;
  for (size_t i = 0; i < matches.size(); ++i) {
    if (estimate.inlier_mask[i]) geometry.inlier_matches.push_back(matches[i]);
  }
  const Eigen::Matrix3d rotation = estimate.cam2_from_cam1.RotationMatrix();
  const Eigen::Vector3d& translation = estimate.cam2_from_cam1.translation;
  geometry.E = CrossProductMatrix(translation) * rotation;
  const Eigen::Matrix3d k_inv = ColmapK(camera).inverse();
  geometry.F = k_inv.transpose() * geometry.E * k_inv;
  const Eigen::Quaterniond& q = estimate.cam2_from_cam1.rotation;
  geometry.qvec = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  geometry.tvec = translation;
  const bool enough_inliers =
      static_cast<int>(geometry.inlier_matches.size()) >= kColmapDefaultInitMinNumInliers;
  verified.allows_default_init =
      enough_inliers && std::abs(translation.normalized().z()) < kColmapDefaultInitMaxForwardMotion;
  if (enough_inliers) {
    verified.init_triangulation_angle_deg = estimate.median_triangulation_angle_deg;
  }
  return verified;
}

VerifiedPair VerifyUncalibrated(const std::vector<Eigen::Vector2d>& points1,
                                const std::vector<Eigen::Vector2d>& points2,
                                const io::ColmapFeatureMatches& matches,
                                const ColmapExportOptions& options) {
  VerifiedPair verified;
  verified.geometry.config = io::kColmapDegenerate;
  if (static_cast<int>(matches.size()) < std::max(8, options.two_view.min_num_inliers)) {
    return verified;
  }
  std::vector<cv::Point2d> cv1, cv2;
  for (size_t i = 0; i < points1.size(); ++i) {
    cv1.emplace_back(points1[i].x(), points1[i].y());
    cv2.emplace_back(points2[i].x(), points2[i].y());
  }
  cv::Mat mask;
  const cv::Mat f_cv = cv::findFundamentalMat(
      cv1, cv2, cv::FM_RANSAC, options.two_view.max_error_px, options.two_view.confidence,
      options.two_view.max_num_iterations, mask);
  if (f_cv.rows != 3 || f_cv.cols != 3 || mask.empty() ||
      cv::countNonZero(mask) < options.two_view.min_num_inliers) {
    return verified;
  }
  io::ColmapTwoViewGeometry& geometry = verified.geometry;
  geometry.config = io::kColmapUncalibrated;
  for (size_t i = 0; i < matches.size(); ++i) {
    if (mask.at<uchar>(static_cast<int>(i))) geometry.inlier_matches.push_back(matches[i]);
  }
  Eigen::Matrix3d f;
  cv::cv2eigen(f_cv, f);
  const Eigen::Matrix3d t = FromColmapPixelsTransform();
  geometry.F = t.transpose() * f * t;
  return verified;
}

// Calls body(i) for i in [0, n) on `num_threads` threads (0: one per core). The first exception
// thrown by a body is rethrown once every thread has stopped.
void ParallelFor(size_t n, int num_threads, const std::function<void(size_t)>& body) {
  const size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  const size_t threads = std::min(n, num_threads > 0 ? static_cast<size_t>(num_threads) : hardware);
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    for (size_t i = next++; i < n; i = next++) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = n;
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace

void ColmapExportOptions::Check() const {
  COMIC_CHECK(pair_window >= 1, kInvalidArgument,
              "COLMAP export pair_window must be >= 1, got " << pair_window);
  COMIC_CHECK(num_threads >= 0, kInvalidArgument,
              "COLMAP export num_threads must be >= 0, got " << num_threads);
  two_view.Check();
}

io::ColmapDatabaseCamera ToColmapDatabaseCamera(const std::optional<Camera>& camera,
                                                const cv::Size& image_size,
                                                CameraModelId default_model) {
  io::ColmapDatabaseCamera row;
  row.width = image_size.width;
  row.height = image_size.height;
  if (camera) {
    row.model_id = static_cast<int>(camera->model);
    row.params = camera->Params();
    const int pp = CameraModelPrincipalPointIndex(camera->model);
    row.params[pp] = io::ToColmapPixel(row.params[pp]);
    row.params[pp + 1] = io::ToColmapPixel(row.params[pp + 1]);
    row.prior_focal_length = true;
  } else {
    // What COLMAP's feature extractor writes when it knows nothing (default_focal_length_factor
    // 1.2, principal point at the image centre, COLMAP's pixel convention).
    Camera fallback;
    fallback.model = default_model;
    fallback.width = image_size.width;
    fallback.height = image_size.height;
    fallback.fx = fallback.fy = 1.2 * std::max(image_size.width, image_size.height);
    fallback.cx = image_size.width / 2.0 - 0.5;
    fallback.cy = image_size.height / 2.0 - 0.5;
    row.model_id = static_cast<int>(default_model);
    row.params = fallback.Params();
    const int pp = CameraModelPrincipalPointIndex(default_model);
    row.params[pp] = io::ToColmapPixel(row.params[pp]);
    row.params[pp + 1] = io::ToColmapPixel(row.params[pp + 1]);
    row.prior_focal_length = false;
  }
  return row;
}

ColmapExportSummary WriteTracksToColmapDatabase(const frontend::FeatureTracks& tracks,
                                                const std::optional<Camera>& camera,
                                                const ColmapExportOptions& options,
                                                io::ColmapDatabase* database) {
  options.Check();
  COMIC_CHECK(database != nullptr, kInvalidArgument, "COLMAP export needs a database");
  tracks.Check();
  COMIC_CHECK(tracks.NumFrames() > 0, kInvalidArgument, "COLMAP export: the tracks hold no frames");
  COMIC_CHECK(tracks.frame_names.size() == tracks.NumFrames(), kInvalidArgument,
              "COLMAP export: the tracks have no frame names (COLMAP needs image names)");
  COMIC_CHECK(tracks.image_size.width > 0 && tracks.image_size.height > 0, kInvalidArgument,
              "COLMAP export: the tracks have no image size");
  if (camera) {
    camera->Check();
    COMIC_CHECK(
        camera->width == tracks.image_size.width && camera->height == tracks.image_size.height,
        kInvalidArgument,
        "COLMAP export: camera is " << camera->width << "x" << camera->height
                                    << " but the frames are " << tracks.image_size.width << "x"
                                    << tracks.image_size.height);
  }
  COMIC_CHECK(database->NumCameras() == 0 && database->NumImages() == 0, kInvalidArgument,
              database->path() << ": COLMAP export needs an empty database");

  ColmapExportSummary summary;
  summary.known_intrinsics = camera.has_value();
  io::ColmapDatabase::Transaction transaction(database);
  const int64_t camera_id = database->WriteCamera(
      ToColmapDatabaseCamera(camera, tracks.image_size, options.default_camera_model));

  // Frame i is image i + 1.
  for (size_t i = 0; i < tracks.NumFrames(); ++i) {
    io::ColmapDatabaseImage image;
    image.image_id = static_cast<int64_t>(i) + 1;
    image.name = options.image_name_prefix + tracks.frame_names[i];
    image.camera_id = camera_id;
    database->WriteImage(image);
    const frontend::FeatureSet& features = tracks.features[i];
    io::ColmapKeypoints keypoints(static_cast<Eigen::Index>(features.size()), 2);
    for (size_t k = 0; k < features.size(); ++k) {
      keypoints(k, 0) = static_cast<float>(io::ToColmapPixel(features[k].x));
      keypoints(k, 1) = static_cast<float>(io::ToColmapPixel(features[k].y));
    }
    database->WriteKeypoints(image.image_id, keypoints);
    summary.num_keypoints += keypoints.rows();
  }
  summary.num_images = static_cast<int>(tracks.NumFrames());

  // Verify every pair (in parallel: each result goes to its own slot, so the output does not
  // depend on the thread count), then write them in pair order.
  const std::map<FramePair, io::ColmapFeatureMatches> pair_matches =
      CollectPairMatches(tracks, options.pair_window);
  std::vector<const std::pair<const FramePair, io::ColmapFeatureMatches>*> pairs;
  for (const auto& entry : pair_matches) pairs.push_back(&entry);
  std::vector<VerifiedPair> verified(pairs.size());
  ParallelFor(pairs.size(), options.num_threads, [&](size_t p) {
    const FramePair& frames = pairs[p]->first;
    const io::ColmapFeatureMatches& matches = pairs[p]->second;
    std::vector<Eigen::Vector2d> points1, points2;
    points1.reserve(matches.size());
    points2.reserve(matches.size());
    for (const io::ColmapFeatureMatch& match : matches) {
      const frontend::Feature& f1 = tracks.features[frames.first][match.point2D_idx1];
      const frontend::Feature& f2 = tracks.features[frames.second][match.point2D_idx2];
      points1.emplace_back(f1.x, f1.y);
      points2.emplace_back(f2.x, f2.y);
    }
    verified[p] = camera ? VerifyCalibrated(*camera, points1, points2, matches, options)
                         : VerifyUncalibrated(points1, points2, matches, options);
  });

  for (size_t p = 0; p < pairs.size(); ++p) {
    const auto& [frames, matches] = *pairs[p];
    const int64_t image_id1 = frames.first + 1;
    const int64_t image_id2 = frames.second + 1;
    database->WriteMatches(image_id1, image_id2, matches);
    database->WriteTwoViewGeometry(image_id1, image_id2, verified[p].geometry);
    ++summary.num_matched_pairs;
    summary.num_matches += static_cast<int64_t>(matches.size());
    if (verified[p].geometry.config != io::kColmapDegenerate) {
      ++summary.num_verified_pairs;
      summary.num_inlier_matches +=
          static_cast<int64_t>(verified[p].geometry.inlier_matches.size());
    }
    summary.num_pairs_allowing_default_init += verified[p].allows_default_init ? 1 : 0;
    summary.max_init_triangulation_angle_deg = std::max(summary.max_init_triangulation_angle_deg,
                                                        verified[p].init_triangulation_angle_deg);
  }
  transaction.Commit();
  return summary;
}

void CheckColmapDatabaseOutput(const std::string& path, bool overwrite) {
  io::CheckWritableFile(path, overwrite);
  io::CheckSqliteFileReplaceable(path);
}

ColmapExportSummary ExportTracksToColmapDatabase(const frontend::FeatureTracks& tracks,
                                                 const std::optional<Camera>& camera,
                                                 const ColmapExportOptions& options,
                                                 const std::string& path, bool overwrite) {
  options.Check();
  ColmapExportSummary summary;
  io::WriteAtomically(
      path,
      [&](const std::string& temp_path) {
        // A stale temporary file from a killed run must not be extended.
        std::error_code ec;
        std::filesystem::remove(temp_path, ec);
        io::ColmapDatabase database = io::ColmapDatabase::Open(temp_path);
        summary = WriteTracksToColmapDatabase(tracks, camera, options, &database);
        database.Close();
      },
      overwrite, io::SqliteReplacement());
  return summary;
}

}  // namespace comic::sfm
