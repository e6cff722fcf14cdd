#include "sfm/pose_gap_filling.h"

#include <algorithm>
#include <random>
#include <set>

#include "io/core/error.h"
#include "sfm/rotation_only_path.h"

namespace comic::sfm {

void PoseGapFillingOptions::Check() const {
  COMIC_CHECK(min_num_inliers >= 2, kInvalidArgument,
              "pose gap filling min_num_inliers must be >= 2, got " << min_num_inliers);
  COMIC_CHECK(min_inlier_ratio >= 0 && min_inlier_ratio <= 1, kInvalidArgument,
              "pose gap filling min_inlier_ratio must be in [0, 1]");
  COMIC_CHECK(max_error_px > 0, kInvalidArgument,
              "pose gap filling max_error_px must be > 0, got " << max_error_px);
  COMIC_CHECK(num_trials >= 1, kInvalidArgument, "pose gap filling num_trials must be >= 1");
  COMIC_CHECK(max_interpolated_gap >= 0, kInvalidArgument,
              "pose gap filling max_interpolated_gap must be >= 0");
}

namespace {

image_t ImageOf(int frame) { return static_cast<image_t>(frame + 1); }

class GapFiller {
 public:
  GapFiller(const frontend::FeatureTracks& tracks, const PoseGapFillingOptions& options,
            Reconstruction* model)
      : tracks_(tracks), options_(options), model_(*model) {
    const int num_frames = static_cast<int>(tracks.NumFrames());
    posed_.assign(num_frames, 0);
    track_of_feature_.resize(num_frames);
    for (int frame = 0; frame < num_frames; ++frame) {
      COMIC_CHECK(model_.ExistsImage(ImageOf(frame)), kInvalidArgument,
                  "pose gap filling: the model has no image for frame " << frame);
      posed_[frame] = model_.image(ImageOf(frame)).registered;
      track_of_feature_[frame].assign(tracks.features[frame].size(), -1);
    }
    track_point_.assign(tracks.tracks.size(), kInvalidPoint3DId);
    for (size_t t = 0; t < tracks.tracks.size(); ++t) {
      for (const frontend::TrackObservation& obs : tracks.tracks[t].observations) {
        track_of_feature_[obs.frame][obs.feature] = static_cast<int>(t);
        const Image& image = model_.image(ImageOf(obs.frame));
        if (image.registered && track_point_[t] == kInvalidPoint3DId) {
          track_point_[t] = image.points2D[obs.feature].point3D_id;
        }
      }
    }
  }

  // Sweeps over the frames until no frame adjacent to a posed one gains a rotation.
  std::vector<int> PoseByRotation(const std::vector<char>& fillable) {
    std::vector<int> posed;
    std::set<std::pair<int, int>> tried;  // (frame, neighbour)
    const int num_frames = static_cast<int>(posed_.size());
    for (bool progress = true; progress;) {
      progress = false;
      for (int frame = 0; frame < num_frames; ++frame) {
        if (posed_[frame] || !fillable[frame]) continue;
        for (int neighbour : {frame - 1, frame + 1}) {
          if (neighbour < 0 || neighbour >= num_frames || !posed_[neighbour]) continue;
          if (!tried.insert({frame, neighbour}).second) continue;
          if (!PoseAbout(frame, neighbour)) continue;
          posed.push_back(frame);
          progress = true;
          break;
        }
      }
    }
    std::sort(posed.begin(), posed.end());
    return posed;
  }

  // Interpolates runs of fillable frames between two posed frames close enough; the poses are
  // returned, not set in the model (pose_gap_filling.h).
  void Interpolate(const std::vector<char>& fillable, PoseGapFilling* result) {
    const int num_frames = static_cast<int>(posed_.size());
    int previous = -1;
    for (int frame = 0; frame < num_frames; ++frame) {
      if (!posed_[frame]) continue;
      const int gap = frame - previous - 1;
      if (previous >= 0 && gap > 0 && gap <= options_.max_interpolated_gap) {
        bool all_fillable = true;
        for (int f = previous + 1; f < frame; ++f) all_fillable = all_fillable && fillable[f];
        if (all_fillable) {
          for (int f = previous + 1; f < frame; ++f) {
            result->interpolated_frames.push_back(f);
            result->interpolated_poses.push_back(InterpolatePose(previous, frame, f));
          }
        }
      }
      previous = frame;
    }
  }

 private:
  // Tries to pose `frame` by a rotation about the centre of `neighbour` (posed).
  bool PoseAbout(int frame, int neighbour) {
    const Image& other = model_.image(ImageOf(neighbour));
    const Camera& camera = model_.camera(model_.image(ImageOf(frame)).camera_id);
    const Eigen::Vector3d center = ProjectionCenter(other.cam_from_world);
    const Eigen::Matrix3d world_from_other =
        other.cam_from_world.rotation.toRotationMatrix().transpose();
    std::vector<Eigen::Vector3d> world_rays, camera_rays;
    for (size_t feature = 0; feature < tracks_.features[frame].size(); ++feature) {
      const int t = track_of_feature_[frame][feature];
      if (t < 0) continue;
      Eigen::Vector3d direction;
      if (track_point_[t] != kInvalidPoint3DId && model_.ExistsPoint3D(track_point_[t])) {
        direction = (model_.point3D(track_point_[t]).xyz - center).normalized();
      } else {
        const int other_feature = tracks_.tracks[t].FeatureInFrame(neighbour);
        if (other_feature < 0) continue;
        direction = world_from_other * Ray(camera, neighbour, other_feature);
      }
      world_rays.push_back(direction);
      camera_rays.push_back(Ray(camera, frame, static_cast<int>(feature)));
    }
    std::mt19937 random(1);
    const double max_angle = options_.max_error_px / (0.5 * (camera.fx + camera.fy));
    const auto fit = EstimateRayRotation(world_rays, camera_rays, max_angle,
                                         options_.min_num_inliers, options_.num_trials, &random);
    if (!fit || static_cast<double>(fit->inliers.size()) <
                    options_.min_inlier_ratio * static_cast<double>(world_rays.size())) {
      return false;
    }
    const Eigen::Quaterniond rotation = Eigen::Quaterniond(fit->rotation).normalized();
    SetPose(frame, Rigid3d(rotation, -(rotation * center)));
    return true;
  }

  Eigen::Vector3d Ray(const Camera& camera, int frame, int feature) const {
    const frontend::Feature& f = tracks_.features[frame][feature];
    const Eigen::Vector2d normalized = camera.CamFromImage(Eigen::Vector2d(f.x, f.y));
    return Eigen::Vector3d(normalized.x(), normalized.y(), 1.0).normalized();
  }

  Rigid3d InterpolatePose(int first, int last, int frame) const {
    const Rigid3d& a = model_.image(ImageOf(first)).cam_from_world;
    const Rigid3d& b = model_.image(ImageOf(last)).cam_from_world;
    const double s = static_cast<double>(frame - first) / static_cast<double>(last - first);
    const Eigen::Quaterniond rotation = a.rotation.slerp(s, b.rotation).normalized();
    const Eigen::Vector3d center = (1.0 - s) * ProjectionCenter(a) + s * ProjectionCenter(b);
    return Rigid3d(rotation, -(rotation * center));
  }

  void SetPose(int frame, const Rigid3d& cam_from_world) {
    model_.image(ImageOf(frame)).cam_from_world = cam_from_world;
    model_.RegisterImage(ImageOf(frame));
    posed_[frame] = 1;
  }

  const frontend::FeatureTracks& tracks_;
  const PoseGapFillingOptions& options_;
  Reconstruction& model_;
  std::vector<char> posed_;
  std::vector<std::vector<int>> track_of_feature_;
  std::vector<point3D_t> track_point_;
};

}  // namespace

PoseGapFilling FillPoseGaps(const frontend::FeatureTracks& tracks,
                            const std::vector<char>& fillable, const PoseGapFillingOptions& options,
                            Reconstruction* model) {
  options.Check();
  COMIC_CHECK(model != nullptr, kInvalidArgument, "pose gap filling: no model");
  COMIC_CHECK(
      fillable.size() == tracks.NumFrames(), kInvalidArgument,
      "pose gap filling: " << fillable.size() << " flags for " << tracks.NumFrames() << " frames");
  GapFiller filler(tracks, options, model);
  PoseGapFilling result;
  result.rotation_only_frames = filler.PoseByRotation(fillable);
  filler.Interpolate(fillable, &result);
  return result;
}

}  // namespace comic::sfm
