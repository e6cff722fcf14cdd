#include "frontend/scale_space_detector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "frontend/combined_detector.h"
#include "frontend/detector_factory.h"
#include "io/core/error.h"
#include "tests/frontend/synthetic_images.h"

namespace comic::frontend {
namespace {

// Prints a measured quantity (quoted in the commit and the report).
void Report(const std::string& what, double value) {
  std::cout << "[ measured ] " << what << ": " << value << "\n";
}

// A detector with an exactly known answer: one feature at the intensity-weighted centroid of the
// image. Area averaging keeps the centroid where it is (each level pixel is the mean of the
// level-0 pixels it covers), so the mapped feature of every level must land on level 0's.
class CentroidDetector : public Detector {
 public:
  std::string Name() const override { return "centroid"; }
  FeatureSet Detect(const cv::Mat& gray) const override {
    const cv::Moments m = cv::moments(gray);
    Feature f;
    f.x = static_cast<float>(m.m10 / m.m00);
    f.y = static_cast<float>(m.m01 / m.m00);
    f.scale = 1.0f;
    f.response = 1.0f;
    return {f};
  }
};

// A Gaussian blob of σ = 10 px centred at `centre` on black.
cv::Mat Blob(cv::Size size, cv::Point2d centre) {
  cv::Mat image(size, CV_8U);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const double d2 = (x - centre.x) * (x - centre.x) + (y - centre.y) * (y - centre.y);
      image.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(250.0 * std::exp(-d2 / 200.0));
    }
  }
  return image;
}

TEST(ScaleSpaceDetector, MapsPositionsBackExactlyAtEveryLevel) {
  const cv::Point2d centre(161.37, 118.81);
  const cv::Mat image = Blob({320, 256}, centre);
  for (const double factor : {2.0, 1.5}) {
    ScaleSpaceDetectorOptions options;
    options.num_levels = 4;
    options.level_factor = factor;
    options.min_level_size = 16;
    const ScaleSpaceDetector detector(std::make_unique<CentroidDetector>(), options);
    const std::vector<FeatureSet> levels = detector.DetectLevels(image);
    ASSERT_EQ(levels.size(), 4u);
    for (size_t l = 0; l < levels.size(); ++l) {
      ASSERT_EQ(levels[l].size(), 1u);
      const Feature& f = levels[l][0];
      // Off by 0.5 (f^l − 1) px with the corner convention x0 = x_l · f^l: 0.5, 1.5, 3.5 px.
      EXPECT_NEAR(f.x, centre.x, 0.02) << "factor " << factor << " level " << l;
      EXPECT_NEAR(f.y, centre.y, 0.02) << "factor " << factor << " level " << l;
      EXPECT_FLOAT_EQ(f.scale, static_cast<float>(std::pow(factor, l)));
    }
  }
  EXPECT_DOUBLE_EQ(ToLevelZero(0.0, 2.0), 0.5);    // level pixel 0 = mean of level-0 pixels 0, 1
  EXPECT_DOUBLE_EQ(ToLevelZero(-0.5, 4.0), -0.5);  // the image's edges coincide at every level
}

TEST(ScaleSpaceDetector, BuildsLevelsDownToTheSmallestSize) {
  ScaleSpaceDetectorOptions options;
  options.num_levels = 8;
  options.min_level_size = 32;
  const std::vector<cv::Mat> levels = BuildScaleLevels(cv::Mat(301, 403, CV_8U, 7), options);
  ASSERT_EQ(levels.size(), 4u);  // 301 -> 150 -> 75 -> 38 -> (19: below 32)
  EXPECT_EQ(levels[1].size(), cv::Size(202, 150));
  EXPECT_EQ(levels[3].size(), cv::Size(50, 38));
  EXPECT_THROW(BuildScaleLevels(cv::Mat(40, 40, CV_32F), options), Error);
}

TEST(ScaleSpaceDetector, MapsSideMasksAndCurvesToLevelZero) {
  Feature f;
  f.x = 10.2f;
  f.y = 20.7f;
  f.scale = 8.4f;
  f.level = 120;
  f.curve = {{9.0f, 20.0f}, {11.0f, 22.0f}};
  // Left half of the level's patch kPlus, right half kMinus, the centre column kNone.
  f.side_mask.assign(kPatchSize * kPatchSize, PatchSide::kNone);
  for (int v = 0; v < kPatchSize; ++v) {
    for (int u = 0; u < kPatchSize; ++u) {
      if (u != kPatchRadius) {
        f.side_mask[v * kPatchSize + u] = u < kPatchRadius ? PatchSide::kPlus : PatchSide::kMinus;
      }
    }
  }
  const Feature g = MapToLevelZero(f, 2.0);
  EXPECT_FLOAT_EQ(g.x, 20.9f);
  EXPECT_FLOAT_EQ(g.y, 41.9f);
  EXPECT_FLOAT_EQ(g.scale, 16.8f);
  EXPECT_EQ(g.level, 120);
  ASSERT_EQ(g.curve.size(), 2u);
  EXPECT_FLOAT_EQ(g.curve[1].x, 22.5f);
  ASSERT_TRUE(g.HasSideMask());
  // Level-0 patch centre 21 (x): level-0 pixel 21 + u lies in level pixel floor((21.5 + u) / 2),
  // which is the level centre 10 for u in [−1, 0]: kNone there, kPlus left of it, kMinus right.
  for (int u = -kPatchRadius; u <= kPatchRadius; ++u) {
    const PatchSide expected =
        u < -1 ? PatchSide::kPlus : (u > 0 ? PatchSide::kMinus : PatchSide::kNone);
    EXPECT_EQ(g.side_mask[kPatchRadius * kPatchSize + u + kPatchRadius], expected) << u;
  }
}

Feature At(float x, float y, float response, float scale) {
  Feature f;
  f.x = x;
  f.y = y;
  f.response = response;
  f.scale = scale;
  return f;
}

TEST(ScaleSpaceDetector, MergeKeepsEachCornerAtItsStrongestLevel) {
  const std::vector<FeatureSet> levels = {
      {At(10, 10, 5, 2), At(11, 10, 4, 2), At(50, 50, 1, 2)},  // level 0: a weak one at (50, 50)
      {At(51, 50, 3, 4), At(10.5f, 12, 2, 4)},                 // level 1
      {At(52, 52, 6, 8)}};                                     // level 2
  const FeatureSet merged = MergeScaleLevels(levels, 3.0);
  // (52, 52) strongest; (10, 10) and (11, 10): one level, both kept; (51, 50) is 2.2 px from
  // (52, 52), (10.5, 12) 2.1 from (10, 10), (50, 50) 2.8 from (52, 52): all three dropped.
  ASSERT_EQ(merged.size(), 3u);
  EXPECT_EQ(merged[0].Position(), cv::Point2f(52, 52));
  EXPECT_EQ(merged[1].Position(), cv::Point2f(10, 10));
  EXPECT_EQ(merged[2].Position(), cv::Point2f(11, 10));
  EXPECT_EQ(MergeScaleLevels(levels, 0.0).size(), 6u);  // 0: every level's features
  EXPECT_EQ(MergeScaleLevels(levels, 0.0)[0].response, 6.0f);
  EXPECT_THROW(MergeScaleLevels(levels, -1.0), Error);
}

TEST(ScaleSpaceDetector, CheckRejectsBadOptions) {
  EXPECT_NO_THROW(ScaleSpaceDetectorOptions().Check());
  auto bad = [](auto change) {
    ScaleSpaceDetectorOptions options;
    change(options);
    EXPECT_THROW(options.Check(), Error);
    DetectorOptions detector;
    detector.name = "harris";
    detector.scale_space = options;
    EXPECT_THROW(detector.Check(), Error);
    EXPECT_THROW(MakeDetector(detector), Error);
  };
  bad([](ScaleSpaceDetectorOptions& o) { o.num_levels = 0; });
  bad([](ScaleSpaceDetectorOptions& o) { o.num_levels = 17; });
  bad([](ScaleSpaceDetectorOptions& o) { o.level_factor = 1.0; });
  bad([](ScaleSpaceDetectorOptions& o) { o.level_factor = 4.5; });
  bad([](ScaleSpaceDetectorOptions& o) { o.level_factor = std::nan(""); });
  bad([](ScaleSpaceDetectorOptions& o) { o.duplicate_radius_px = -0.5; });
  bad([](ScaleSpaceDetectorOptions& o) { o.duplicate_radius_px = INFINITY; });
  bad([](ScaleSpaceDetectorOptions& o) { o.min_level_size = 7; });
  EXPECT_THROW(ScaleSpaceDetector(nullptr, ScaleSpaceDetectorOptions()), Error);
  try {
    ScaleSpaceDetectorOptions options;
    options.level_factor = 0.5;
    options.Check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("level_factor"), std::string::npos) << e.what();
  }
}

TEST(ScaleSpaceDetector, FactoryWrapsEachDetectorOnlyWithSeveralLevels) {
  DetectorOptions options;
  options.name = "harris";
  EXPECT_EQ(dynamic_cast<const ScaleSpaceDetector*>(MakeDetector(options).get()), nullptr);
  options.scale_space.num_levels = 3;
  const auto harris = MakeDetector(options);
  ASSERT_NE(dynamic_cast<const ScaleSpaceDetector*>(harris.get()), nullptr);
  EXPECT_EQ(harris->Name(), "harris");  // the descriptor's σ per scale is chosen by name
  // A combined detector stays one (tracked component by component), its components in scale
  // space.
  options.name = "harris+fast";
  const auto combined = MakeDetector(options);
  const auto* parts = dynamic_cast<const CombinedDetector*>(combined.get());
  ASSERT_NE(parts, nullptr);
  EXPECT_EQ(parts->Name(), "harris+fast");
  for (size_t i = 0; i < parts->NumComponents(); ++i) {
    EXPECT_NE(dynamic_cast<const ScaleSpaceDetector*>(&parts->Component(i)), nullptr);
  }
}

// ---- the same contract for harris and comic

// Harris: a checkerboard of 32 px cells at a sub-pixel offset (its X-junctions stay where they
// are under any blur, by symmetry). CoMIC: polygons twice the size of the CoMIC tests' (an X
// junction has no single iso-curve corner), so that their sides are still 20+ px at level 2.
struct Scene {
  cv::Mat image;
  std::vector<cv::Point2d> corners;
};

Scene Checkerboard(double blur_sigma) {
  std::vector<test::Polygon> squares;
  const cv::Point2d origin(24.3, 21.6);
  const double cell = 32.0;
  Scene scene;
  for (int j = 0; j < 7; ++j) {
    for (int i = 0; i < 10; ++i) {
      if ((i + j) % 2 == 0) {
        squares.push_back(test::MakeSquare(origin + cv::Point2d(i * cell, j * cell), cell, 190));
      }
      if (i > 0 && j > 0) scene.corners.push_back(origin + cv::Point2d(i * cell, j * cell));
    }
  }
  scene.image = test::RenderPolygons(test::FlatBackground({368, 270}, 60), squares, blur_sigma);
  return scene;
}

Scene Polygons(double blur_sigma) {
  const std::vector<test::Polygon> shapes = {
      test::MakeSquare({60.3, 71.2}, 90, 200), test::MakeL({220.4, 61.4}, 120, 50, 190),
      test::MakeTriangle({80.8, 350.4}, {211.2, 330.6}, {120.2, 201.6}, 215),
      test::MakeT({240.6, 230.8}, 120, 40, 44, 130, 180)};
  Scene scene;
  for (const test::Polygon& p : shapes) {
    scene.corners.insert(scene.corners.end(), p.vertices.begin(), p.vertices.end());
  }
  scene.image = test::RenderPolygons(test::FlatBackground({400, 400}, 50), shapes, blur_sigma);
  return scene;
}

struct DetectorCase {
  std::string name;
  Scene (*scene)(double blur_sigma);
  // The coarsest level at which the blurred copy (σ 3 px) is still too blurred for the
  // detector's positions to stay within 1 px of the sharp image's, plus one. Harris: at level 1
  // (σ 1.5 level px beside its σ_D = 1) an X junction's maximum splits into four around it and
  // an L corner's moves inwards by 1.0-1.2 px (measured); at level 2 (0.75) both hold. CoMIC's
  // vertex correction (curve_cornerness.h) puts the corner back on the arms' intersection at
  // level 1 already.
  int first_blur_tolerant_level;
};

class ScaleSpaceContract : public testing::TestWithParam<DetectorCase> {
 protected:
  DetectorOptions Options(int levels, int threads = 1) const {
    DetectorOptions options;
    options.name = GetParam().name;
    options.comic.num_threads = threads;
    options.scale_space.num_levels = levels;
    return options;
  }
  float BaseScale() const {
    return GetParam().name == "harris"
               ? static_cast<float>(HarrisDetectorOptions().integration_sigma)
               : static_cast<float>(ComicDirectDetectorOptions().scale);
  }
};

double DistanceToNearest(const FeatureSet& features, const cv::Point2d& p) {
  double best = 1e300;
  for (const Feature& f : features) best = std::min(best, std::hypot(f.x - p.x, f.y - p.y));
  return best;
}

// The features of `level` at most `max_distance` px from a true corner.
FeatureSet AtCorners(const FeatureSet& level, const std::vector<cv::Point2d>& corners,
                     double max_distance) {
  FeatureSet near;
  for (const Feature& f : level) {
    for (const cv::Point2d& c : corners) {
      if (std::hypot(f.x - c.x, f.y - c.y) <= max_distance) {
        near.push_back(f);
        break;
      }
    }
  }
  return near;
}

// Issue 41's known answer: a Gaussian-blurred copy (σ 3) yields features at the coarser levels
// that land within one (level-0) pixel of the sharp image's features of the same level.
TEST_P(ScaleSpaceContract, BlurredCopyFindsTheSharpFeaturesAtCoarserLevels) {
  const Scene sharp = GetParam().scene(0.0);
  const Scene blurred = GetParam().scene(3.0);
  const auto detector = MakeDetector(Options(3));
  const auto& scale_space = dynamic_cast<const ScaleSpaceDetector&>(*detector);
  const std::vector<FeatureSet> sharp_levels = scale_space.DetectLevels(sharp.image);
  const std::vector<FeatureSet> blurred_levels = scale_space.DetectLevels(blurred.image);
  ASSERT_EQ(sharp_levels.size(), 3u);
  ASSERT_EQ(blurred_levels.size(), 3u);
  for (size_t l = 1; l < 3; ++l) {
    // The blurred image's features at the corners (within 2^l px: a corner's feature at that
    // level), each within 1 px of one of the sharp image's at the same level, from the first
    // level at which the detector's position stands the blur of σ = 3 / 2^l level pixels.
    const FeatureSet found = AtCorners(blurred_levels[l], blurred.corners, std::pow(2.0, l));
    const bool asserted = static_cast<int>(l) >= GetParam().first_blur_tolerant_level;
    double worst = 0.0;
    for (const Feature& f : found) {
      const double d = DistanceToNearest(sharp_levels[l], f.Position());
      worst = std::max(worst, d);
      if (asserted) {
        EXPECT_LE(d, 1.0) << GetParam().name << " level " << l << " at " << f.Position();
      }
      EXPECT_FLOAT_EQ(f.scale, BaseScale() * static_cast<float>(std::pow(2.0, l)));
    }
    Report(GetParam().name + " level " + std::to_string(l) + ": blurred features at corners",
           static_cast<double>(found.size()));
    Report(GetParam().name + " level " + std::to_string(l) + ": worst distance to sharp, px",
           worst);
    if (asserted) {
      EXPECT_GE(found.size(), blurred.corners.size() / 3) << GetParam().name << " level " << l;
    }
  }
  // With the pyramid, the blurred image yields more features, the new ones at coarser scales.
  const FeatureSet one = MakeDetector(Options(1))->Detect(blurred.image);
  const FeatureSet three = detector->Detect(blurred.image);
  const auto coarser = [&](const FeatureSet& features) {
    return std::count_if(features.begin(), features.end(),
                         [&](const Feature& f) { return f.scale > 1.5f * BaseScale(); });
  };
  const size_t one_at_corners = AtCorners(one, blurred.corners, 2.0).size();
  const size_t three_at_corners = AtCorners(three, blurred.corners, 2.0).size();
  Report(GetParam().name + " blurred, 1 level: features (at corners)",
         static_cast<double>(one.size()) + one_at_corners / 1000.0);
  Report(GetParam().name + " blurred, 3 levels: features (at corners)",
         static_cast<double>(three.size()) + three_at_corners / 1000.0);
  EXPECT_GT(three.size(), one.size());
  EXPECT_EQ(coarser(one), 0);
  EXPECT_GT(coarser(three), 0);
  EXPECT_TRUE(std::is_sorted(three.begin(), three.end(), [](const Feature& a, const Feature& b) {
    return a.response > b.response;
  }));
}

// A known answer per level: each level's features at the scene's corners map onto the corners.
TEST_P(ScaleSpaceContract, CoarseFeaturesLandOnTheCornersInLevelZeroPixels) {
  const Scene scene = GetParam().scene(1.0);
  const auto detector = MakeDetector(Options(3));
  const std::vector<FeatureSet> levels =
      dynamic_cast<const ScaleSpaceDetector&>(*detector).DetectLevels(scene.image);
  for (size_t l = 0; l < levels.size(); ++l) {
    double sum = 0.0;
    int count = 0;
    for (const cv::Point2d& c : scene.corners) {
      const double d = DistanceToNearest(levels[l], c);
      if (d > std::pow(2.0, l) + 1.0) continue;  // not found at this level
      sum += d;
      ++count;
    }
    ASSERT_GT(count, 0) << GetParam().name << " level " << l;
    Report(GetParam().name + " level " + std::to_string(l) + ": mean distance to the corners, px",
           sum / count);
    // Half a level pixel on average: a wrong pixel convention alone would add 0.5 (2^l − 1) px.
    EXPECT_LE(sum / count, 0.5 * std::pow(2.0, l)) << GetParam().name << " level " << l;
  }
}

TEST_P(ScaleSpaceContract, NoTwoFeaturesOfDifferentLevelsCloserThanTheRadius) {
  // A textured background: candidates everywhere, at every level.
  std::vector<test::Polygon> shapes = {
      test::MakeSquare({60.3, 71.2}, 90, 200),
      test::MakeTriangle({80.8, 350.4}, {211.2, 330.6}, {120.2, 201.6}, 215)};
  const cv::Mat image =
      test::RenderPolygons(test::TexturedBackground({320, 400}, 5, 20, 120, 6), shapes, 1.0);
  const DetectorOptions options = Options(3);
  const FeatureSet features = MakeDetector(options)->Detect(image);
  const double r = options.scale_space.duplicate_radius_px;
  const auto level = [&](const Feature& f) {
    return std::lround(std::log2(f.scale / BaseScale()));
  };
  std::vector<int> per_level(3, 0);
  for (size_t i = 0; i < features.size(); ++i) {
    ++per_level.at(level(features[i]));
    for (size_t j = i + 1; j < features.size(); ++j) {
      if (level(features[i]) == level(features[j])) continue;
      EXPECT_GE(std::hypot(features[i].x - features[j].x, features[i].y - features[j].y), r);
    }
  }
  for (int l = 0; l < 3; ++l) {
    Report(GetParam().name + " textured: features of level " + std::to_string(l), per_level[l]);
    EXPECT_GT(per_level[l], 0) << l;
  }
}

TEST_P(ScaleSpaceContract, SameFeaturesForAnyThreadCount) {
  const cv::Mat image = GetParam().scene(2.0).image;
  const FeatureSet one = MakeDetector(Options(3, 1))->Detect(image);
  const FeatureSet three = MakeDetector(Options(3, 3))->Detect(image);
  ASSERT_EQ(one.size(), three.size());
  ASSERT_FALSE(one.empty());
  for (size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].x, three[i].x);
    EXPECT_EQ(one[i].y, three[i].y);
    EXPECT_EQ(one[i].scale, three[i].scale);
    EXPECT_EQ(one[i].response, three[i].response);
    EXPECT_EQ(one[i].side_mask, three[i].side_mask);
    EXPECT_EQ(one[i].curve, three[i].curve);
  }
}

TEST_P(ScaleSpaceContract, OneLevelIsTheDetectorAlone) {
  const cv::Mat image = GetParam().scene(1.0).image;
  DetectorOptions plain = Options(1);
  const FeatureSet expected = MakeDetector(plain)->Detect(image);
  const ScaleSpaceDetector wrapped(MakeDetector(plain), ScaleSpaceDetectorOptions());
  const FeatureSet got = wrapped.Detect(image);
  ASSERT_EQ(got.size(), expected.size());
  for (size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].Position(), expected[i].Position());
}

INSTANTIATE_TEST_SUITE_P(Detectors, ScaleSpaceContract,
                         testing::Values(DetectorCase{"harris", &Checkerboard, 2},
                                         DetectorCase{"comic", &Polygons, 1}),
                         [](const testing::TestParamInfo<DetectorCase>& info) {
                           return info.param.name;
                         });

}  // namespace
}  // namespace comic::frontend
