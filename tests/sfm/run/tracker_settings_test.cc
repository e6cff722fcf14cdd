// The tracker settings of a run: a field left unset takes the default as the chosen pairing sets
// it up, a field given is kept as given; --match-window given makes auto a no-op.
#include "sfm/run/tracker_settings.h"

#include <gtest/gtest.h>

#include "frontend/matching/track_builder.h"
#include "io/core/error.h"
#include "io/image/image_sequence.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

frontend::PairingChoice Chosen(frontend::PairingMode mode, int window = 0) {
  frontend::PairingChoice choice;
  choice.chosen = {mode, window};
  return choice;
}

TEST(TrackerSettings, UnsetFieldsAreTheDefaults) {
  const frontend::TrackerOptions defaults = DefaultRunTrackerOptions();
  const frontend::TrackerOptions options = TrackerSettings().ToTrackerOptions();
  EXPECT_EQ(options.max_features, defaults.max_features);
  EXPECT_EQ(options.matcher.radius, defaults.matcher.radius);
  EXPECT_EQ(options.prediction, defaults.prediction);
  EXPECT_EQ(TrackerSettings().TrackConflictsName(),
            frontend::TrackConflictRuleName(defaults.conflict_rule));
}

TEST(TrackerSettings, PatchAlignmentAndContinuationAreKeptAsGiven) {
  EXPECT_FALSE(TrackerSettings().ToTrackerOptions().align_patches);
  TrackerSettings settings;
  settings.Give("align-patches", [](frontend::TrackerOptions& o) { o.align_patches = true; });
  settings.Give("min-window-eigenvalue",
                [](frontend::TrackerOptions& o) { o.min_window_eigenvalue = 20.0; });
  settings.Give("max-continued-frames",
                [](frontend::TrackerOptions& o) { o.continuation.max_continued_frames = 30; });
  settings.Give("bridge-frames",
                [](frontend::TrackerOptions& o) { o.continuation.bridge_frames = 3; });
  for (frontend::PairingMode mode :
       {frontend::PairingMode::kSequential, frontend::PairingMode::kExhaustive}) {
    const frontend::TrackerOptions options = TrackerOptionsForRun(settings, Chosen(mode), 10);
    EXPECT_TRUE(options.align_patches);
    EXPECT_EQ(options.min_window_eigenvalue, 20.0);
    EXPECT_EQ(options.continuation.max_continued_frames, 30);
    EXPECT_EQ(options.continuation.bridge_frames, 3);
  }
  // Continuation without alignment is refused, naming the field.
  settings.Give("align-patches", [](frontend::TrackerOptions& o) { o.align_patches = false; });
  EXPECT_THROW(settings.ToTrackerOptions(), Error);
}

TEST(TrackerSettings, ThePairingSetsUpWhatWasNotGiven) {
  TrackerSettings settings;
  settings.Give("search-radius", [](frontend::TrackerOptions& o) { o.matcher.radius = 25.0; });
  settings.Give("max-features", [](frontend::TrackerOptions& o) { o.max_features = 500; });
  const frontend::TrackerOptions options =
      TrackerOptionsForRun(settings, Chosen(frontend::PairingMode::kExhaustive), 10);
  // Exhaustive matching: every later frame, verified, turned, coarse-to-fine ...
  EXPECT_EQ(options.match_window, 9);
  EXPECT_EQ(options.verify_min_gap, 1);
  EXPECT_TRUE(options.match_turned_180);
  EXPECT_EQ(options.prediction, frontend::MotionPrediction::kCoarseToFine);
  // ... but the radius given wins over the pairing's 40 px.
  EXPECT_EQ(options.matcher.radius, 25.0);
  EXPECT_EQ(options.max_features, 500);

  settings.Give("match-turned", [](frontend::TrackerOptions& o) { o.match_turned_180 = false; });
  settings.Give("verify-min-gap", [](frontend::TrackerOptions& o) { o.verify_min_gap = 0; });
  const frontend::TrackerOptions kept =
      TrackerOptionsForRun(settings, Chosen(frontend::PairingMode::kExhaustive), 10);
  EXPECT_FALSE(kept.match_turned_180);
  EXPECT_EQ(kept.verify_min_gap, 0);
}

TEST(TrackerSettings, MatchWindowGivenLeavesAutoAlone) {
  const io::ImageSequence sequence =
      io::ImageSequence::Open(comic::test::ExampleDir() + "/image_l", {});
  TrackerSettings settings;
  settings.Give("match-window", [](frontend::TrackerOptions& o) { o.match_window = 3; });
  const frontend::PairingChoice choice = ChooseRunPairing("auto", settings, sequence);
  EXPECT_EQ(choice.chosen.mode, frontend::PairingMode::kSequential);
  EXPECT_FALSE(choice.measured);
  EXPECT_EQ(TrackerOptionsForRun(settings, choice, 12).match_window, 3);
  // Without it, auto looks at the frames: the bundled clip is a video.
  const frontend::PairingChoice measured = ChooseRunPairing("auto", TrackerSettings(), sequence);
  EXPECT_TRUE(measured.measured);
  EXPECT_TRUE(measured.looks_like_video);
}

TEST(TrackerSettings, BadNamesNameTheFlag) {
  TrackerSettings settings;
  try {
    settings.GiveName("prediction", "psychic");
    ADD_FAILURE() << "psychic accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_EQ(std::string(e.what()).rfind("--prediction: ", 0), 0u) << e.what();
  }
  EXPECT_FALSE(settings.Given("prediction"));  // a refused name is not given
  EXPECT_THROW(settings.GiveName("track-conflicts", "merge"), Error);
  EXPECT_THROW(settings.GiveName("search-radius", "wide"), Error);  // not a named option
  EXPECT_THROW(settings.MarkGiven("psychic-radius"), Error);        // not the table's
  settings.given.insert("psychic-radius");
  EXPECT_THROW(settings.ToTrackerOptions(), Error);
  settings.given.clear();
  settings.GiveName("prediction", "coarse-to-fine");
  EXPECT_EQ(settings.ToTrackerOptions().prediction, frontend::MotionPrediction::kCoarseToFine);
  const io::ImageSequence sequence =
      io::ImageSequence::Open(comic::test::ExampleDir() + "/image_l", {});
  EXPECT_THROW(ChooseRunPairing("window:0", TrackerSettings(), sequence), Error);
}

}  // namespace
}  // namespace comic::sfm
