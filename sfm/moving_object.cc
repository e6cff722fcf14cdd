#include "sfm/moving_object.h"

#include <optional>
#include <sstream>
#include <vector>

#include "io/core/error.h"
#include "sfm/track_drift.h"

namespace comic::sfm {
namespace {

// The tracks of `tracks` that `keep` marks, the frames and features as they are.
frontend::FeatureTracks TracksSubset(const frontend::FeatureTracks& tracks,
                                     const std::vector<bool>& keep) {
  frontend::FeatureTracks subset;
  subset.detector_name = tracks.detector_name;
  subset.image_size = tracks.image_size;
  subset.frame_names = tracks.frame_names;
  subset.features = tracks.features;
  subset.descriptors = tracks.descriptors;
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    if (keep[t]) subset.tracks.push_back(tracks.tracks[t]);
  }
  return subset;
}

// Which tracks a model can judge (>= 3 views in its frames), and which of those it does not
// explain.
struct Explanation {
  std::vector<bool> measured;
  std::vector<bool> unexplained;
  int num_measured = 0;
  int num_unexplained = 0;

  bool Explains(size_t track) const { return measured[track] && !unexplained[track]; }
};

Explanation ExplainTracks(const frontend::FeatureTracks& tracks, const Reconstruction& model,
                          double max_drift_px) {
  const std::vector<std::optional<double>> drift = MeasureTrackDrift(tracks, model);
  Explanation explanation;
  explanation.measured.assign(tracks.tracks.size(), false);
  explanation.unexplained.assign(tracks.tracks.size(), false);
  for (size_t t = 0; t < drift.size(); ++t) {
    if (!drift[t]) continue;
    explanation.measured[t] = true;
    ++explanation.num_measured;
    if (*drift[t] > max_drift_px) {
      explanation.unexplained[t] = true;
      ++explanation.num_unexplained;
    }
  }
  return explanation;
}

}  // namespace

void MovingObjectOptions::Check() const {
  COMIC_CHECK(max_explained_drift_px > 0, kInvalidArgument,
              "moving object: max_explained_drift_px must be > 0");
  COMIC_CHECK(min_unexplained_tracks >= 1, kInvalidArgument,
              "moving object: min_unexplained_tracks must be >= 1");
  COMIC_CHECK(max_tracks_mapped_again >= 1, kInvalidArgument,
              "moving object: max_tracks_mapped_again must be >= 1");
  COMIC_CHECK(min_unexplained_fraction > 0 && min_unexplained_fraction <= 1, kInvalidArgument,
              "moving object: min_unexplained_fraction must be in (0, 1]");
  COMIC_CHECK(min_second_model_frames > 0 && min_second_model_frames <= 1, kInvalidArgument,
              "moving object: min_second_model_frames must be in (0, 1]");
  COMIC_CHECK(max_shared_explanation > 0 && max_shared_explanation <= 1, kInvalidArgument,
              "moving object: max_shared_explanation must be in (0, 1]");
}

MovingObjectCheck CheckForMovingObject(const frontend::FeatureTracks& tracks, const Camera& camera,
                                       const IncrementalPipelineOptions& mapper_options,
                                       const MovingObjectOptions& options,
                                       IncrementalReconstruction* mapping) {
  COMIC_CHECK(mapping != nullptr, kInvalidArgument, "moving object: no model");
  options.Check();
  MovingObjectCheck check;
  if (!options.enabled || !HasModel(mapping->status)) return check;

  // Stage 1: the tracks the model explains.
  const Explanation first =
      ExplainTracks(tracks, mapping->reconstruction, options.max_explained_drift_px);
  check.measured_tracks = first.num_measured;
  check.unexplained_tracks = first.num_unexplained;
  const std::string unexplained = std::to_string(first.num_unexplained) + " of " +
                                  std::to_string(first.num_measured) + " tracks unexplained";
  if (first.num_unexplained < options.min_unexplained_tracks ||
      first.num_unexplained < options.min_unexplained_fraction * first.num_measured) {
    check.reason = unexplained + ": one motion";
    return check;
  }

  // Stage 2: the unexplained tracks mapped on their own (every k-th of them beyond the cap).
  check.mapped_again = true;
  std::vector<bool> mapped = first.unexplained;
  const int step = (first.num_unexplained + options.max_tracks_mapped_again - 1) /
                   options.max_tracks_mapped_again;
  for (size_t t = 0, seen = 0; t < mapped.size(); ++t) {
    if (mapped[t]) mapped[t] = seen++ % step == 0;
  }
  const IncrementalReconstruction second =
      ReconstructIncrementally(TracksSubset(tracks, mapped), camera, mapper_options);
  check.second_model_frames =
      HasModel(second.status) ? static_cast<int>(second.registered_frames.size()) : 0;
  const int first_frames = static_cast<int>(mapping->registered_frames.size());
  if (check.second_model_frames < options.min_second_model_frames * first_frames) {
    check.reason = unexplained + ", and they make no model of their own as large (" +
                   std::to_string(check.second_model_frames) + " of " +
                   std::to_string(first_frames) + " frames): one motion";
    return check;
  }

  // Stage 3: a second motion only if that model does not explain the first one's tracks too.
  const Explanation by_second =
      ExplainTracks(tracks, second.reconstruction, options.max_explained_drift_px);
  int first_explained = 0;
  int both_explained = 0;
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    if (!first.Explains(t)) continue;
    ++first_explained;
    if (by_second.Explains(t)) ++both_explained;
  }
  check.first_tracks_explained_by_second =
      first_explained > 0 ? static_cast<double>(both_explained) / first_explained : 0.0;
  std::ostringstream reason;
  reason.precision(3);
  reason << unexplained << " make a model of their own (" << check.second_model_frames << " of "
         << first_frames << " frames) that explains "
         << 100.0 * check.first_tracks_explained_by_second << " % of the model's tracks";
  if (check.first_tracks_explained_by_second >= options.max_shared_explanation) {
    check.reason = reason.str() + ": one world, one motion";
    return check;
  }
  check.second_motion = true;
  reason << ": two rigid motions, so the model may follow an object moving through the view "
            "(--masks can remove it)";
  check.reason = reason.str();
  ModelSelfCheck& self_check = mapping->self_check;
  if (!self_check.suspect) {
    self_check.suspect = true;
    self_check.reason = check.reason;
  }
  mapping->status = ReconstructionStatus::kSuspect;
  return check;
}

}  // namespace comic::sfm
