#include "sfm/track_labels.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

frontend::SideChange Sides(float plus, float minus) {
  frontend::SideChange sides;
  sides.measured = true;
  sides.plus_mean = plus;
  sides.minus_mean = minus;
  sides.num_compared = 3;
  return sides;
}

TEST(TrackLabels, EachCombinationOfSidesAndDriftHasItsLabel) {
  const std::vector<frontend::SideChange> sides = {
      Sides(0.1f, 0.1f),  // both sides keep their look
      Sides(0.1f, 0.9f),  // the bright side keeps it: an object's corner before a moving scene
      Sides(0.9f, 0.2f),  // the dark side keeps it
      Sides(0.5f, 0.9f),  // one has changed, the other neither kept nor changed
      Sides(0.9f, 0.8f),  // neither
      Sides(0.1f, 0.1f),  // both, but the track strays from every point
      {},                 // no sides, in the model without drift
      {},                 // no sides, not in the model
  };
  const std::vector<std::optional<double>> drift = {0.3, 0.3, std::nullopt, 0.3,
                                                    0.3, 2.5, 0.4,          std::nullopt};
  const std::vector<LabelledTrack> labels = LabelTracks(sides, drift, {});
  ASSERT_EQ(labels.size(), sides.size());
  EXPECT_EQ(labels[0].label, TrackLabel::kInterior);
  EXPECT_EQ(labels[1].label, TrackLabel::kBoundary);
  EXPECT_EQ(labels[1].object_side, frontend::PatchSide::kPlus);
  EXPECT_EQ(labels[2].label, TrackLabel::kBoundary);
  EXPECT_EQ(labels[2].object_side, frontend::PatchSide::kMinus);
  EXPECT_EQ(labels[3].label, TrackLabel::kInterior);
  EXPECT_EQ(labels[4].label, TrackLabel::kSliding);
  EXPECT_EQ(labels[5].label, TrackLabel::kSliding);
  EXPECT_EQ(labels[6].label, TrackLabel::kInterior);
  EXPECT_EQ(labels[7].label, TrackLabel::kUnknown);
  EXPECT_EQ(TrackLabelName(TrackLabel::kSliding), "sliding");
}

TEST(TrackLabels, RefusesBadOptionsAndLengthsThatDiffer) {
  TrackLabelOptions options;
  options.side_kept_max = 0;
  EXPECT_THROW(LabelTracks({}, {}, options), Error);
  options = TrackLabelOptions();
  options.side_changed_min = 0.3;  // below side_kept_max
  EXPECT_THROW(LabelTracks({}, {}, options), Error);
  options = TrackLabelOptions();
  options.drift_max_px = -1;
  EXPECT_THROW(LabelTracks({}, {}, options), Error);
  EXPECT_THROW(LabelTracks({Sides(0, 0)}, {}, TrackLabelOptions()), Error);
}

}  // namespace
}  // namespace comic::sfm
