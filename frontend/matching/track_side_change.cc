#include "frontend/matching/track_side_change.h"

#include <array>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "frontend/matching/level_line_sides.h"
#include "io/core/error.h"

namespace comic::frontend {

namespace {

using Patch = std::array<float, kPatchSize * kPatchSize>;

// What a track keeps from its first observation while it is being measured.
struct ReferenceSides {
  std::vector<PatchSide> mask;
  Patch patch{};
  double plus_sum = 0.0;
  double minus_sum = 0.0;
};

// The kPatchSize² patch centred on the feature's sub-pixel position (bilinear).
Patch SamplePatch(const cv::Mat& gray_float, const Feature& feature) {
  cv::Mat sampled;
  cv::getRectSubPix(gray_float, cv::Size(kPatchSize, kPatchSize), feature.Position(), sampled,
                    CV_32F);
  Patch patch;
  for (int v = 0; v < kPatchSize; ++v) {
    for (int u = 0; u < kPatchSize; ++u) patch[v * kPatchSize + u] = sampled.at<float>(v, u);
  }
  return patch;
}

// The normalised change of one side between two patches (see the header).
float SideChangeOf(const std::vector<PatchSide>& mask, PatchSide side, const Patch& first,
                   const Patch& later, double noise_variance) {
  double n = 0, sum_a = 0, sum_b = 0, sum_aa = 0, sum_bb = 0, sum_ab = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] != side) continue;
    const double a = first[i], b = later[i];
    n += 1;
    sum_a += a;
    sum_b += b;
    sum_aa += a * a;
    sum_bb += b * b;
    sum_ab += a * b;
  }
  if (n == 0) return 0.0f;
  const double var_a = std::max(0.0, sum_aa / n - (sum_a / n) * (sum_a / n));
  const double var_b = std::max(0.0, sum_bb / n - (sum_b / n) * (sum_b / n));
  const double cov = sum_ab / n - (sum_a / n) * (sum_b / n);
  // Mean of ((b - mean b) - (a - mean a))² = var a + var b - 2 cov.
  const double difference = std::max(0.0, var_a + var_b - 2.0 * cov);
  return static_cast<float>(difference / (var_a + var_b + noise_variance));
}

// Per frame, the tracks (long enough) with an observation there, and which observation.
std::vector<std::vector<std::pair<int, int>>> ObservationsByFrame(
    const FeatureTracks& tracks, const TrackSideChangeOptions& options) {
  std::vector<std::vector<std::pair<int, int>>> by_frame(tracks.NumFrames());
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    const Track& track = tracks.tracks[t];
    if (static_cast<int>(track.Length()) < options.min_track_length) continue;
    for (size_t o = 0; o < track.observations.size(); ++o) {
      by_frame[track.observations[o].frame].emplace_back(static_cast<int>(t), static_cast<int>(o));
    }
  }
  return by_frame;
}

}  // namespace

void TrackSideChangeOptions::Check() const {
  COMIC_CHECK(min_track_length >= 2, kInvalidArgument,
              "track side change: min_track_length must be at least 2, got " << min_track_length);
  COMIC_CHECK(noise_grey_levels > 0, kInvalidArgument,
              "track side change: noise_grey_levels must be positive, got " << noise_grey_levels);
}

std::vector<SideChange> MeasureTrackSideChanges(const FeatureTracks& tracks,
                                                const GrayFrameFn& gray,
                                                const TrackSideChangeOptions& options) {
  options.Check();
  std::vector<SideChange> changes(tracks.tracks.size());
  std::vector<std::unique_ptr<ReferenceSides>> references(tracks.tracks.size());
  const double noise_variance = options.noise_grey_levels * options.noise_grey_levels;
  const auto by_frame = ObservationsByFrame(tracks, options);
  for (size_t f = 0; f < by_frame.size(); ++f) {
    if (by_frame[f].empty()) continue;
    const cv::Mat image = gray(static_cast<int>(f));
    COMIC_CHECK(image.type() == CV_8UC1 && image.size() == tracks.image_size, kInvalidArgument,
                "track side change: frame " << f << " is not a grey image of the tracks' size");
    cv::Mat image_float;
    image.convertTo(image_float, CV_32F);
    for (const auto& [t, o] : by_frame[f]) {
      const Track& track = tracks.tracks[t];
      const Feature& feature = tracks.FeatureOf(track.observations[o]);
      std::unique_ptr<ReferenceSides>& reference = references[t];
      if (o == 0) {
        if (!PatchFits(feature, image.size())) continue;
        const LevelLineSides sides = ComputeLevelLineSides(image, feature);
        // A CoMIC feature's own mask comes back as it is, possibly with one side only.
        if (!HasBothSides(sides.mask)) continue;
        reference = std::make_unique<ReferenceSides>();
        reference->mask = sides.mask;
        reference->patch = SamplePatch(image_float, feature);
        changes[t].object_side = sides.object_side;
        continue;
      }
      if (reference == nullptr) continue;
      if (PatchFits(feature, image.size())) {
        const Patch later = SamplePatch(image_float, feature);
        SideChange& change = changes[t];
        change.plus_last = SideChangeOf(reference->mask, PatchSide::kPlus, reference->patch, later,
                                        noise_variance);
        change.minus_last = SideChangeOf(reference->mask, PatchSide::kMinus, reference->patch,
                                         later, noise_variance);
        reference->plus_sum += change.plus_last;
        reference->minus_sum += change.minus_last;
        ++change.num_compared;
      }
      if (o + 1 == static_cast<int>(track.Length())) {
        SideChange& change = changes[t];
        change.measured = change.num_compared > 0;
        if (change.measured) {
          change.plus_mean = static_cast<float>(reference->plus_sum / change.num_compared);
          change.minus_mean = static_cast<float>(reference->minus_sum / change.num_compared);
        }
        reference.reset();
      }
    }
  }
  return changes;
}

}  // namespace comic::frontend
