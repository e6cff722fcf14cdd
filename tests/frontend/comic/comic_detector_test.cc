// The CoMIC detector (Algorithm 1) end to end on images with known answers: rendered polygons
// (sub-pixel vertices, Gaussian blur) on flat and textured backgrounds, geometric and photometric
// changes, degenerate inputs, and the bundled and shared real images. The contract both searches
// keep (input types, fields, order, threads, threshold) is in comic_search_contract_test.cc.
#include "frontend/comic/comic_detector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "io/core/error.h"
#include "io/image/image_io.h"
#include "tests/frontend/comic/polygon_scenes.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

using test::Distance;
using test::ExpectIdentical;
using test::FlatScene;
using test::kSceneSize;
using test::Nearest;
using test::Polygon;
using test::Shapes;
using test::TexturedScene;
using test::Vertices;

// Prints a measured quantity (quoted in docs/comic_detector.md).
void Report(const std::string& what, double value) {
  std::cout << "[ measured ] " << what << ": " << value << "\n";
}

TEST(ComicDetector, NameAndOptionValidation) {
  EXPECT_EQ(ComicDetector().Name(), "comic-paper");
  auto rejects = [](auto mutate) {
    ComicDetectorOptions options;
    mutate(&options);
    try {
      options.Check();
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
      EXPECT_THROW(ComicDetector detector(options), Error);
      return true;
    }
    return false;
  };
  EXPECT_FALSE(rejects([](ComicDetectorOptions*) {}));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->scale = 0; }));
  // Upper bounds (issue 19: scale 1e9 overflowed int in the initial corners' filter supports).
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->scale = 1e9; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->scale = 64.5; }));
  EXPECT_FALSE(rejects([](ComicDetectorOptions* o) { o->scale = 64.0; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->block_size = 5000; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->delta = 1000; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->half_length = 100000; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->max_iterations = 1000000; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->block_size = 4; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->delta = 0; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->half_length = 1; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->max_iterations = 0; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->convergence_tolerance = -1; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->stop_tolerance = -1; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->merge_radius = -1; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->min_stability = -0.5; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->num_threads = -1; }));
  EXPECT_TRUE(rejects([](ComicDetectorOptions* o) { o->min_cornerness = 0.3; }));
}

// The largest accepted values run to the end without overflow (under the sanitizer build, a signed
// overflow in the filter supports or block origins fails this test) and keep their contract.
TEST(ComicDetector, LargestAcceptedOptionsRunOnASmallImage) {
  ComicDetectorOptions options;
  options.scale = ComicDetectorOptions::kMaxScale;
  options.delta = ComicDetectorOptions::kMaxDelta;
  options.half_length = ComicDetectorOptions::kMaxHalfLength;
  const ComicDetector detector(options);
  const cv::Mat image = test::RenderPolygons(test::FlatBackground({240, 200}, 50),
                                             {test::MakeSquare({60.3, 50.6}, 80, 200)}, 1.0);
  const FeatureSet features = detector.Detect(image);
  for (const Feature& f : features) {
    EXPECT_GE(f.x, 0);
    EXPECT_LT(f.x, image.cols);
    EXPECT_GE(f.y, 0);
    EXPECT_LT(f.y, image.rows);
  }
}

TEST(ComicDetector, ImagesSmallerThanABlockOrConstantGiveNoFeatures) {
  const ComicDetector detector;
  // Smaller than a block (100) in one dimension, with a perfectly good corner in it.
  const cv::Mat narrow = test::RenderPolygons(test::FlatBackground({300, 99}, 50),
                                              {test::MakeSquare({40.3, 30.6}, 40, 200)}, 1.0);
  EXPECT_TRUE(detector.Detect(narrow).empty());
  EXPECT_TRUE(detector.Detect(cv::Mat(50, 50, CV_8UC1, cv::Scalar(3))).empty());
  EXPECT_TRUE(detector.Detect(cv::Mat(300, 300, CV_8UC1, cv::Scalar(128))).empty());
  EXPECT_TRUE(detector.Detect(cv::Mat(300, 300, CV_8UC1, cv::Scalar(0))).empty());
}

TEST(ComicDetector, StraightEdgesAndSmoothGradientsGiveNoCorners) {
  const ComicDetector detector;
  const Polygon tilted{{{-10, -10}, {120.3, -10}, {70.7, 210}, {-10, 210}}, 200};
  EXPECT_TRUE(
      detector.Detect(test::RenderPolygons(test::FlatBackground(kSceneSize, 50), {tilted}, 1.0))
          .empty());
  const Polygon vertical{{{-10, -10}, {100.4, -10}, {100.4, 210}, {-10, 210}}, 180};
  EXPECT_TRUE(
      detector.Detect(test::RenderPolygons(test::FlatBackground(kSceneSize, 60), {vertical}, 2.0))
          .empty());
  cv::Mat gradient(kSceneSize, CV_8UC1);
  for (int y = 0; y < gradient.rows; ++y) {
    for (int x = 0; x < gradient.cols; ++x) {
      gradient.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(20 + 0.7 * x + 0.4 * y);
    }
  }
  EXPECT_TRUE(detector.Detect(gradient).empty());
}

TEST(ComicDetector, FindsPolygonCornersOnFlatAndTexturedBackgrounds) {
  const ComicDetector detector;
  const std::vector<std::pair<std::string, cv::Mat>> scenes = {
      {"flat", FlatScene()},
      {"textured (seed 3)", TexturedScene(3)},
      {"textured (seed 4)", TexturedScene(4)}};
  for (const auto& [name, image] : scenes) {
    const FeatureSet features = detector.Detect(image);
    double worst = 0;
    for (const Polygon& shape : Shapes()) {
      for (const cv::Point2d& vertex : shape.vertices) {
        const Feature* f = Nearest(features, vertex);
        EXPECT_LT(Distance(f, vertex), 1.5) << vertex;
        worst = std::max(worst, Distance(f, vertex));
      }
    }
    Report("largest vertex error, " + name + " background, px", worst);
  }
  // On the flat background every feature is a vertex: nothing else has a corner.
  const FeatureSet flat = detector.Detect(FlatScene());
  EXPECT_EQ(flat.size(), Vertices(Shapes()).size());
  // Polarity: the L's reflex vertex points into the dark background, its other vertices into the
  // bright shape.
  const Polygon l_shape = Shapes()[1];
  for (size_t i = 0; i < l_shape.vertices.size(); ++i) {
    const Feature* f = Nearest(flat, l_shape.vertices[i]);
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->polarity, i == 2 ? Polarity::kDark : Polarity::kBright) << "vertex " << i;
  }
}

TEST(ComicDetector, LocalisesBlurredCornersWithinAThirdOfAPixel) {
  const ComicDetector detector;
  double worst = 0, sum = 0;
  int count = 0;
  for (const cv::Point2d offset :
       {cv::Point2d(0, 0), cv::Point2d(0.25, 0.6), cv::Point2d(0.5, 0.1), cv::Point2d(0.8, 0.45)}) {
    const FeatureSet features = detector.Detect(FlatScene(offset.x, offset.y));
    for (const cv::Point2d& vertex : Vertices(Shapes(offset.x, offset.y))) {
      const double error = Distance(Nearest(features, vertex), vertex);
      EXPECT_LT(error, 0.3) << vertex << " offset " << offset;
      worst = std::max(worst, error);
      sum += error;
      ++count;
    }
  }
  Report("blurred polygons at 4 sub-pixel offsets: mean vertex error, px", sum / count);
  Report("blurred polygons at 4 sub-pixel offsets: largest vertex error, px", worst);
}

TEST(ComicDetector, CornersFollowAHalfPixelShift) {
  const ComicDetector detector;
  const FeatureSet base = detector.Detect(FlatScene());
  double least = 1e9, most = -1e9;
  for (const cv::Point2d shift : {cv::Point2d(0.5, 0), cv::Point2d(0, 0.5)}) {
    const FeatureSet moved = detector.Detect(FlatScene(shift.x, shift.y));
    for (const cv::Point2d& vertex : Vertices(Shapes())) {
      const Feature* a = Nearest(base, vertex);
      const Feature* b = Nearest(moved, vertex + shift);
      ASSERT_TRUE(a != nullptr && b != nullptr);
      const cv::Point2d motion(b->x - a->x, b->y - a->y);
      // The motion along the shift is 0.5 +- 0.2; across it, at most 0.2.
      EXPECT_NEAR(motion.dot(shift) / 0.5, 0.5, 0.2) << vertex << " shift " << shift;
      EXPECT_LT(std::abs(motion.cross(shift) / 0.5), 0.2) << vertex << " shift " << shift;
      least = std::min(least, motion.dot(shift) / 0.5);
      most = std::max(most, motion.dot(shift) / 0.5);
    }
  }
  Report("0.5 px shifts: smallest motion of a corner along the shift, px", least);
  Report("0.5 px shifts: largest motion of a corner along the shift, px", most);
}

// The features of `b`, mapped back into `a`'s frame by `to_a`, against `a`'s: for every polygon
// vertex (inside `region`), the features nearest to it in both images are within 1 px.
template <class Map>
void ExpectSameVertexCorners(const FeatureSet& a, const FeatureSet& b, Map to_a,
                             const std::vector<cv::Point2d>& vertices, const cv::Rect2d& region,
                             const std::string& what) {
  FeatureSet b_in_a = b;
  for (Feature& f : b_in_a) {
    const cv::Point2d p = to_a(cv::Point2d(f.x, f.y));
    f.x = static_cast<float>(p.x);
    f.y = static_cast<float>(p.y);
  }
  int checked = 0;
  for (const cv::Point2d& vertex : vertices) {
    if (!region.contains(vertex)) continue;
    ++checked;
    const Feature* fa = Nearest(a, vertex);
    const Feature* fb = Nearest(b_in_a, vertex);
    ASSERT_TRUE(fa != nullptr && fb != nullptr);
    EXPECT_LT(Distance(fa, vertex), 1.5) << what << " " << vertex;
    EXPECT_LT(std::hypot(fa->x - fb->x, fa->y - fb->y), 1.0) << what << " " << vertex;
  }
  EXPECT_GT(checked, 10) << what;
}

TEST(ComicDetector, SameCornersAfterIntegerShiftRotationAndAffineIntensityChange) {
  const ComicDetector detector;
  // A larger textured scene, so that an integer shift is two crops of it.
  const cv::Size big(240, 230);
  const cv::Mat scene =
      test::RenderPolygons(test::TexturedBackground(big, 21, 20, 110, 8), Shapes(12, 10), 1.0);
  const std::vector<cv::Point2d> vertices = Vertices(Shapes(12, 10));
  const cv::Rect crop_a(0, 0, 220, 215), crop_b(11, 7, 220, 215);
  const FeatureSet a = detector.Detect(scene(crop_a));
  const FeatureSet b = detector.Detect(scene(crop_b));
  ExpectSameVertexCorners(
      a, b, [](cv::Point2d p) { return p + cv::Point2d(11, 7); }, vertices,
      cv::Rect2d(20, 20, 190, 180), "integer shift");

  const cv::Mat image = TexturedScene(5);
  const FeatureSet base = detector.Detect(image);
  const cv::Rect2d all(0, 0, image.cols, image.rows);
  cv::Mat rotated;
  cv::rotate(image, rotated, cv::ROTATE_90_CLOCKWISE);  // (x, y) -> (rows - 1 - y, x)
  ExpectSameVertexCorners(
      base, detector.Detect(rotated),
      [&](cv::Point2d p) { return cv::Point2d(p.y, image.rows - 1 - p.x); }, Vertices(Shapes()),
      all, "rotation by 90°");
  for (const auto& [gain, offset] : {std::pair{0.7, 30.0}, std::pair{1.2, -20.0}}) {
    cv::Mat changed;
    image.convertTo(changed, CV_8U, gain, offset);
    ExpectSameVertexCorners(
        base, detector.Detect(changed), [](cv::Point2d p) { return p; }, Vertices(Shapes()), all,
        "intensity " + std::to_string(gain) + " I + " + std::to_string(offset));
  }
}

TEST(ComicDetector, RotationBy90DegreesRepeatsTheStrongFeatures) {
  // Beyond the vertices: the strongest features of a textured scene, texture corners included.
  const ComicDetector detector;
  const cv::Mat image = TexturedScene(6);
  cv::Mat rotated;
  cv::rotate(image, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);  // (x, y) -> (y, cols - 1 - x)
  const FeatureSet a = detector.Detect(image);
  const FeatureSet b = detector.Detect(rotated);
  ASSERT_GT(a.size(), 40u);
  int repeated = 0;
  const int strongest = 40;
  for (int i = 0; i < strongest; ++i) {
    const cv::Point2d in_b(a[i].y, image.cols - 1 - a[i].x);
    repeated += Distance(Nearest(b, in_b), in_b) < 1.0;
  }
  EXPECT_GE(repeated, 36) << "of the " << strongest << " strongest features";
  Report("rotation by 90 degrees: of the 40 strongest features, repeated within 1 px", repeated);
}

TEST(ComicDetector, TexturedScenesRepeatUnderOneGreyLevelOfNoise) {
  // Repeatability on the same scene with Gaussian noise of one grey level added: a corner must
  // not depend on details far out along its arms. (Before the vertex correction was restricted
  // to straight arms it extrapolated textured arms by up to 3 px, and this share was 0.71.)
  const ComicDetector detector;
  int features = 0, repeated = 0;
  for (int cell : {8, 6, 4}) {
    for (uint64_t seed : {3, 4, 5}) {
      const cv::Mat image = test::RenderPolygons(
          test::TexturedBackground(kSceneSize, seed, 20, 110, cell), Shapes(), 1.0);
      cv::Mat noise(image.size(), CV_32F);
      cv::RNG rng(seed + 100);
      rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
      cv::Mat noisy;
      image.convertTo(noisy, CV_32F);
      noisy += noise;
      noisy.convertTo(noisy, CV_8U);
      const FeatureSet a = detector.Detect(image);
      const FeatureSet b = detector.Detect(noisy);
      for (const Feature& f : a) {
        if (f.x < 15 || f.y < 15 || f.x > kSceneSize.width - 15 || f.y > kSceneSize.height - 15) {
          continue;
        }
        ++features;
        repeated += Distance(Nearest(b, {f.x, f.y}), {f.x, f.y}) <= 1.0;
      }
    }
  }
  ASSERT_GT(features, 800);
  const double share = static_cast<double>(repeated) / features;
  EXPECT_GT(share, 0.75);
  Report("9 textured scenes plus noise of 1 grey level: share of the features repeated within 1 px",
         share);
}

TEST(ComicDetector, BoundaryCornersAreTheSameOnDifferentBackgrounds) {
  // The paper's point: the iso-curves of an object's boundary, hence its corners, follow the
  // object whatever the background it is seen against. Under blur a level line's offset from
  // the boundary depends on the background next to it, so "the same place" is within the 1.5 px
  // match tolerance (typically 0.6 px; docs/comic_detector.md).
  const ComicDetector detector;
  const std::vector<Polygon> object = {
      test::MakeL({40.3, 50.8}, 90, 40, 215),
      test::MakeTriangle({150.2, 30.6}, {185.7, 85.4}, {140.9, 100.3}, 225)};
  const FeatureSet a = detector.Detect(
      test::RenderPolygons(test::TexturedBackground(kSceneSize, 101, 20, 120, 8), object, 1.0));
  const FeatureSet b = detector.Detect(
      test::RenderPolygons(test::TexturedBackground(kSceneSize, 202, 10, 110, 6), object, 1.0));
  std::vector<double> disagreement;
  for (const cv::Point2d& vertex : Vertices(object)) {
    const Feature* fa = Nearest(a, vertex);
    const Feature* fb = Nearest(b, vertex);
    ASSERT_TRUE(fa != nullptr && fb != nullptr);
    EXPECT_LT(Distance(fa, vertex), 1.5) << vertex;
    EXPECT_LT(Distance(fb, vertex), 1.5) << vertex;
    disagreement.push_back(std::hypot(fa->x - fb->x, fa->y - fb->y));
    EXPECT_LT(disagreement.back(), 1.5) << vertex;
  }
  std::sort(disagreement.begin(), disagreement.end());
  EXPECT_LT(disagreement[disagreement.size() / 2], 1.0);
  Report("object on two backgrounds: median distance between its corners, px",
         disagreement[disagreement.size() / 2]);
  Report("object on two backgrounds: largest distance between its corners, px",
         disagreement.back());
}

TEST(ComicDetector, SideMaskSplitsThePatchAlongTheShapeBoundary) {
  const ComicDetector detector;
  const cv::Point2d vertex(60.4, 70.7);
  const Polygon square = test::MakeSquare(vertex, 50, 200);
  for (const cv::Mat& image :
       {test::RenderPolygons(test::FlatBackground({160, 160}, 50), {square}, 1.0),
        test::RenderPolygons(test::TexturedBackground({160, 160}, 9, 20, 110, 8), {square}, 1.0)}) {
    const FeatureSet features = detector.Detect(image);
    const Feature* f = Nearest(features, vertex);
    ASSERT_LT(Distance(f, vertex), 1.5);
    ASSERT_TRUE(f->HasSideMask());
    const int cx = static_cast<int>(std::lround(f->x));
    const int cy = static_cast<int>(std::lround(f->y));
    int checked = 0;
    for (int v = -kPatchRadius; v <= kPatchRadius; ++v) {
      for (int u = -kPatchRadius; u <= kPatchRadius; ++u) {
        const double x = cx + u, y = cy + v;
        // Distance to the square's boundary (negative inside).
        const double inside = std::min(x - vertex.x, y - vertex.y);
        if (std::abs(inside) < 2.0) continue;
        const PatchSide side = f->side_mask[(v + kPatchRadius) * kPatchSize + u + kPatchRadius];
        EXPECT_EQ(side, inside > 0 ? PatchSide::kPlus : PatchSide::kMinus) << u << "," << v;
        ++checked;
      }
    }
    EXPECT_GT(checked, 400);
  }
}

TEST(ComicDetector, StatisticsAccountForEverySeedAndLeaveTheFeaturesUnchanged) {
  const cv::Mat image = TexturedScene(10);
  ComicDetectorOptions options;
  options.num_threads = 2;
  const ComicDetector detector(options);
  ComicDetectionStats stats;
  stats.num_seeds = -7;  // overwritten, not accumulated
  const FeatureSet features = detector.Detect(image, &stats);
  ExpectIdentical(features, detector.Detect(image));
  // Every feature is a settled seed (duplicates merged), every settled seed took at least one
  // iteration, and no seed took more than max_iterations.
  EXPECT_GE(stats.num_settled, static_cast<int>(features.size()));
  EXPECT_GE(stats.num_seeds, stats.num_settled);
  EXPECT_GE(stats.num_iterations, stats.num_settled);
  EXPECT_LE(stats.num_iterations, options.max_iterations * stats.num_seeds);
  EXPECT_GT(stats.initialisation_ms, 0.0);
  EXPECT_GT(stats.convergence_ms, 0.0);
  EXPECT_GE(stats.output_ms, 0.0);
  // The counts are properties of the image, not of the run.
  ComicDetectionStats again;
  detector.Detect(image, &again);
  EXPECT_EQ(again.num_seeds, stats.num_seeds);
  EXPECT_EQ(again.num_iterations, stats.num_iterations);
  EXPECT_EQ(again.num_settled, stats.num_settled);
  // A frame smaller than a block does no work.
  ComicDetectionStats none;
  none.num_seeds = 5;
  EXPECT_TRUE(detector.Detect(cv::Mat(40, 40, CV_8UC1, cv::Scalar(9)), &none).empty());
  EXPECT_EQ(none.num_seeds, 0);
  EXPECT_EQ(none.num_iterations, 0);
}

TEST(ComicDetector, SkippingDuplicateConvergencePathsKeepsTheCorners) {
  // Seeds that reach another seed's state are suspended; the corners found must be those every
  // seed converged to the end gives, up to which of two near-identical results the merge keeps.
  ComicDetectorOptions every_path;
  every_path.skip_duplicate_paths = false;
  for (uint64_t seed : {3, 6}) {
    const cv::Mat image = TexturedScene(seed);
    const FeatureSet skipping = ComicDetector().Detect(image);
    const FeatureSet full = ComicDetector(every_path).Detect(image);
    ASSERT_GT(full.size(), 100u);
    int same = 0;
    for (const Feature& f : full) same += Distance(Nearest(skipping, {f.x, f.y}), {f.x, f.y}) < 0.1;
    EXPECT_GE(same, 0.9 * full.size()) << "seed " << seed;
    EXPECT_NEAR(static_cast<double>(skipping.size()), static_cast<double>(full.size()),
                0.05 * full.size());
    Report("duplicate paths skipped, seed " + std::to_string(seed) +
               ": share of the features within 0.1 px of those found converging every seed",
           static_cast<double>(same) / full.size());
  }
}

TEST(ComicDetector, FullResolutionInitialisationFindsTheSameCorners) {
  ComicDetectorOptions options;
  options.coarse_initialisation = false;
  const FeatureSet features = ComicDetector(options).Detect(FlatScene(0.3, 0.7));
  for (const cv::Point2d& vertex : Vertices(Shapes(0.3, 0.7))) {
    EXPECT_LT(Distance(Nearest(features, vertex), vertex), 0.3) << vertex;
  }
}

TEST(ComicDetector, BundledKittiFrame) {
  const io::LoadedImage frame =
      io::LoadImage(test::ExampleDir() + "/image_l/000000.png", /*resize_height=*/0);
  ComicDetectorOptions options;
  options.num_threads = 2;
  const FeatureSet features = ComicDetector(options).Detect(frame.gray);
  EXPECT_GT(features.size(), 500u);
  int bright = 0;
  for (const Feature& f : features) bright += f.polarity == Polarity::kBright;
  // Both polarities occur in a real scene.
  EXPECT_GT(bright, static_cast<int>(features.size()) / 5);
  EXPECT_LT(bright, static_cast<int>(features.size()) * 4 / 5);
}

TEST(ComicDetector, ConesCornersLieOnSilhouettesAndInside) {
  COMIC_REQUIRE_SHARED_DATA();
  const std::string dir = test::SharedDataDir() + "/middlebury2003_cones";
  const io::LoadedImage image = io::LoadImage(dir + "/im2.png");
  const cv::Mat disc = cv::imread(dir + "/disc.png", cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(disc.size(), image.gray.size());
  ComicDetectorOptions options;
  options.num_threads = 2;
  const FeatureSet features = ComicDetector(options).Detect(image.gray);
  ASSERT_GT(features.size(), 300u);
  // disc.png: 255 near a depth discontinuity (the objects' silhouettes), 128 elsewhere.
  int boundary = 0, interior = 0;
  for (int i = 0; i < 300; ++i) {
    const int v = disc.at<uint8_t>(static_cast<int>(std::lround(features[i].y)),
                                   static_cast<int>(std::lround(features[i].x)));
    boundary += v == 255;
    interior += v == 128;
  }
  const double boundary_area = cv::countNonZero(disc == 255) / static_cast<double>(disc.total());
  Report("cones, 300 strongest: on the depth-discontinuity band (disc = 255)", boundary);
  Report("cones, 300 strongest: interior (disc = 128)", interior);
  Report("cones: share of the image in the depth-discontinuity band", boundary_area);
  // More of the strongest corners on silhouettes than their share of the image, and many inside.
  EXPECT_GT(boundary / 300.0, boundary_area)
      << boundary << " boundary, " << interior << " interior";
  EXPECT_GT(interior, 60);
}

}  // namespace
}  // namespace comic::frontend
