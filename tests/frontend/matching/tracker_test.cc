#include "frontend/matching/tracker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "frontend/baselines/harris_detector.h"
#include "frontend/evaluation/epipolar_check.h"
#include "io/core/error.h"
#include "io/datasets/kitti_odometry.h"
#include "io/image/image_sequence.h"
#include "tests/frontend/track_test_helpers.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

cv::Mat Texture(cv::Size size, uint64_t seed) {
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Scalar m, s;
  cv::meanStdDev(noise, m, s);
  cv::Mat out;
  noise.convertTo(out, CV_8U, 50 / s[0], 128 - 50 * m[0] / s[0]);
  return out;
}

// Frames of a textured scene translating by `step` pixels per frame.
std::vector<cv::Mat> TranslatingFrames(int count, cv::Point step, cv::Size size = {220, 160}) {
  const int margin = std::max(std::abs(step.x), std::abs(step.y)) * count + 5;
  const cv::Mat world = Texture({size.width + 2 * margin, size.height + 2 * margin}, 17);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    // Content at world (u, v) appears at (u − origin) : moving the window by −step moves the
    // content by +step.
    const cv::Rect window(margin - i * step.x, margin - i * step.y, size.width, size.height);
    frames.push_back(world(window).clone());
  }
  return frames;
}

// Fraction of track steps moving by `step` (within 1 px).
double CorrectStepFraction(const FeatureTracks& tracks, cv::Point step, int* steps = nullptr) {
  int total = 0, correct = 0;
  for (const Track& track : tracks.tracks) {
    for (size_t k = 1; k < track.observations.size(); ++k) {
      const cv::Point2f d = tracks.FeatureOf(track.observations[k]).Position() -
                            tracks.FeatureOf(track.observations[k - 1]).Position();
      ++total;
      correct += std::hypot(d.x - step.x, d.y - step.y) < 1.0 ? 1 : 0;
    }
  }
  if (steps) *steps = total;
  return total == 0 ? 0.0 : static_cast<double>(correct) / total;
}

TrackerOptions HarrisOptions() {
  TrackerOptions options;
  options.min_response = 1.0f;
  return options;
}

TEST(Tracker, ChainsMatchesOfATranslatingSceneIntoLongTracks) {
  const auto frames = TranslatingFrames(5, {3, 2});
  const HarrisDetector harris;
  const TrackingResult result =
      TrackFrames(frames, harris, HarrisOptions(), {"a", "b", "c", "d", "e"});
  const FeatureTracks& tracks = result.tracks;
  EXPECT_NO_THROW(tracks.Check());
  EXPECT_EQ(tracks.NumFrames(), 5u);
  EXPECT_EQ(tracks.detector_name, "harris");
  EXPECT_EQ(tracks.image_size, cv::Size(220, 160));
  EXPECT_EQ(tracks.frame_names[4], "e");
  int steps = 0;
  EXPECT_GT(CorrectStepFraction(tracks, {3, 2}, &steps), 0.95);
  int full_length = 0;
  for (const Track& t : tracks.tracks) full_length += t.Length() == 5 ? 1 : 0;
  EXPECT_GE(full_length, 30);
  ASSERT_EQ(result.mutual_matches.size(), 4u);
  ASSERT_EQ(result.accepted_matches.size(), 4u);
  for (size_t p = 0; p < 4; ++p) {
    EXPECT_LE(result.accepted_matches[p].size(), result.mutual_matches[p].size());
  }
}

TEST(Tracker, IsDeterministic) {
  const auto frames = TranslatingFrames(4, {2, -1});
  const HarrisDetector harris;
  const FeatureTracks a = TrackFrames(frames, harris, HarrisOptions()).tracks;
  const FeatureTracks b = TrackFrames(frames, harris, HarrisOptions()).tracks;
  ASSERT_EQ(a.tracks.size(), b.tracks.size());
  for (size_t t = 0; t < a.tracks.size(); ++t) {
    ASSERT_EQ(a.tracks[t].Length(), b.tracks[t].Length());
    for (size_t k = 0; k < a.tracks[t].Length(); ++k) {
      EXPECT_EQ(a.tracks[t].observations[k].feature, b.tracks[t].observations[k].feature);
    }
  }
}

TEST(Tracker, MotionPredictionFollowsMotionBeyondTheSearchRadius) {
  // 30 px per frame: beyond r = 20 px around the old position.
  const cv::Point step(30, 4);
  const auto frames = TranslatingFrames(5, step, {300, 200});
  const HarrisDetector harris;
  TrackerOptions options = HarrisOptions();
  int steps_without = 0;
  const double without =
      CorrectStepFraction(TrackFrames(frames, harris, options).tracks, step, &steps_without);
  EXPECT_LT(without * steps_without, 5) << "no prediction should find almost no correct step";

  // Constant velocity: the first pair needs a wide search, later pairs use r = 20 around the
  // prediction.
  options.prediction = MotionPrediction::kConstantVelocity;
  options.unpredicted_radius = 40;
  int steps_velocity = 0;
  const TrackingResult velocity = TrackFrames(frames, harris, options);
  EXPECT_GT(CorrectStepFraction(velocity.tracks, step, &steps_velocity), 0.9);
  EXPECT_GE(steps_velocity, 100);

  // Coarse to fine: predicted from the downscaled frames, from the first pair on.
  options.prediction = MotionPrediction::kCoarseToFine;
  options.unpredicted_radius = 0;
  options.coarse_factor = 2;
  options.coarse_radius = 50;
  int steps_coarse = 0;
  const TrackingResult coarse = TrackFrames(frames, harris, options);
  EXPECT_GT(CorrectStepFraction(coarse.tracks, step, &steps_coarse), 0.9);
  EXPECT_GE(steps_coarse, 100);
  EXPECT_GE(coarse.accepted_matches[0].size(), 20u);
}

TEST(Tracker, ConsecutiveMatchesChainIntoTracks) {
  std::vector<FeatureSet> features(3, FeatureSet(3));
  // 0:0 -> 1:2 -> 2:1; 0:1 -> 1:0 (ends); 1:1 -> 2:2.
  const std::vector<FramePairMatches> pairs = {{0, 1, {{0, 2, 1.f}, {1, 0, 1.f}}},
                                               {1, 2, {{2, 1, 1.f}, {1, 2, 1.f}}}};
  const std::vector<Track> tracks = BuildTracks(features, pairs, TrackConflictRule::kGreedy);
  ASSERT_EQ(tracks.size(), 3u);
  EXPECT_EQ(tracks[0].Length(), 3u);
  EXPECT_EQ(tracks[0].observations[2].feature, 1);
  EXPECT_EQ(tracks[1].Length(), 2u);
  EXPECT_EQ(tracks[2].FirstFrame(), 1);
  EXPECT_THROW(
      BuildTracks(features, {{0, 1, {{0, 2, 1.f}, {1, 2, 1.f}}}}, TrackConflictRule::kGreedy),
      Error);
  EXPECT_THROW(BuildTracks(features, {{0, 1, {{0, 3, 1.f}}}}, TrackConflictRule::kGreedy), Error);
}

TEST(Tracker, RethresholdingMatchesTrackingAtThatThreshold) {
  const auto frames = TranslatingFrames(4, {3, 1});
  cv::Mat noisy;
  std::vector<cv::Mat> noisy_frames;
  cv::RNG rng(5);
  for (const cv::Mat& f : frames) {
    cv::Mat n(f.size(), CV_8UC1);
    rng.fill(n, cv::RNG::UNIFORM, 0, 30);
    noisy_frames.push_back(f + n);
  }
  const HarrisDetector harris;
  TrackerOptions options = HarrisOptions();
  options.matcher.max_cost = std::numeric_limits<double>::infinity();
  const TrackingResult loose = TrackFrames(noisy_frames, harris, options);
  options.matcher.max_cost = 60;
  const TrackingResult strict = TrackFrames(noisy_frames, harris, options);
  const FeatureTracks rethresholded = TracksAtThreshold(loose, 60);
  ASSERT_EQ(rethresholded.tracks.size(), strict.tracks.tracks.size());
  for (size_t t = 0; t < rethresholded.tracks.size(); ++t) {
    EXPECT_EQ(rethresholded.tracks[t].Length(), strict.tracks.tracks[t].Length());
  }
  EXPECT_LT(strict.tracks.tracks.size() + 0u, loose.tracks.tracks.size() + 1000u);
  size_t loose_steps = 0, strict_steps = 0;
  for (const auto& m : loose.accepted_matches) loose_steps += m.size();
  for (const auto& m : strict.accepted_matches) strict_steps += m.size();
  EXPECT_LT(strict_steps, loose_steps);  // the threshold removed some matches
}

// Translating frames with a flat grey box over the middle of frame `occluded_frame`.
std::vector<cv::Mat> OccludedFrames(int count, cv::Point step, int occluded_frame,
                                    cv::Rect box = {100, 60, 100, 80}) {
  std::vector<cv::Mat> frames = TranslatingFrames(count, step, {300, 200});
  frames[occluded_frame](box).setTo(cv::Scalar(128));
  return frames;
}

// Tracks holding frames `a` and `b` but not the frames between, and how many of those moved by
// (b − a)·step from a to b (within 1 px).
int TracksSkipping(const FeatureTracks& tracks, int a, int b, cv::Point step, int* correct) {
  int skipping = 0;
  *correct = 0;
  for (const Track& track : tracks.tracks) {
    const TrackObservation* in_a = nullptr;
    const TrackObservation* in_b = nullptr;
    bool between = false;
    for (const TrackObservation& obs : track.observations) {
      if (obs.frame == a) in_a = &obs;
      if (obs.frame == b) in_b = &obs;
      between |= obs.frame > a && obs.frame < b;
    }
    if (!in_a || !in_b || between) continue;
    ++skipping;
    const cv::Point2f d = tracks.FeatureOf(*in_b).Position() - tracks.FeatureOf(*in_a).Position();
    *correct += std::hypot(d.x - (b - a) * step.x, d.y - (b - a) * step.y) < 1.0 ? 1 : 0;
  }
  return skipping;
}

TEST(Tracker, MatchWindowLinksFeaturesAcrossAnOccludedFrame) {
  // Frame 2 hides the middle of the scene: features there are seen in frames 1 and 3 only.
  const cv::Point step(3, 2);
  const auto frames = OccludedFrames(5, step, 2);
  const HarrisDetector harris;
  TrackerOptions options = HarrisOptions();
  int correct = 0;
  const TrackingResult consecutive = TrackFrames(frames, harris, options);
  EXPECT_EQ(TracksSkipping(consecutive.tracks, 1, 3, step, &correct), 0);
  EXPECT_TRUE(consecutive.window_mutual_matches.empty());

  options.match_window = 2;
  const TrackingResult window = TrackFrames(frames, harris, options);
  EXPECT_NO_THROW(window.tracks.Check());
  const int skipping = TracksSkipping(window.tracks, 1, 3, step, &correct);
  EXPECT_GE(skipping, 10);
  EXPECT_GT(correct, 0.9 * skipping) << correct << " of " << skipping;
  // The occluded features' tracks run on across the gap: frames 0 to 4 without frame 2.
  int across = 0;
  for (const Track& t : window.tracks.tracks) {
    across += t.FirstFrame() == 0 && t.LastFrame() == 4 && t.Length() == 4 ? 1 : 0;
  }
  EXPECT_GE(across, 5);
  // Pairs (0, 2), (1, 3), (2, 4) besides the consecutive ones, which are unchanged: the window
  // only adds matches.
  ASSERT_EQ(window.window_accepted_matches.size(), 3u);
  EXPECT_EQ(window.window_accepted_matches[1].frame1, 1);
  EXPECT_EQ(window.window_accepted_matches[1].frame2, 3);
  ASSERT_EQ(window.accepted_matches.size(), consecutive.accepted_matches.size());
  for (size_t p = 0; p < window.accepted_matches.size(); ++p) {
    ASSERT_EQ(window.accepted_matches[p].size(), consecutive.accepted_matches[p].size());
    for (size_t m = 0; m < window.accepted_matches[p].size(); ++m) {
      EXPECT_EQ(window.accepted_matches[p][m].index2, consecutive.accepted_matches[p][m].index2);
    }
  }
}

TEST(Tracker, MatchWindowPredictsFartherFramesFromTwoHops) {
  // 12 px per frame: 25 px over two frames, beyond the 20 px search radius, so the occluded
  // features of frame 1 are found in frame 3 only by a prediction — the displacement of their
  // neighbours' two-hop links 1 -> 2 -> 3, or the coarse pass between frames 1 and 3.
  const cv::Point step(12, 3);
  const auto frames = OccludedFrames(5, step, 2);
  const HarrisDetector harris;
  TrackerOptions options = HarrisOptions();
  options.match_window = 2;
  int correct = 0;
  EXPECT_LT(TracksSkipping(TrackFrames(frames, harris, options).tracks, 1, 3, step, &correct), 3)
      << "without prediction the gap is too wide";

  options.prediction = MotionPrediction::kConstantVelocity;
  options.unpredicted_radius = 40;
  const TrackingResult velocity = TrackFrames(frames, harris, options);
  int skipping = TracksSkipping(velocity.tracks, 1, 3, step, &correct);
  EXPECT_GE(skipping, 10);
  EXPECT_GT(correct, 0.9 * skipping) << correct << " of " << skipping;

  options.prediction = MotionPrediction::kCoarseToFine;
  options.unpredicted_radius = 0;
  options.coarse_factor = 2;
  options.coarse_radius = 50;
  const TrackingResult coarse = TrackFrames(frames, harris, options);
  skipping = TracksSkipping(coarse.tracks, 1, 3, step, &correct);
  EXPECT_GE(skipping, 10);
  EXPECT_GT(correct, 0.9 * skipping) << correct << " of " << skipping;
}

// Noisy translating frames: tracks break now and then.
std::vector<cv::Mat> NoisyFrames(int count, cv::Point step, uint64_t seed) {
  std::vector<cv::Mat> noisy;
  cv::RNG rng(seed);
  for (const cv::Mat& f : TranslatingFrames(count, step)) {
    cv::Mat n(f.size(), CV_8UC1);
    rng.fill(n, cv::RNG::UNIFORM, 0, 40);
    noisy.push_back(f + n);
  }
  return noisy;
}

TEST(Tracker, DefaultWindowGivesTheChainsOfConsecutiveMatches) {
  const auto frames = NoisyFrames(6, {3, 1}, 3);
  const HarrisDetector harris;
  TrackerOptions options = HarrisOptions();
  options.prediction = MotionPrediction::kConstantVelocity;
  options.matcher.max_cost = 300;
  const TrackingResult result = TrackFrames(frames, harris, options);
  EXPECT_EQ(options.match_window, 1);
  EXPECT_TRUE(result.window_accepted_matches.empty());
  std::vector<int> num_features;
  for (const FeatureSet& f : result.tracks.features) num_features.push_back(f.size());
  const std::vector<std::string> chains =
      Describe(ChainConsecutiveMatches(num_features, result.accepted_matches));
  EXPECT_EQ(Describe(result.tracks.tracks), chains);
  int broken = 0;  // the noise ends some tracks early: the test covers more than full chains
  for (const Track& t : result.tracks.tracks) broken += t.Length() < 6 ? 1 : 0;
  EXPECT_GE(broken, 10) << result.tracks.tracks.size() << " tracks";
  EXPECT_GE(result.tracks.tracks.size() - broken, 10u) << "and some full ones";
  options.conflict_rule = TrackConflictRule::kDrop;  // no conflict without a window
  EXPECT_EQ(Describe(TrackFrames(frames, harris, options).tracks.tracks), chains);
}

TEST(Tracker, MatchWindowIsDeterministicAndRethresholds) {
  const auto frames = NoisyFrames(6, {3, 1}, 5);
  const HarrisDetector harris;
  TrackerOptions options = HarrisOptions();
  options.match_window = 3;
  options.matcher.max_cost = std::numeric_limits<double>::infinity();
  const TrackingResult loose = TrackFrames(frames, harris, options);
  EXPECT_EQ(Describe(TrackFrames(frames, harris, options).tracks.tracks),
            Describe(loose.tracks.tracks));
  EXPECT_EQ(loose.window_mutual_matches.size(), 4u + 3u);  // gaps 2 and 3
  EXPECT_GT(loose.track_building.num_refused_matches, 0) << "loose matches should conflict";
  // Without prediction the mutual matches do not depend on the threshold: re-thresholding gives
  // exactly the tracks of tracking at that threshold.
  options.matcher.max_cost = 150;
  const TrackingResult strict = TrackFrames(frames, harris, options);
  EXPECT_EQ(Describe(TracksAtThreshold(loose, 150).tracks), Describe(strict.tracks.tracks));
  EXPECT_LT(strict.tracks.tracks.size(), loose.tracks.tracks.size());
  options.match_window = 0;
  EXPECT_THROW(options.Check(), Error);
}

// A bright square's corner at (50, 50) whose background (everything but the square) has grey
// `background` in each frame.
std::vector<cv::Mat> CornerOverBackgrounds(const std::vector<int>& backgrounds) {
  std::vector<cv::Mat> frames;
  for (int background : backgrounds) {
    cv::Mat gray(100, 100, CV_8UC1, cv::Scalar(background));
    gray(cv::Rect(50, 50, 40, 40)).setTo(200);
    frames.push_back(gray);
  }
  return frames;
}

// The accepted matches of every consecutive pair when tracking the corner with `cost`.
std::vector<size_t> CornerMatches(const std::vector<cv::Mat>& frames, MatchCost cost,
                                  TrackingResult* result = nullptr) {
  TrackerOptions options;
  options.matcher.cost = cost;
  Tracker tracker(options, "corner");
  Feature corner;
  corner.x = 50;
  corner.y = 50;
  for (const cv::Mat& frame : frames) tracker.AddFrame(frame, {corner});
  TrackingResult tracked = tracker.Result();
  std::vector<size_t> accepted;
  for (const auto& pair : tracked.accepted_matches) accepted.push_back(pair.size());
  if (result) *result = std::move(tracked);
  return accepted;
}

TEST(Tracker, TrackSidesComparesByTheFullPatchAFeatureWhoseLastMatchWasWonByItsFullPatch) {
  // Frames 0 and 1 identical: the match costs its full patch (0), so in the pair (1, 2), where
  // the background changes, the corner is compared by its full patch and lost; the calibrated
  // cost, without memory, matches it on its object side.
  const std::vector<cv::Mat> still_then_changed = CornerOverBackgrounds({40, 40, 120});
  EXPECT_EQ(CornerMatches(still_then_changed, MatchCost::kCalibratedSides),
            (std::vector<size_t>{1, 1}));
  EXPECT_EQ(CornerMatches(still_then_changed, MatchCost::kTrackSides), (std::vector<size_t>{1, 0}));
  EXPECT_EQ(CornerMatches(still_then_changed, MatchCost::kFullPatch), (std::vector<size_t>{1, 0}));
  // A background that keeps changing: the side won the first match, so it is kept.
  const std::vector<cv::Mat> changing = CornerOverBackgrounds({40, 120, 80});
  TrackingResult calibrated, track_sides;
  EXPECT_EQ(CornerMatches(changing, MatchCost::kCalibratedSides, &calibrated),
            (std::vector<size_t>{1, 1}));
  EXPECT_EQ(CornerMatches(changing, MatchCost::kTrackSides, &track_sides),
            (std::vector<size_t>{1, 1}));
  EXPECT_EQ(CornerMatches(changing, MatchCost::kFullPatch), (std::vector<size_t>{0, 0}));
  // The first pair has no memory yet: the calibrated cost bit for bit.
  ASSERT_EQ(track_sides.mutual_matches[0].size(), 1u);
  EXPECT_EQ(track_sides.mutual_matches[0][0].cost, calibrated.mutual_matches[0][0].cost);
  EXPECT_EQ(track_sides.mutual_matches[1][0].cost, calibrated.mutual_matches[1][0].cost);
}

TEST(Tracker, SelectsTrackableFeatures) {
  FeatureSet detected(4);
  detected[0].x = 50, detected[0].y = 50, detected[0].response = 1;
  detected[1].x = 5, detected[1].y = 50, detected[1].response = 9;  // patch does not fit
  detected[2].x = 60, detected[2].y = 50, detected[2].response = 3;
  detected[3].x = 70, detected[3].y = 50, detected[3].response = 2;
  TrackerOptions options;
  options.min_response = 1.5f;
  FeatureSet kept = SelectTrackableFeatures(detected, {100, 100}, options);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].x, 60);
  options.max_features = 1;
  kept = SelectTrackableFeatures(detected, {100, 100}, options);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].response, 3);
}

TrackerOptions AlignedOptions(int max_continued_frames) {
  TrackerOptions options = HarrisOptions();
  options.align_patches = true;
  options.continuation.max_continued_frames = max_continued_frames;
  return options;
}

TEST(Tracker, AlignedPatchesFollowAMotionBeyondTheSearchRadius) {
  const int kStep = 16;
  const auto frames = TranslatingFrames(4, {kStep, 0}, {260, 160});
  const HarrisDetector harris;
  TrackerOptions plain_options = HarrisOptions();
  plain_options.matcher.radius = 10;
  const FeatureTracks plain = TrackFrames(frames, harris, plain_options).tracks;
  EXPECT_LT(CorrectStepFraction(plain, {kStep, 0}), 0.2);
  TrackerOptions aligned_options = AlignedOptions(0);
  aligned_options.matcher.radius = 10;
  const TrackingResult aligned = TrackFrames(frames, harris, aligned_options);
  int steps = 0;
  EXPECT_GT(CorrectStepFraction(aligned.tracks, {kStep, 0}, &steps), 0.95);
  EXPECT_GE(steps, 600);
  ASSERT_EQ(aligned.alignments.size(), 3u);
  ASSERT_EQ(aligned.search_regions.size(), 3u);
  // No continuation asked: every feature is a detection.
  for (const std::vector<uint8_t>& flags : aligned.continued) {
    for (uint8_t f : flags) EXPECT_EQ(f, 0);
  }
}

// Tracks frames with the detector's features, except in frame `missed`, which gets none (the
// detector missed them all: a blurred frame).
TrackingResult TrackMissingAFrame(const std::vector<cv::Mat>& frames, int missed,
                                  const TrackerOptions& options) {
  const HarrisDetector harris;
  Tracker tracker(options, harris.Name(), &harris);
  for (int i = 0; i < static_cast<int>(frames.size()); ++i) {
    FeatureSet features;
    if (i != missed)
      features = SelectTrackableFeatures(harris.Detect(frames[i]), frames[i], options);
    tracker.AddFrame(frames[i], features);
  }
  return tracker.Result();
}

TEST(Tracker, ContinuationCarriesTracksThroughAFrameWithoutDetections) {
  const auto frames = TranslatingFrames(5, {3, 2});
  const auto full_tracks = [](const FeatureTracks& tracks) {
    int n = 0;
    for (const Track& t : tracks.tracks) n += t.Length() == 5 ? 1 : 0;
    return n;
  };
  const TrackingResult plain = TrackMissingAFrame(frames, 2, AlignedOptions(0));
  const TrackingResult continued = TrackMissingAFrame(frames, 2, AlignedOptions(2));
  EXPECT_EQ(full_tracks(plain.tracks), 0);
  EXPECT_GE(full_tracks(continued.tracks), 30);
  // Frame 2 holds continued features only, each where the scene moved it.
  ASSERT_EQ(continued.continued.size(), 5u);
  EXPECT_GE(continued.continued[2].size(), 30u);
  for (uint8_t f : continued.continued[2]) EXPECT_EQ(f, 1);
  for (uint8_t f : continued.continued[3]) EXPECT_EQ(f, 0);
  EXPECT_GT(CorrectStepFraction(continued.tracks, {3, 2}), 0.95);
  // Deterministic.
  const TrackingResult again = TrackMissingAFrame(frames, 2, AlignedOptions(2));
  ASSERT_EQ(again.tracks.tracks.size(), continued.tracks.tracks.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    ASSERT_EQ(again.tracks.features[f].size(), continued.tracks.features[f].size());
    for (size_t k = 0; k < again.tracks.features[f].size(); ++k) {
      EXPECT_EQ(again.tracks.features[f][k].Position(), continued.tracks.features[f][k].Position());
    }
  }
}

TEST(Tracker, BridgesRelinkTracksAcrossAFrameWithoutDetections) {
  // No continuation: with bridge_frames = 2 the tracks lost at frame 2 are found again in frame 3.
  const auto frames = TranslatingFrames(5, {3, 2});
  TrackerOptions options = AlignedOptions(0);
  options.continuation.bridge_frames = 2;
  const TrackingResult bridged = TrackMissingAFrame(frames, 2, options);
  int skipping = 0, correct = 0;
  for (const Track& t : bridged.tracks.tracks) {
    for (size_t k = 1; k < t.observations.size(); ++k) {
      if (t.observations[k - 1].frame != 1 || t.observations[k].frame != 3) continue;
      ++skipping;
      const cv::Point2f d = bridged.tracks.FeatureOf(t.observations[k]).Position() -
                            bridged.tracks.FeatureOf(t.observations[k - 1]).Position();
      correct += std::hypot(d.x - 6, d.y - 4) < 1.0 ? 1 : 0;
    }
  }
  EXPECT_GE(skipping, 30);
  EXPECT_GE(correct, 0.95 * skipping);
}

TEST(Tracker, WindowEigenvalueDropsFeaturesOnStraightEdges) {
  cv::Mat gray(100, 100, CV_8UC1, cv::Scalar(30));
  gray(cv::Rect(50, 0, 50, 100)).setTo(200);  // a vertical edge at x = 50
  gray(cv::Rect(70, 60, 30, 40)).setTo(90);   // a corner at (70, 60)
  FeatureSet detected(2);
  detected[0].x = 50, detected[0].y = 30, detected[0].response = 5;  // on the straight edge
  detected[1].x = 70, detected[1].y = 60, detected[1].response = 1;  // on the corner
  TrackerOptions options;
  options.min_window_eigenvalue = 1.0;
  const FeatureSet kept = SelectTrackableFeatures(detected, gray, options);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].x, 70);
  EXPECT_THROW(SelectTrackableFeatures(detected, gray.size(), options), Error);
}

TEST(Tracker, BadOptionsAndFrames) {
  TrackerOptions options;
  options.matcher.gate = CandidateGate::kRectifiedStereo;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.prediction = MotionPrediction::kCoarseToFine;
  EXPECT_THROW(Tracker(options, "x"), Error);  // needs a detector
  EXPECT_THROW(ParseMotionPrediction("kalman"), Error);
  options = {};
  options.continuation.max_continued_frames = 3;  // needs align_patches
  EXPECT_THROW(options.Check(), Error);
  options.align_patches = true;
  EXPECT_NO_THROW(options.Check());
  options.min_window_eigenvalue = -1;
  EXPECT_THROW(options.Check(), Error);
  EXPECT_EQ(ParseMotionPrediction("coarse-to-fine"), MotionPrediction::kCoarseToFine);
  Tracker tracker(TrackerOptions{}, "x");
  tracker.AddFrame(cv::Mat(50, 50, CV_8UC1, cv::Scalar(0)), {});
  EXPECT_THROW(tracker.AddFrame(cv::Mat(50, 60, CV_8UC1, cv::Scalar(0)), {}), Error);
  EXPECT_THROW(tracker.AddFrame(cv::Mat(50, 50, CV_8UC3), {}), Error);
}

TEST(Tracker, TracksTheBundledKittiClip) {
  io::ImageSequenceOptions sequence_options;
  sequence_options.last_frame = 3;
  const auto sequence = io::ImageSequence::Open(test::ExampleDir() + "/image_l", sequence_options);
  const HarrisDetector harris;
  TrackerOptions options;
  options.max_features = 800;
  options.prediction = MotionPrediction::kCoarseToFine;
  size_t calls = 0;
  const TrackingResult result =
      TrackSequence(sequence, harris, options, [&](size_t done, size_t total) {
        ++calls;
        EXPECT_EQ(done, calls);
        EXPECT_EQ(total, 4u);
      });
  EXPECT_EQ(calls, 4u);
  EXPECT_NO_THROW(result.tracks.Check());
  EXPECT_EQ(result.tracks.frame_names[0], "000000.png");
  EXPECT_EQ(result.tracks.features[0].size(), 800u);
  int long_tracks = 0;
  for (const Track& t : result.tracks.tracks) long_tracks += t.Length() == 4 ? 1 : 0;
  EXPECT_GE(long_tracks, 50);
  // Almost no accepted match is grossly wrong: within 3 px of the ground-truth epipolar line
  // (detector-to-detector matches are off by a pixel or two from localisation alone).
  const auto poses = io::ReadKittiPoses(test::ExampleDir() + "/poses.txt");
  const cv::Matx33d K = io::ReadKittiIntrinsics(test::ExampleDir() + "/calib.txt");
  int accepted = 0, consistent = 0;
  for (size_t p = 0; p < 3; ++p) {
    const auto ok = EpipolarConsistency(FundamentalFromPoses(K, poses[p], poses[p + 1]),
                                        result.tracks.features[p], result.tracks.features[p + 1],
                                        result.accepted_matches[p], 3.0);
    accepted += static_cast<int>(ok.size());
    for (bool b : ok) consistent += b ? 1 : 0;
  }
  EXPECT_GE(accepted, 3 * 150);
  EXPECT_GT(consistent, 0.97 * accepted) << consistent << " of " << accepted;
}

}  // namespace
}  // namespace comic::frontend
