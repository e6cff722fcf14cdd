// Loop candidates by appearance on a synthetic walk: 30 places seen in order, then places 0-9
// seen again with noisy, partial descriptors. The revisits are found (each within one keyframe of
// the true place), nothing is found before the walk returns, and closing the found loops in the
// pose graph shrinks the end-to-start gap.
#include "sfm/loop_detection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

#include "io/core/error.h"
#include "sfm/pose_graph.h"

namespace comic::sfm {
namespace {

constexpr int kPlaces = 30;
constexpr int kRevisits = 10;

// Descriptors come from visual words, as real ones do: 3000 random prototypes; each place draws
// its 150 descriptors from 40 of them (its own choice, a fixed seed), each value moved by up to
// ±16.
std::vector<cv::Mat> MakePlaces() {
  cv::RNG rng(7);
  cv::Mat prototypes(3000, 128, CV_8U);
  rng.fill(prototypes, cv::RNG::UNIFORM, 0, 256);
  std::vector<cv::Mat> places;
  for (int p = 0; p < kPlaces; ++p) {
    std::vector<int> words;
    for (int w = 0; w < 40; ++w) words.push_back(rng.uniform(0, 3000));
    cv::Mat d;
    for (int r = 0; r < 150; ++r) d.push_back(prototypes.row(words[r % 40]));
    places.push_back(d);
  }
  return places;
}

cv::Mat AddNoise(const cv::Mat& rows, cv::RNG& rng) {
  cv::Mat noise(rows.size(), CV_16S);
  rng.fill(noise, cv::RNG::UNIFORM, -16, 17);
  cv::Mat noisy;
  rows.convertTo(noisy, CV_16S);
  noisy += noise;
  cv::Mat result;
  noisy.convertTo(result, CV_8U);  // saturates at 0 and 255
  return result;
}

// A keyframe at place p: 70 % of its descriptors (a window that moves with `shift`) and 30 rows of
// the next place (neighbouring keyframes overlap), all with fresh noise.
cv::Mat Observe(const std::vector<cv::Mat>& places, int p, int shift, cv::RNG& rng) {
  cv::Mat keyframe;
  for (int r = 0; r < 105; ++r) keyframe.push_back(places[p].row((r + shift) % 150));
  for (int r = 0; r < 30; ++r) keyframe.push_back(places[(p + 1) % kPlaces].row(r));
  return AddNoise(keyframe, rng);
}

struct Walk {
  std::vector<cv::Mat> descriptors;
  std::vector<int> frames;
};

Walk MakeWalk() {
  const std::vector<cv::Mat> places = MakePlaces();
  cv::RNG rng(11);
  Walk walk;
  for (int k = 0; k < kPlaces + kRevisits; ++k) {
    const bool revisit = k >= kPlaces;
    walk.descriptors.push_back(Observe(places, k % kPlaces, revisit ? 40 : 0, rng));
    walk.frames.push_back(10 * k);
  }
  return walk;
}

TEST(LoopDetection, FindsTheRevisitsAndNothingBefore) {
  const Walk walk = MakeWalk();
  LoopDetectionOptions options;
  const std::vector<LoopCandidate> found =
      DetectLoopCandidates(walk.descriptors, walk.frames, options);
  int revisits_found = 0;
  for (const LoopCandidate& c : found) {
    ASSERT_GE(c.query, kPlaces) << "a loop before the walk returns: " << c.query << " -> "
                                << c.match;
    EXPECT_LE(std::abs(c.match - (c.query - kPlaces)), 1) << c.query << " -> " << c.match;
    EXPECT_GE(c.consecutive, options.min_consecutive);
    ++revisits_found;
  }
  EXPECT_GE(revisits_found, 8);  // the first revisit waits for its confirmation
  // The same input gives the same candidates.
  const std::vector<LoopCandidate> again =
      DetectLoopCandidates(walk.descriptors, walk.frames, options);
  ASSERT_EQ(again.size(), found.size());
  for (size_t k = 0; k < found.size(); ++k) {
    EXPECT_EQ(again[k].match, found[k].match);
    EXPECT_EQ(again[k].similarity, found[k].similarity);
  }
}

TEST(LoopDetection, FoundLoopsCloseThePoseGraph) {
  const Walk walk = MakeWalk();
  LoopDetectionOptions options;
  const std::vector<LoopCandidate> found =
      DetectLoopCandidates(walk.descriptors, walk.frames, options);
  ASSERT_FALSE(found.empty());

  // The walk: keyframes on a circle (kPlaces per turn), then the first kRevisits places again.
  const int n = kPlaces + kRevisits;
  std::vector<Sim3d> truth(n);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * (k % kPlaces) / kPlaces;
    truth[k].rotation = Eigen::Quaterniond(Eigen::AngleAxisd(-a, Eigen::Vector3d::UnitY()));
    const Eigen::Vector3d center(10 * std::cos(a), 0, 10 * std::sin(a));
    truth[k].translation = -(truth[k].rotation * center);
  }
  // Odometry with 1 % scale drift per step.
  std::vector<PoseGraphEdge> edges;
  std::vector<Sim3d> poses = {truth[0]};
  Sim3d drift;
  drift.scale = 1.01;
  for (int k = 0; k + 1 < n; ++k) {
    PoseGraphEdge e{k, k + 1, ComposeSim3(drift, ComposeSim3(truth[k + 1], InverseSim3(truth[k])))};
    poses.push_back(ComposeSim3(e.j_from_i, poses.back()));
    edges.push_back(e);
  }
  const auto center = [](const Sim3d& p) {
    return Eigen::Vector3d(-(p.rotation.conjugate() * p.translation) / p.scale);
  };
  const auto revisit_gap = [&](const std::vector<Sim3d>& p) {
    return (center(p[n - 1]) - center(p[kRevisits - 1])).norm();  // the same place, truly
  };
  const double gap_before = revisit_gap(poses);
  // The found loops as edges (their relative motion as a geometric verification would give it).
  for (const LoopCandidate& c : found) {
    edges.push_back({c.match, c.query, ComposeSim3(truth[c.query], InverseSim3(truth[c.match]))});
  }
  OptimizePoseGraph(PoseGraphOptions(), edges, {0}, &poses);
  const double gap_after = revisit_gap(poses);
  EXPECT_GT(gap_before, 2.0);
  EXPECT_LT(gap_after, 0.2 * gap_before);
}

// A route with a look-alike: keyframes 20-22 show places 3-5 again with the same parked cars
// (words only they and the revisit have), so for each revisit (30-32) the look-alike is the most
// similar keyframe and the true place 3-5 the second. Exact prototype rows, no noise: every
// similarity is fixed by construction.
TEST(LoopDetection, ALookAlikeDoesNotHideTheTrueRevisit) {
  cv::RNG rng(5);
  const auto words = [&](int count) {
    cv::Mat rows(count, 128, CV_8U);
    rng.fill(rows, cv::RNG::UNIFORM, 0, 256);
    return rows;
  };
  std::vector<cv::Mat> places, cars;
  for (int p = 0; p < 30; ++p) places.push_back(words(6));
  for (int c = 0; c < 3; ++c) cars.push_back(words(6));
  std::vector<cv::Mat> descriptors;
  std::vector<int> frames;
  for (int k = 0; k < 33; ++k) {
    cv::Mat keyframe;
    if (k >= 20 && k <= 22) {
      cv::vconcat(places[k - 17], cars[k - 20], keyframe);  // the look-alike of place 3-5
    } else if (k >= 30) {
      cv::vconcat(places[k - 27], cars[k - 30], keyframe);  // the revisit of place 3-5
    } else {
      keyframe = places[k].clone();
    }
    descriptors.push_back(keyframe);
    frames.push_back(10 * k);
  }
  LoopDetectionOptions options;
  options.vocabulary_size = 1000;  // more than the rows: every prototype is its own word
  const auto matches_of_revisits = [&](const std::vector<LoopCandidate>& found) {
    std::set<std::pair<int, int>> pairs;
    for (const LoopCandidate& c : found) {
      if (c.query >= 30) pairs.insert({c.query, c.match});
    }
    return pairs;
  };
  // The best only: the revisit is confirmed by the look-alike alone.
  options.candidates_per_keyframe = 1;
  EXPECT_EQ(matches_of_revisits(DetectLoopCandidates(descriptors, frames, options)),
            (std::set<std::pair<int, int>>{{31, 21}, {32, 22}}));
  // The default three: the true places too, each confirmed by the keyframe before it.
  options.candidates_per_keyframe = 3;
  EXPECT_EQ(matches_of_revisits(DetectLoopCandidates(descriptors, frames, options)),
            (std::set<std::pair<int, int>>{{31, 21}, {31, 4}, {32, 22}, {32, 5}}));
  // The best only, with a prior that rules out keyframes 10 or more before the revisit's start
  // (an odometry that knows the look-alike street is elsewhere): the true places alone.
  options.candidates_per_keyframe = 1;
  const RevisitPrior not_the_look_alike = [](int, int match) { return match < 10; };
  EXPECT_EQ(
      matches_of_revisits(DetectLoopCandidates(descriptors, frames, options, not_the_look_alike)),
      (std::set<std::pair<int, int>>{{31, 4}, {32, 5}}));
}

TEST(LoopDetection, RejectsBadInput) {
  LoopDetectionOptions options;
  cv::Mat floats(3, 128, CV_32F, cv::Scalar(0));
  EXPECT_THROW(DetectLoopCandidates({floats, floats}, {0, 50}, options), Error);
  cv::Mat bytes(3, 128, CV_8U, cv::Scalar(0));
  EXPECT_THROW(DetectLoopCandidates({bytes, bytes}, {50, 0}, options), Error);
  EXPECT_THROW(DetectLoopCandidates({bytes}, {0, 1}, options), Error);
  options.vocabulary_size = 1;
  EXPECT_THROW(DetectLoopCandidates({bytes, bytes}, {0, 50}, options), Error);
  options = LoopDetectionOptions();
  options.candidates_per_keyframe = 0;
  EXPECT_THROW(options.Check(), Error);
}

}  // namespace
}  // namespace comic::sfm
