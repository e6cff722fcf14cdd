#include "sfm/track_labels.h"

#include "io/core/error.h"

namespace comic::sfm {

namespace {

LabelledTrack LabelOne(const frontend::SideChange& sides, const std::optional<double>& drift,
                       const TrackLabelOptions& options) {
  if (drift && *drift > options.drift_max_px) return {TrackLabel::kSliding};
  if (!sides.measured) return {drift ? TrackLabel::kInterior : TrackLabel::kUnknown};
  const bool plus_kept = sides.plus_mean <= options.side_kept_max;
  const bool minus_kept = sides.minus_mean <= options.side_kept_max;
  const bool plus_changed = sides.plus_mean >= options.side_changed_min;
  const bool minus_changed = sides.minus_mean >= options.side_changed_min;
  if (plus_changed && minus_changed) return {TrackLabel::kSliding};
  if (plus_kept && minus_changed) return {TrackLabel::kBoundary, frontend::PatchSide::kPlus};
  if (minus_kept && plus_changed) return {TrackLabel::kBoundary, frontend::PatchSide::kMinus};
  return {TrackLabel::kInterior};
}

}  // namespace

std::string TrackLabelName(TrackLabel label) {
  switch (label) {
    case TrackLabel::kUnknown:
      return "unknown";
    case TrackLabel::kInterior:
      return "interior";
    case TrackLabel::kBoundary:
      return "boundary";
    case TrackLabel::kSliding:
      return "sliding";
  }
  return "unknown";
}

void TrackLabelOptions::Check() const {
  COMIC_CHECK(side_kept_max > 0 && side_kept_max < side_changed_min && side_changed_min < 2,
              kInvalidArgument,
              "track labels: need 0 < side_kept_max < side_changed_min < 2, got "
                  << side_kept_max << " and " << side_changed_min);
  COMIC_CHECK(drift_max_px > 0, kInvalidArgument,
              "track labels: drift_max_px must be positive, got " << drift_max_px);
}

std::vector<LabelledTrack> LabelTracks(const std::vector<frontend::SideChange>& sides,
                                       const std::vector<std::optional<double>>& drift,
                                       const TrackLabelOptions& options) {
  options.Check();
  COMIC_CHECK(
      sides.size() == drift.size(), kInvalidArgument,
      "track labels: " << sides.size() << " side changes for " << drift.size() << " drifts");
  std::vector<LabelledTrack> labels;
  labels.reserve(sides.size());
  for (size_t t = 0; t < sides.size(); ++t) labels.push_back(LabelOne(sides[t], drift[t], options));
  return labels;
}

}  // namespace comic::sfm
