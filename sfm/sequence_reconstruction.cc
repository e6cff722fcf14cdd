#include "sfm/sequence_reconstruction.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>

#include "frontend/matching/combined_tracking.h"
#include "io/core/error.h"

namespace comic::sfm {

SequenceReconstructionOptions::SequenceReconstructionOptions() {
  tracker.prediction = frontend::MotionPrediction::kConstantVelocity;
  tracker.unpredicted_radius = 60.0;
  tracker.max_features = 2000;
}

void SequenceReconstructionOptions::Check() const {
  tracker.Check();
  if (image_set) image_set->Check();
  mapper.Check();
  moving_object.Check();
}

namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

void CheckMappingInputs(const io::ImageSequence& sequence, const Camera& camera,
                        const SequenceReconstructionOptions& options) {
  options.Check();
  camera.Check();
  COMIC_CHECK(
      camera.width == sequence.FrameSize().width && camera.height == sequence.FrameSize().height,
      kInvalidArgument,
      "camera is for " << camera.width << "x" << camera.height << " images, the frames are "
                       << sequence.FrameSize().width << "x" << sequence.FrameSize().height);
}

}  // namespace

SequenceTracking TrackFrames(const io::ImageSequence& sequence, const frontend::Detector& detector,
                             const SequenceReconstructionOptions& options,
                             const frontend::TrackingProgress& tracking_progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  SequenceTracking tracking;
  // The masks act here, once, for both paths: each frame's detection loses its masked features
  // before the tracker or the matcher selects from it.
  std::atomic<int64_t> masked(0);
  frontend::DetectionFilter filter;
  if (options.feature_masks) {
    COMIC_CHECK(options.feature_masks->NumFrames() == sequence.NumFrames() &&
                    (sequence.NumFrames() == 0 ||
                     options.feature_masks->MaskSize() == sequence.FrameSize()),
                kInvalidArgument,
                "feature masks: " << options.feature_masks->NumFrames() << " masks of "
                                  << options.feature_masks->MaskSize().width << "x"
                                  << options.feature_masks->MaskSize().height << " for "
                                  << sequence.NumFrames() << " frames of "
                                  << sequence.FrameSize().width << "x"
                                  << sequence.FrameSize().height);
    filter = options.feature_masks->Filter(&masked);
  }
  if (options.image_set) {
    frontend::ImageSetMatching matched = frontend::MatchImageSet(
        sequence, detector, *options.image_set,
        frontend::ProgressInFrames(tracking_progress, sequence.NumFrames()), filter);
    tracking.tracks = std::move(matched.tracks);
    tracking.track_building = matched.track_building;
    tracking.image_set_matching = matched.summary;
  } else {
    frontend::TrackingResult result = frontend::TrackSequenceWithDetector(
        sequence, detector, options.tracker, tracking_progress, filter);
    tracking.tracks = std::move(result.tracks);
    tracking.track_building = result.track_building;
  }
  tracking.masked_features = masked.load();
  tracking.time_s = Seconds(start);
  return tracking;
}

SequenceReconstruction ReconstructFromTracks(const io::ImageSequence& sequence,
                                             const frontend::Detector& detector,
                                             const Camera& camera,
                                             const SequenceReconstructionOptions& options,
                                             SequenceTracking tracking,
                                             const MapperProgressCallback& mapper_progress) {
  CheckMappingInputs(sequence, camera, options);
  // Tracks from a cache are of these frames by their key; this guards a caller that mixes them up.
  COMIC_CHECK(tracking.tracks.NumFrames() == sequence.NumFrames(), kInvalidArgument,
              "tracks of " << tracking.tracks.NumFrames() << " frames for a sequence of "
                           << sequence.NumFrames());
  const auto start = std::chrono::steady_clock::now();
  SequenceReconstruction run;
  run.detector_name = detector.Name();
  run.tracks = std::move(tracking.tracks);
  run.track_building = tracking.track_building;
  run.image_set_matching = tracking.image_set_matching;
  run.masked_features = tracking.masked_features;
  run.tracking_time_s = tracking.time_s;
  // Loop closure recognises places by the descriptors of the tracked features (the database
  // written afterwards reuses them).
  if (options.mapper.close_loops && !run.tracks.HasDescriptors() && run.tracks.NumFrames() > 0) {
    const auto describe_start = std::chrono::steady_clock::now();
    frontend::DescribeTrackedFeatures(sequence, &run.tracks, /*num_threads=*/0);
    run.tracking_time_s += Seconds(describe_start);
  }

  const auto mapping_start = std::chrono::steady_clock::now();
  run.input_size = sequence.SourceFrameSize();
  run.frame_size = sequence.FrameSize();
  const FrameMatcher seam_matcher =
      options.match_seams ? MakeSeamMatcher(sequence, detector, run.tracks, options.tracker)
                          : FrameMatcher();
  run.mapping =
      ReconstructIncrementally(run.tracks, camera, options.mapper, mapper_progress, seam_matcher);
  run.moving_object =
      CheckForMovingObject(run.tracks, camera, options.mapper, options.moving_object, &run.mapping);
  run.mapping_time_s = Seconds(mapping_start);

  const auto coloring_start = std::chrono::steady_clock::now();
  if (run.mapping.reconstruction.NumPoints3D() > 0) {
    ColorizeReconstruction(sequence, &run.mapping.reconstruction);
  }
  run.coloring_time_s = Seconds(coloring_start);
  run.wall_time_s = run.tracking_time_s + Seconds(start);
  return run;
}

SequenceReconstruction ReconstructSequence(const io::ImageSequence& sequence,
                                           const frontend::Detector& detector, const Camera& camera,
                                           const SequenceReconstructionOptions& options,
                                           const frontend::TrackingProgress& tracking_progress,
                                           const MapperProgressCallback& mapper_progress) {
  CheckMappingInputs(sequence, camera, options);  // before the tracking: a bad camera fails now
  return ReconstructFromTracks(sequence, detector, camera, options,
                               TrackFrames(sequence, detector, options, tracking_progress),
                               mapper_progress);
}

FrameMatcher MakeSeamMatcher(const io::ImageSequence& sequence, const frontend::Detector& detector,
                             const frontend::FeatureTracks& tracks,
                             const frontend::TrackerOptions& tracker) {
  frontend::TrackerOptions options = tracker;
  options.prediction = frontend::MotionPrediction::kCoarseToFine;
  options.match_window = 1;
  options.verify_min_gap = 1;
  options.match_turned_180 = false;
  options.Check();
  return [&sequence, &detector, &tracks, options](int frame1, int frame2) {
    frontend::Tracker matcher(options, detector.Name(), &detector);
    matcher.AddFrame(sequence.ReadFrame(frame1).gray, tracks.features[frame1]);
    matcher.AddFrame(sequence.ReadFrame(frame2).gray, tracks.features[frame2]);
    const frontend::TrackingResult result = matcher.Result();
    std::vector<std::pair<int, int>> matches;
    if (result.accepted_matches.empty()) return matches;
    for (const frontend::PatchMatch& match : result.accepted_matches.front()) {
      matches.emplace_back(match.index1, match.index2);
    }
    return matches;
  };
}

void ColorizeReconstruction(const io::ImageSequence& sequence, Reconstruction* reconstruction) {
  COMIC_CHECK(reconstruction != nullptr, kInvalidArgument, "colorize: no reconstruction");
  std::map<point3D_t, std::array<double, 4>> sums;  // r, g, b, count
  for (const auto& [image_id, image] : reconstruction->images()) {
    if (!image.registered || image.NumPoints3D() == 0) continue;
    const size_t frame = static_cast<size_t>(image_id) - 1;
    COMIC_CHECK(frame < sequence.NumFrames(), kInvalidArgument,
                "colorize: image " << image_id << " has no frame in the sequence");
    const cv::Mat color = sequence.ReadFrame(frame).color;
    for (const Point2D& point2D : image.points2D) {
      if (!point2D.HasPoint3D()) continue;
      const double x = std::clamp(point2D.xy.x(), 0.0, color.cols - 1.0);
      const double y = std::clamp(point2D.xy.y(), 0.0, color.rows - 1.0);
      const int x0 = std::min(static_cast<int>(x), std::max(color.cols - 2, 0));
      const int y0 = std::min(static_cast<int>(y), std::max(color.rows - 2, 0));
      const int x1 = std::min(x0 + 1, color.cols - 1);
      const int y1 = std::min(y0 + 1, color.rows - 1);
      const double ax = x - x0, ay = y - y0;
      std::array<double, 4>& sum = sums[point2D.point3D_id];
      for (int c = 0; c < 3; ++c) {
        const double value = (1 - ax) * (1 - ay) * color.at<cv::Vec3b>(y0, x0)[c] +
                             ax * (1 - ay) * color.at<cv::Vec3b>(y0, x1)[c] +
                             (1 - ax) * ay * color.at<cv::Vec3b>(y1, x0)[c] +
                             ax * ay * color.at<cv::Vec3b>(y1, x1)[c];
        sum[2 - c] += value;  // BGR -> RGB
      }
      sum[3] += 1.0;
    }
  }
  for (const auto& [point3D_id, sum] : sums) {
    Point3D& point = reconstruction->point3D(point3D_id);
    for (int c = 0; c < 3; ++c) {
      point.color[c] = static_cast<uint8_t>(std::clamp(std::lround(sum[c] / sum[3]), 0L, 255L));
    }
  }
}

}  // namespace comic::sfm
