#include "sfm/model_self_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/core/error.h"

namespace comic::sfm {

void ModelSelfCheckOptions::Check() const {
  COMIC_CHECK(min_shared_tracks >= 8, kInvalidArgument,
              "self-check min_shared_tracks must be >= 8, got " << min_shared_tracks);
  COMIC_CHECK(min_parallax_deg >= 0, kInvalidArgument, "self-check min_parallax_deg must be >= 0");
  COMIC_CHECK(max_error_ratio >= 1, kInvalidArgument,
              "self-check max_error_ratio must be >= 1, got " << max_error_ratio);
  COMIC_CHECK(min_error_px > 0, kInvalidArgument, "self-check min_error_px must be > 0");
  COMIC_CHECK(max_disagreeing_fraction >= 0 && max_disagreeing_fraction <= 1, kInvalidArgument,
              "self-check max_disagreeing_fraction must be in [0, 1]");
  COMIC_CHECK(min_inlier_ratio >= 0 && min_inlier_ratio <= 1, kInvalidArgument,
              "self-check min_inlier_ratio must be in [0, 1]");
  COMIC_CHECK(min_disagreeing_pairs >= 1, kInvalidArgument,
              "self-check min_disagreeing_pairs must be >= 1");
  COMIC_CHECK(min_pairs >= 1, kInvalidArgument, "self-check min_pairs must be >= 1");
  COMIC_CHECK(max_pairs_per_frame >= 1, kInvalidArgument,
              "self-check max_pairs_per_frame must be >= 1");
  two_view.Check();
}

namespace {

// Observations further apart than this along one track are not counted as a pair: the count is
// quadratic in a track's length, and a long video track's far ends are seen from many pairs.
constexpr size_t kMaxObservationSpan = 50;

uint64_t PairKey(int frame1, int frame2) {
  return (static_cast<uint64_t>(frame1) << 32) | static_cast<uint32_t>(frame2);
}

// Per registered frame, (track, feature) sorted by track: the frame's side of every pair.
using FrameTracks = std::vector<std::vector<std::pair<int, int>>>;

FrameTracks RegisteredFrameTracks(const std::vector<char>& registered,
                                  const frontend::FeatureTracks& tracks) {
  FrameTracks frame_tracks(tracks.NumFrames());
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : tracks.tracks[t].observations) {
      if (registered[obs.frame]) {
        frame_tracks[obs.frame].emplace_back(static_cast<int>(t), obs.feature);
      }
    }
  }
  return frame_tracks;  // sorted by track: tracks are visited in order
}

// Tracks shared by each pair of registered frames (frame1 < frame2).
std::unordered_map<uint64_t, int> SharedTrackCounts(const std::vector<char>& registered,
                                                    const frontend::FeatureTracks& tracks) {
  std::unordered_map<uint64_t, int> counts;
  std::vector<int> frames;
  for (const frontend::Track& track : tracks.tracks) {
    frames.clear();
    for (const frontend::TrackObservation& obs : track.observations) {
      if (registered[obs.frame]) frames.push_back(obs.frame);
    }
    for (size_t a = 0; a < frames.size(); ++a) {
      const size_t end = std::min(frames.size(), a + 1 + kMaxObservationSpan);
      for (size_t b = a + 1; b < end; ++b) ++counts[PairKey(frames[a], frames[b])];
    }
  }
  return counts;
}

// The median of `values` (0 when empty).
double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

// Where the model puts each registered frame's camera, and the median depth of the 3-D points it
// sees (camera units; 0 without points): computed once, read for every pair.
struct ViewGeometry {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double median_depth = 0.0;
};

std::vector<ViewGeometry> RegisteredViews(const Reconstruction& model, size_t num_frames) {
  std::vector<ViewGeometry> views(num_frames);
  for (const image_t image_id : model.RegisteredImageIds()) {
    const size_t frame = static_cast<size_t>(image_id) - 1;
    if (frame >= num_frames) continue;
    const Image& image = model.image(image_id);
    std::vector<double> depths;
    for (const Point2D& point : image.points2D) {
      if (!point.HasPoint3D()) continue;
      depths.push_back((image.cam_from_world * model.point3D(point.point3D_id).xyz).z());
    }
    views[frame] = {ProjectionCenter(image.cam_from_world), Median(std::move(depths))};
  }
  return views;
}

// The parallax the model gives a pair: its baseline seen from the nearer median depth, degrees.
double ModelParallaxDeg(const ViewGeometry& view1, const ViewGeometry& view2) {
  const double depth = std::min(view1.median_depth, view2.median_depth);
  if (depth <= 0) return 0.0;
  return 2.0 * std::atan2(0.5 * (view1.center - view2.center).norm(), depth) * 180.0 / M_PI;
}

// Per frame, its partners in the order they are tried: those the model gives enough parallax
// for a well-conditioned essential matrix, most shared tracks first (pairs matched directly
// rather than joined through long chains of other frames).
std::vector<std::vector<int>> PartnerCandidates(const std::unordered_map<uint64_t, int>& counts,
                                                const Reconstruction& model, size_t num_frames,
                                                const ModelSelfCheckOptions& options) {
  const std::vector<ViewGeometry> views = RegisteredViews(model, num_frames);
  std::vector<std::vector<std::pair<int, int>>> by_frame(num_frames);  // (partner, count)
  for (const auto& [key, count] : counts) {
    if (count < options.min_shared_tracks) continue;
    const int frame1 = static_cast<int>(key >> 32);
    const int frame2 = static_cast<int>(key & 0xffffffffu);
    if (ModelParallaxDeg(views[frame1], views[frame2]) < options.min_parallax_deg) {
      continue;
    }
    by_frame[frame1].emplace_back(frame2, count);
  }
  std::vector<std::vector<int>> partners(num_frames);
  for (size_t frame = 0; frame < num_frames; ++frame) {
    std::vector<std::pair<int, int>>& candidates = by_frame[frame];
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
      return a.second != b.second ? a.second > b.second : a.first < b.first;
    });
    for (const auto& [partner, count] : candidates) partners[frame].push_back(partner);
  }
  return partners;
}

struct PairVerdict {
  bool kept = false;
  int inliers = 0;
  int shared_tracks = 0;
  double rotation_difference_deg = 0.0;
  // Median Sampson distances (pixels) of the pair's inliers to the model's epipolar geometry and
  // to the pair's own.
  double model_median_error_px = 0.0;
  double own_median_error_px = 0.0;
};

// Sampson distance of a normalised correspondence to the epipolar geometry `essential`.
double SampsonDistance(const Eigen::Matrix3d& essential, const Eigen::Vector2d& normalized1,
                       const Eigen::Vector2d& normalized2) {
  const Eigen::Vector3d x1 = normalized1.homogeneous();
  const Eigen::Vector3d x2 = normalized2.homogeneous();
  const Eigen::Vector3d line2 = essential * x1;
  const Eigen::Vector3d line1 = essential.transpose() * x2;
  const double residual = x2.dot(line2);
  const double denominator = line2.head<2>().squaredNorm() + line1.head<2>().squaredNorm();
  return denominator > 0 ? std::abs(residual) / std::sqrt(denominator) : 0.0;
}

Eigen::Matrix3d EssentialMatrix(const Rigid3d& cam2_from_cam1) {
  const Eigen::Vector3d t = cam2_from_cam1.translation.normalized();
  Eigen::Matrix3d cross;
  cross << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  return cross * cam2_from_cam1.rotation.toRotationMatrix();
}

PairVerdict CheckPair(const Reconstruction& model, const frontend::FeatureTracks& tracks,
                      const FrameTracks& frame_tracks, int frame1, int frame2,
                      const ModelSelfCheckOptions& options) {
  std::vector<Eigen::Vector2d> points1;
  std::vector<Eigen::Vector2d> points2;
  const auto& side1 = frame_tracks[frame1];
  const auto& side2 = frame_tracks[frame2];
  for (size_t a = 0, b = 0; a < side1.size() && b < side2.size();) {
    if (side1[a].first < side2[b].first) {
      ++a;
    } else if (side2[b].first < side1[a].first) {
      ++b;
    } else {
      const frontend::Feature& f1 = tracks.features[frame1][side1[a].second];
      const frontend::Feature& f2 = tracks.features[frame2][side2[b].second];
      points1.emplace_back(f1.x, f1.y);
      points2.emplace_back(f2.x, f2.y);
      ++a;
      ++b;
    }
  }
  const Image& image1 = model.image(static_cast<image_t>(frame1 + 1));
  const Image& image2 = model.image(static_cast<image_t>(frame2 + 1));
  const TwoViewGeometry geometry = EstimateCalibratedTwoViewGeometry(
      model.camera(image1.camera_id), model.camera(image2.camera_id), points1, points2,
      options.two_view);
  PairVerdict verdict;
  verdict.inliers = geometry.num_inliers;
  verdict.shared_tracks = static_cast<int>(points1.size());
  // A homography-like pair (little parallax, or a plane) still tests the model's rotation: with
  // x2 ~ R x1, x2' [t]x R x1 vanishes for every t, so only a wrong R leaves a distance.
  verdict.kept =
      geometry.configuration != TwoViewConfiguration::kDegenerate &&
      geometry.num_inliers >= options.min_inlier_ratio * static_cast<double>(points1.size());
  if (verdict.kept) {
    const Rigid3d model_cam2_from_cam1 = image2.cam_from_world * image1.cam_from_world.Inverse();
    verdict.rotation_difference_deg =
        RotationAngleDeg(model_cam2_from_cam1.rotation, geometry.cam2_from_cam1.rotation);
    const Camera& camera1 = model.camera(image1.camera_id);
    const Camera& camera2 = model.camera(image2.camera_id);
    const Eigen::Matrix3d essential = EssentialMatrix(model_cam2_from_cam1);
    const Eigen::Matrix3d own_essential = EssentialMatrix(geometry.cam2_from_cam1);
    const double focal = 0.25 * (camera1.fx + camera1.fy + camera2.fx + camera2.fy);
    std::vector<double> model_errors;
    std::vector<double> own_errors;
    for (size_t i = 0; i < points1.size(); ++i) {
      if (!geometry.inlier_mask[i]) continue;
      const Eigen::Vector2d n1 = camera1.CamFromImage(points1[i]);
      const Eigen::Vector2d n2 = camera2.CamFromImage(points2[i]);
      model_errors.push_back(SampsonDistance(essential, n1, n2) * focal);
      own_errors.push_back(SampsonDistance(own_essential, n1, n2) * focal);
    }
    verdict.model_median_error_px = Median(model_errors);
    verdict.own_median_error_px = Median(own_errors);
  }

  return verdict;
}

std::string SuspectReason(const ModelSelfCheck& check, const ModelSelfCheckOptions& options) {
  std::ostringstream reason;
  reason.setf(std::ios::fixed);
  reason.precision(1);
  reason << check.pairs_disagreeing << " of " << check.pairs_checked
         << " frame pairs estimated on their own are not explained by the model's cameras (their "
            "matches lie more than "
         << options.max_error_ratio
         << " times farther from the model's epipolar lines than from their own; median pair "
         << check.median_error_ratio << " times, rotations " << check.median_rotation_difference_deg
         << " deg apart)";
  return reason.str();
}

}  // namespace

ModelSelfCheck CheckModelAgainstItsPairs(const Reconstruction& model,
                                         const frontend::FeatureTracks& tracks,
                                         const ModelSelfCheckOptions& options) {
  options.Check();
  const size_t num_frames = tracks.NumFrames();
  std::vector<char> registered(num_frames, 0);
  for (const image_t image_id : model.RegisteredImageIds()) {
    const size_t frame = static_cast<size_t>(image_id) - 1;
    if (frame < num_frames) registered[frame] = 1;
  }
  const FrameTracks frame_tracks = RegisteredFrameTracks(registered, tracks);
  const std::vector<std::vector<int>> partners =
      PartnerCandidates(SharedTrackCounts(registered, tracks), model, num_frames, options);

  std::vector<double> differences;
  std::vector<double> error_ratios;
  ModelSelfCheck check;
  for (size_t frame = 0; frame < num_frames; ++frame) {
    int kept = 0;
    int tried = 0;
    for (const int partner : partners[frame]) {
      if (kept >= options.max_pairs_per_frame || tried >= 2 * options.max_pairs_per_frame) break;
      ++tried;
      const PairVerdict verdict =
          CheckPair(model, tracks, frame_tracks, static_cast<int>(frame), partner, options);
      if (!verdict.kept) continue;
      ++kept;
      const double ratio = verdict.model_median_error_px /
                           std::max(verdict.own_median_error_px, options.min_error_px);
      differences.push_back(verdict.rotation_difference_deg);
      error_ratios.push_back(ratio);
      if (ratio > options.max_error_ratio) {
        check.disagreeing.push_back({static_cast<int>(frame), partner, ratio,
                                     verdict.rotation_difference_deg, verdict.inliers,
                                     verdict.shared_tracks});
      }
    }
  }

  check.pairs_checked = static_cast<int>(differences.size());
  check.pairs_disagreeing = static_cast<int>(check.disagreeing.size());
  for (const double difference : differences) {
    check.max_rotation_difference_deg = std::max(check.max_rotation_difference_deg, difference);
  }
  check.median_rotation_difference_deg = Median(differences);
  check.median_error_ratio = Median(error_ratios);
  check.suspect = check.pairs_checked >= options.min_pairs &&
                  check.pairs_disagreeing >= options.min_disagreeing_pairs &&
                  check.pairs_disagreeing >
                      options.max_disagreeing_fraction * static_cast<double>(check.pairs_checked);
  if (check.suspect) check.reason = SuspectReason(check, options);
  return check;
}

KeptModelChoice ChooseKeptModel(const std::vector<const Reconstruction*>& models,
                                const frontend::FeatureTracks& tracks,
                                const ModelSelfCheckOptions& options, double yield_fraction) {
  COMIC_CHECK(!models.empty(), kInvalidArgument, "ChooseKeptModel: no model");
  KeptModelChoice choice;
  choice.check = CheckModelAgainstItsPairs(*models.front(), tracks, options);
  if (!choice.check.suspect) return choice;
  const size_t first_frames = models.front()->NumRegisteredImages();
  for (size_t m = 1; m < models.size(); ++m) {
    const double frames = static_cast<double>(models[m]->NumRegisteredImages());
    if (frames < yield_fraction * static_cast<double>(first_frames)) continue;
    ModelSelfCheck other = CheckModelAgainstItsPairs(*models[m], tracks, options);
    if (other.suspect || other.pairs_checked < options.min_pairs) continue;
    other.passed_over_model_frames = static_cast<int>(first_frames);
    other.passed_over_pairs_disagreeing = choice.check.pairs_disagreeing;
    return {m, std::move(other)};
  }
  return choice;
}

}  // namespace comic::sfm
