#include "frontend/evaluation/stereo_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/imgcodecs.hpp>

#include "io/core/error.h"
#include "tests/frontend/synthetic_stereo_scene.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

using comic::test::SyntheticStereoScene;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kB = 0, kNB = 1, kO = 2;

Feature At(float x, float y) {
  Feature f;
  f.x = x;
  f.y = y;
  f.response = 1.0f;
  return f;
}

// Side labels of a patch split at column offset 0: ic+ for u >= 0 (the foreground of a feature
// on the rectangle's left edge), ic− for u < 0.
Feature WithVerticalSplit(Feature f) {
  f.side_mask.resize(kPatchSize * kPatchSize);
  for (int v = 0; v < kPatchSize; ++v) {
    for (int u = 0; u < kPatchSize; ++u) {
      f.side_mask[v * kPatchSize + u] = u >= kPatchRadius ? PatchSide::kPlus : PatchSide::kMinus;
    }
  }
  return f;
}

// Hand-placed features, one per row so that each left feature has exactly one gated candidate.
// Index: what it is -> expected verdict.
struct PlacedFeatures {
  FeatureSet left, right;
};
PlacedFeatures Place() {
  PlacedFeatures p;
  auto add = [&](Feature l, Feature r) {
    p.left.push_back(l);
    p.right.push_back(r);
  };
  add(At(110, 40), At(98, 40));   // 0 foreground interior, exact -> NB correct, cost 0
  add(At(120, 46), At(109, 46));  // 1 foreground interior, 1 px off -> NB correct
  add(At(100, 52), At(90, 52));   // 2 foreground interior, 2 px off -> NB wrong
  add(WithVerticalSplit(At(80, 58)), WithVerticalSplit(At(68, 58)));  // 3 fg left edge -> B
  add(At(141, 64), At(137, 64));  // 4 background beside the right edge, exact -> B correct
  add(At(75, 70), At(70, 70));    // 5 occluded background -> excluded
  add(At(185, 76), At(181, 76));  // 6 unknown disparity -> excluded
  add(At(30, 82), At(26, 82));    // 7 background interior, exact -> NB correct, cost 0
  add(At(82, 88), At(73, 88));    // 8 near the left edge, 3 px off -> B wrong
  p.left.push_back(At(40, 100));  // 9 background interior, no partner -> NB unmatched
  return p;
}

TEST(StereoEvaluation, GroundTruthClassesAreAsConstructed) {
  const io::MiddleburyPair pair = SyntheticStereoScene::Make();
  const StereoGroundTruth truth(pair);
  EXPECT_EQ(truth.Classify(110, 40), StereoPixelClass::kNonBoundary);
  EXPECT_EQ(truth.Classify(80, 58), StereoPixelClass::kBoundary);
  EXPECT_EQ(truth.Classify(77, 58), StereoPixelClass::kOccluded);     // x in [72, 80)
  EXPECT_EQ(truth.Classify(82, 58), StereoPixelClass::kBoundary);     // 2 px inside the edge
  EXPECT_EQ(truth.Classify(84, 58), StereoPixelClass::kNonBoundary);  // 4 px inside
  EXPECT_EQ(truth.Classify(2, 58), StereoPixelClass::kOccluded);      // right position x < 0
  EXPECT_EQ(truth.Classify(180, 58), StereoPixelClass::kUnknownDisparity);
  EXPECT_EQ(truth.Classify(-1, 58), StereoPixelClass::kUnknownDisparity);
  EXPECT_EQ(truth.Classify(79.6f, 58.2f), StereoPixelClass::kBoundary);  // rounds to (80, 58)
  EXPECT_EQ(truth.TrueRightPosition(110.25f, 40), cv::Point2f(98.25f, 40));
  EXPECT_EQ(truth.TrueRightPosition(30, 82), cv::Point2f(26, 82));
  EXPECT_DOUBLE_EQ(truth.MaxDisparity(), 12.0);
  // The right image really is the left shifted by the GT disparity on every valid pixel.
  for (int y = 0; y < pair.left_gray.rows; ++y) {
    for (int x = 0; x < pair.left_gray.cols; ++x) {
      if (truth.ValidMask().at<uint8_t>(y, x) == 0) continue;
      const cv::Point2f r = truth.TrueRightPosition(x, y);
      ASSERT_EQ(pair.left_gray.at<uint8_t>(y, x),
                pair.right_gray.at<uint8_t>(y, static_cast<int>(r.x)))
          << x << "," << y;
    }
  }
}

TEST(StereoEvaluation, CorrectnessAndBoundarySplitOnPlacedFeatures) {
  const io::MiddleburyPair pair = SyntheticStereoScene::Make();
  const StereoGroundTruth truth(pair);
  const PlacedFeatures placed = Place();
  const StereoDetection d =
      MakeStereoDetection(truth, "placed", placed.left, placed.right, {1.0, 1.5, 2.5});
  ASSERT_EQ(d.left.size(), 10u);
  EXPECT_EQ(d.detected[kB], 3);
  EXPECT_EQ(d.detected[kNB], 5);
  EXPECT_EQ(d.detected[kO], 8);
  EXPECT_EQ(d.occluded, 1);
  EXPECT_EQ(d.unknown_disparity, 1);
  // Repeatability: within 1 and 1.5 px: B {3, 4}, NB {0, 1, 7}; within 2.5 px NB adds 2.
  EXPECT_EQ(d.repeatable[0][kB], 2);
  EXPECT_EQ(d.repeatable[0][kNB], 3);
  EXPECT_EQ(d.repeatable[1][kNB], 3);
  EXPECT_EQ(d.repeatable[2][kB], 2);
  EXPECT_EQ(d.repeatable[2][kNB], 4);
  EXPECT_EQ(d.repeatable[2][kO], 6);

  StereoEvaluationOptions options;
  options.working_height = 0;
  const StereoMatching full =
      MatchStereoDetection(pair, truth, d, MatchCost::kFullPatch, options, 13.5);
  ASSERT_EQ(full.mutual.size(), 9u);  // every left feature but #9 has its one candidate
  const std::vector<int8_t> expected_verdicts = {1, 1, 0, 1, 1, -1, -1, 1, 0};
  EXPECT_EQ(full.verdict, expected_verdicts);

  const RegionScores all = ScoreAt(d, full, kInf);
  EXPECT_EQ(all[kB].accepted, 3);
  EXPECT_EQ(all[kB].correct, 2);
  EXPECT_EQ(all[kNB].accepted, 4);
  EXPECT_EQ(all[kNB].correct, 3);
  EXPECT_EQ(all[kO].accepted, 7);
  EXPECT_EQ(all[kO].correct, 5);
  EXPECT_DOUBLE_EQ(*all[kB].MScore(), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(*all[kNB].MScore(), 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(*all[kO].MScore(), 5.0 / 8.0);
  EXPECT_DOUBLE_EQ(*all[kNB].Precision(), 3.0 / 4.0);

  // Exact shifts cost 0; the edge feature's full patch mixes foreground and a background shifted
  // by 8 px, so the full cost rejects it at T = 400 while the like-sides split cost (foreground
  // side against foreground side) is 0 and accepts it.
  EXPECT_EQ(full.mutual[0].cost, 0.0f);
  EXPECT_EQ(full.mutual[7].cost, 0.0f);
  EXPECT_GT(full.mutual[3].cost, 400.0f);
  const RegionScores full_at_0 = ScoreAt(d, full, 0.0);
  EXPECT_EQ(full_at_0[kB].accepted, 0);
  EXPECT_EQ(full_at_0[kNB].accepted, 2);
  EXPECT_EQ(full_at_0[kNB].correct, 2);
  const StereoMatching split =
      MatchStereoDetection(pair, truth, d, MatchCost::kSplitLikeSides, options, 13.5);
  ASSERT_EQ(split.mutual.size(), 9u);
  EXPECT_EQ(split.mutual[3].cost, 0.0f);
  const RegionScores split_at_400 = ScoreAt(d, split, 400.0);
  EXPECT_EQ(ScoreAt(d, full, 400.0)[kB].correct + 1, split_at_400[kB].correct);
}

TEST(StereoEvaluation, GateExcludesDisparitiesOutsideTheRange) {
  const io::MiddleburyPair pair = SyntheticStereoScene::Make();
  const StereoGroundTruth truth(pair);
  const PlacedFeatures placed = Place();
  const StereoDetection d = MakeStereoDetection(truth, "placed", placed.left, placed.right, {1.0});
  StereoEvaluationOptions options;
  // Up to 11 px: the foreground partners at disparity 12 (#0, #3) drop out; #1 (11) stays.
  const StereoMatching m = MatchStereoDetection(pair, truth, d, MatchCost::kFullPatch, options, 11);
  std::vector<int> left;
  for (const PatchMatch& match : m.mutual) left.push_back(match.index1);
  EXPECT_EQ(left, (std::vector<int>{1, 2, 4, 5, 6, 7, 8}));
}

TEST(StereoEvaluation, MatchedPrecisionThresholdReachesTheTargetExactly) {
  // Hand-built: left features B, B, NB, NB, NB, occluded; one match each with these costs.
  StereoDetection d;
  d.left_class = {StereoPixelClass::kBoundary,    StereoPixelClass::kBoundary,
                  StereoPixelClass::kNonBoundary, StereoPixelClass::kNonBoundary,
                  StereoPixelClass::kNonBoundary, StereoPixelClass::kOccluded};
  d.detected = {2, 3, 5};
  StereoMatching m;
  m.mutual = {{0, 0, 10.f}, {1, 1, 20.f}, {2, 2, 30.f}, {3, 3, 40.f}, {4, 4, 50.f}, {5, 5, 5.f}};
  m.verdict = {1, 1, 0, 1, 0, -1};
  // Precision by T over judged matches: 10: 1, 20: 1, 30: 2/3, 40: 3/4, 50: 3/5 (the excluded
  // match at cost 5 never counts).
  MatchedPrecision mp = ScoreAtPrecision(d, m, 0.75);
  ASSERT_TRUE(mp.point.has_value());
  EXPECT_EQ(mp.point->max_cost, 40.0);
  EXPECT_DOUBLE_EQ(mp.point->precision, 0.75);
  EXPECT_EQ(mp.point->accepted, 4);
  EXPECT_EQ(mp.scores[kB].correct, 2);
  EXPECT_DOUBLE_EQ(*mp.scores[kB].MScore(), 1.0);
  EXPECT_DOUBLE_EQ(*mp.scores[kNB].MScore(), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(*mp.scores[kNB].Precision(), 0.5);
  EXPECT_DOUBLE_EQ(*mp.scores[kO].MScore(), 3.0 / 5.0);
  mp = ScoreAtPrecision(d, m, 1.0);
  ASSERT_TRUE(mp.point.has_value());
  EXPECT_EQ(mp.point->max_cost, 20.0);
  EXPECT_EQ(mp.point->accepted, 2);  // not 3: the excluded match is not judged
  mp = ScoreAtPrecision(d, m, 0.6);
  ASSERT_TRUE(mp.point.has_value());
  EXPECT_EQ(mp.point->max_cost, 50.0);
  m.verdict = {0, 0, 0, 0, 0, -1};
  mp = ScoreAtPrecision(d, m, 0.1);
  EXPECT_FALSE(mp.point.has_value());
  EXPECT_EQ(mp.scores[kNB].detected, 3);
  EXPECT_EQ(mp.scores[kNB].accepted, 0);
}

TEST(StereoEvaluation, EmptyRegionsGiveUndefinedScoresNotDivisionByZero) {
  const RegionCounts none;
  EXPECT_FALSE(none.MScore().has_value());
  EXPECT_FALSE(none.Precision().has_value());
  const RegionCounts detected_only{4, 0, 0};
  EXPECT_DOUBLE_EQ(*detected_only.MScore(), 0.0);
  EXPECT_FALSE(detected_only.Precision().has_value());
}

TEST(StereoEvaluation, DetectorsOnTheSyntheticPairMatchAsConstructed) {
  const io::MiddleburyPair pair = SyntheticStereoScene::Make();
  StereoEvaluationOptions options;
  options.working_height = 0;
  options.methods = {{"harris", MatchCost::kFullPatch}};
  options.target_counts = {60};
  const StereoPairEvaluation result = EvaluateStereoPair(pair, options);
  EXPECT_DOUBLE_EQ(result.max_gt_disparity, 12.0);
  EXPECT_DOUBLE_EQ(result.gate_max_disparity, 13.5);
  ASSERT_EQ(result.runs.size(), 1u);
  const StereoRun& run = result.runs[0];
  const StereoDetection& d = run.DetectionFor("harris");
  EXPECT_EQ(d.detected[kO], 60);  // Harris responses are real numbers: no tie at the cut
  EXPECT_EQ(d.detected[kB] + d.detected[kNB], 60);
  EXPECT_GT(d.detected[kB], 0);
  // An exact shift: interior corners reappear exactly where the disparity sends them.
  EXPECT_GE(d.repeatable[0][kNB], 0.8 * d.detected[kNB]);
  const RegionScores all = ScoreAt(d, run.matchings[0], kInf);
  EXPECT_GE(*all[kNB].MScore(), 0.8);
  EXPECT_GE(*all[kNB].Precision(), 0.9);
  // Precision target: harris/full at T = 400.
  ASSERT_TRUE(run.target_precision.has_value());
  EXPECT_DOUBLE_EQ(*run.target_precision,
                   *ScoreAt(d, run.matchings[0], options.max_cost)[kO].Precision());
  EXPECT_THROW(run.DetectionFor("fast"), Error);
}

TEST(StereoEvaluation, UniformPairGivesZeroFeaturesAndNoCrash) {
  io::MiddleburyPair pair = SyntheticStereoScene::Make();
  pair.left_gray.setTo(128);
  pair.right_gray.setTo(128);
  StereoEvaluationOptions options;
  options.working_height = 0;
  options.target_counts = {0, 50};  // 0: CoMIC's own count, which is 0 here
  const StereoPairEvaluation result = EvaluateStereoPair(pair, options);
  EXPECT_EQ(result.reference_count, 0);
  ASSERT_EQ(result.runs.size(), 2u);
  EXPECT_EQ(result.runs[0].target_count, 0);
  for (const StereoRun& run : result.runs) {
    ASSERT_EQ(run.matchings.size(), options.methods.size());
    for (const StereoMatching& m : run.matchings) {
      EXPECT_TRUE(m.mutual.empty()) << m.method.Label();
      const RegionScores s = ScoreAt(run.DetectionFor(m.method.detector), m, kInf);
      EXPECT_FALSE(s[kO].MScore().has_value());
    }
    EXPECT_FALSE(run.target_precision.has_value());  // harris accepted nothing
  }
}

TEST(StereoEvaluation, DisparityScaleAndWorkingSizeAreHonoured) {
  // The pair written as files with the disparity stored x4, then loaded like a Middlebury pair.
  comic::test::ScopedTempDir dir;
  const io::MiddleburyPair scene = SyntheticStereoScene::Make();
  cv::Mat stored;
  scene.disparity.convertTo(stored, CV_8U, 4.0);
  cv::imwrite(dir.File("left.png"), scene.left_gray);
  cv::imwrite(dir.File("right.png"), scene.right_gray);
  cv::imwrite(dir.File("disp.png"), stored);
  cv::imwrite(dir.File("nonocc.png"), scene.nonocc);
  cv::imwrite(dir.File("disc.png"), scene.disc);
  io::MiddleburyPairPaths paths;
  paths.left = dir.File("left.png");
  paths.right = dir.File("right.png");
  paths.disparity = dir.File("disp.png");
  paths.nonocc = dir.File("nonocc.png");
  paths.disc = dir.File("disc.png");
  StereoEvaluationOptions options;
  options.methods = {{"harris", MatchCost::kFullPatch}};
  options.target_counts = {60};

  auto overall_at_inf = [&](double scale, int height) {
    paths.disparity_scale = scale;
    options.working_height = height;
    const StereoPairEvaluation r =
        EvaluateStereoPair(io::LoadMiddleburyPair(paths, height), options);
    const StereoRun& run = r.runs[0];
    return std::pair{r.max_gt_disparity,
                     ScoreAt(run.DetectionFor("harris"), run.matchings[0], kInf)[kO]};
  };
  const auto [max_right, right] = overall_at_inf(4.0, 0);
  EXPECT_DOUBLE_EQ(max_right, 12.0);
  EXPECT_GE(*right.MScore(), 0.7);
  // Doubling the size doubles the disparities: matches stay correct.
  const auto [max_double, doubled] = overall_at_inf(4.0, 2 * SyntheticStereoScene::kHeight);
  EXPECT_DOUBLE_EQ(max_double, 24.0);
  EXPECT_GE(*doubled.MScore(), 0.5);
  // A wrong scale (x8 read as x4 halves every disparity): almost nothing is correct.
  const auto [max_wrong, wrong] = overall_at_inf(8.0, 0);
  EXPECT_DOUBLE_EQ(max_wrong, 6.0);
  EXPECT_LE(*wrong.MScore(), 0.1);
  // The working height is part of the protocol: a pair of another height is refused.
  options.working_height = 700;
  EXPECT_THROW(EvaluateStereoPair(scene, options), Error);
}

TEST(StereoEvaluation, BadOptionsAndPairsAreRefused) {
  StereoEvaluationOptions options;
  EXPECT_NO_THROW(options.Check());
  auto refused = [](StereoEvaluationOptions o) { EXPECT_THROW(o.Check(), Error); };
  StereoEvaluationOptions o = options;
  o.max_cost = 0;
  refused(o);
  o = options;
  o.correct_tolerance = 0;
  refused(o);
  o = options;
  o.target_counts = {-1};
  refused(o);
  o = options;
  o.methods = {{"harris", MatchCost::kFullPatch}};  // the precision reference is harris/full: ok
  EXPECT_NO_THROW(o.Check());
  o.methods = {{"fast", MatchCost::kFullPatch}};  // no reference and no fixed target
  refused(o);
  o.target_precision = 0.9;
  EXPECT_NO_THROW(o.Check());
  o.target_precision = 1.5;
  refused(o);
  o = options;
  o.methods.push_back(o.methods.front());
  refused(o);

  EXPECT_EQ(ParseStereoMethods("comic/split,harris").size(), 2u);
  EXPECT_EQ(ParseStereoMethods("harris")[0].cost, MatchCost::kFullPatch);
  EXPECT_EQ(ParseStereoMethods("comic/like-sides")[0].Label(), "comic/like-sides");
  EXPECT_THROW(ParseStereoMethods("sift/full"), Error);
  EXPECT_THROW(ParseStereoMethods("harris/ncc"), Error);
  EXPECT_THROW(ParseStereoMethods("harris,harris/full"), Error);
  EXPECT_THROW(ParseStereoMethods(""), Error);

  io::MiddleburyPair pair = SyntheticStereoScene::Make();
  pair.right_gray = cv::Mat(10, 10, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(StereoGroundTruth{pair}, Error);
  pair = SyntheticStereoScene::Make();
  pair.disparity = cv::Mat(10, 10, CV_32FC1, cv::Scalar(1));
  EXPECT_THROW(StereoGroundTruth{pair}, Error);
  pair = SyntheticStereoScene::Make();
  pair.disc = cv::Mat(10, 10, CV_8UC1, cv::Scalar(255));
  EXPECT_THROW(StereoGroundTruth{pair}, Error);
}

TEST(StereoEvaluation, WithoutMasksNothingIsOccludedOrBoundary) {
  io::MiddleburyPair pair = SyntheticStereoScene::Make();
  pair.disc.release();
  pair.nonocc.release();
  const StereoGroundTruth truth(pair);
  EXPECT_FALSE(truth.has_disc());
  EXPECT_EQ(truth.Classify(80, 58), StereoPixelClass::kNonBoundary);
  EXPECT_EQ(truth.Classify(77, 58), StereoPixelClass::kNonBoundary);
  EXPECT_EQ(truth.Classify(180, 58), StereoPixelClass::kUnknownDisparity);
  const auto counts = truth.PixelCounts();
  EXPECT_EQ(counts[static_cast<int>(StereoPixelClass::kBoundary)], 0);
  EXPECT_EQ(counts[static_cast<int>(StereoPixelClass::kUnknownDisparity)],
            (SyntheticStereoScene::kWidth - SyntheticStereoScene::kUnknownX0) *
                SyntheticStereoScene::kHeight);
}

TEST(StereoEvaluation, RealPairsRunWithTheBaselines) {
  COMIC_REQUIRE_SHARED_DATA();
  StereoEvaluationOptions options;
  options.methods = {{"harris", MatchCost::kFullPatch}};
  options.target_counts = {500};
  const io::MiddleburyPair pair =
      io::LoadMiddleburyFolder(comic::test::SharedDataDir() + "/middlebury2001_tsukuba", 700);
  const StereoPairEvaluation result = EvaluateStereoPair(pair, options);
  // Tsukuba's GT maximum is 14 px at 384 wide, 34 px at 933 wide.
  EXPECT_NEAR(result.max_gt_disparity, 14 * 933.0 / 384.0, 1e-3);
  const StereoRun& run = result.runs[0];
  const StereoDetection& d = run.DetectionFor("harris");
  EXPECT_EQ(d.detected[kO], 500);
  EXPECT_GT(d.detected[kB], 50);      // Tsukuba's disc band is wide
  EXPECT_GT(d.unknown_disparity, 0);  // the 18-pixel unknown border
  const RegionScores s = ScoreAt(d, run.matchings[0], options.max_cost);
  // Harris matches real stereo reasonably; the boundary is harder than the interior.
  EXPECT_GT(*s[kNB].MScore(), 0.4);
  EXPECT_LT(*s[kB].MScore(), *s[kNB].MScore());
}

}  // namespace
}  // namespace comic::frontend
