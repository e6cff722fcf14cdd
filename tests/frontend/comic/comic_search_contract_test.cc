// The contract every CoMIC search keeps (frontend/detector.h), said once and run over both
// searches: Algorithm 1's seeds and convergence (ComicDetector, "comic-paper") and the direct
// search of the §2 definition over the component trees (ComicDirectDetector, "comic"). Each
// detector's own test file holds what only it does (statistics, run records, real images).
#include <gtest/gtest.h>

#include <type_traits>
#include <utility>

#include "frontend/comic/comic_detector.h"
#include "frontend/comic/comic_direct_detector.h"
#include "frontend/matching/tracker.h"
#include "io/core/error.h"
#include "tests/frontend/comic/polygon_scenes.h"

namespace comic::frontend {
namespace {

using test::Polygon;

// The type parameter is the detector; its options type is what options() returns.
template <class DetectorType>
class ComicSearchContract : public ::testing::Test {
 protected:
  using Options = std::decay_t<decltype(std::declval<DetectorType>().options())>;
  static FeatureSet Detect(const cv::Mat& gray, const Options& options = {}) {
    return DetectorType(options).Detect(gray);
  }
};

using Searches = ::testing::Types<ComicDetector, ComicDirectDetector>;
TYPED_TEST_SUITE(ComicSearchContract, Searches);

TYPED_TEST(ComicSearchContract, RejectsImagesThatAreNotEightBitGrey) {
  for (const cv::Mat& image : {cv::Mat(), cv::Mat(120, 120, CV_8UC3, cv::Scalar::all(9)),
                               cv::Mat(120, 120, CV_16UC1, cv::Scalar(9))}) {
    try {
      this->Detect(image);
      ADD_FAILURE() << "no error for type " << image.type();
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    }
  }
}

TYPED_TEST(ComicSearchContract, TinyOrUniformImagesGiveNoFeatures) {
  EXPECT_TRUE(this->Detect(cv::Mat(1, 1, CV_8UC1, cv::Scalar(3))).empty());
  EXPECT_TRUE(this->Detect(cv::Mat(3, 500, CV_8UC1, cv::Scalar(3))).empty());
  for (int value : {0, 128, 255}) {
    EXPECT_TRUE(this->Detect(cv::Mat(300, 300, CV_8UC1, cv::Scalar(value))).empty()) << value;
  }
}

TYPED_TEST(ComicSearchContract, FindsTheCornersOfSyntheticPolygons) {
  for (const cv::Mat& image : {test::FlatScene(), test::TexturedScene(3)}) {
    const FeatureSet features = this->Detect(image);
    for (const cv::Point2d& vertex : test::Vertices(test::Shapes())) {
      EXPECT_LT(test::Distance(test::Nearest(features, vertex), vertex), 1.5) << vertex;
    }
  }
  // On the flat background every feature is a vertex: nothing else has a corner.
  const FeatureSet flat = this->Detect(test::FlatScene());
  EXPECT_EQ(flat.size(), test::Vertices(test::Shapes()).size());
  // Polarity: the L's reflex vertex points into the dark background, its other vertices into the
  // bright shape.
  const Polygon l_shape = test::Shapes()[1];
  for (size_t i = 0; i < l_shape.vertices.size(); ++i) {
    const Feature* f = test::Nearest(flat, l_shape.vertices[i]);
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->polarity, i == 2 ? Polarity::kDark : Polarity::kBright) << "vertex " << i;
  }
}

TYPED_TEST(ComicSearchContract, FeaturesLieInsideTheImageWithEveryFieldFilled) {
  const typename TestFixture::Options options;
  const cv::Mat image = test::TexturedScene(7);
  const FeatureSet features = this->Detect(image, options);
  ASSERT_GT(features.size(), 30u);
  for (const Feature& f : features) {
    // Inside the image: pixel centres at integer coordinates, so [-0.5, size - 0.5].
    EXPECT_GE(f.x, -0.5f);
    EXPECT_GE(f.y, -0.5f);
    EXPECT_LE(f.x, image.cols - 0.5f);
    EXPECT_LE(f.y, image.rows - 0.5f);
    EXPECT_FLOAT_EQ(f.scale, static_cast<float>(options.scale));
    EXPECT_GT(f.response, 0);
    EXPECT_GE(f.cornerness, options.min_cornerness - 1e-6);
    EXPECT_LE(f.cornerness, 0.25f);
    EXPECT_GE(f.level, 0);
    EXPECT_LT(f.level, 255);
    EXPECT_NE(f.polarity, Polarity::kNone);
    EXPECT_TRUE(f.HasSideMask());
    EXPECT_EQ(f.curve.size(), static_cast<size_t>(2 * options.half_length + 1));
    double nearest = 1e300;
    for (const cv::Point2f& p : f.curve) nearest = std::min(nearest, cv::norm(p - f.Position()));
    // The MSICS passes by the corner: the vertex lies off it by at most the vertex refinement's
    // bound (0.25 k = 3 px), plus half a sample.
    EXPECT_LT(nearest, 0.25 * options.half_length + 0.6);
    // A patch inside the image holds both sides.
    if (PatchFits(f, image.size())) {
      EXPECT_GT(std::count(f.side_mask.begin(), f.side_mask.end(), PatchSide::kPlus), 20);
      EXPECT_GT(std::count(f.side_mask.begin(), f.side_mask.end(), PatchSide::kMinus), 20);
    }
  }
}

TYPED_TEST(ComicSearchContract, SortedStrongestFirstTiesByPosition) {
  const FeatureSet features = this->Detect(test::TexturedScene(7));
  ASSERT_GT(features.size(), 30u);
  for (size_t i = 1; i < features.size(); ++i) {
    const Feature& a = features[i - 1];
    const Feature& b = features[i];
    EXPECT_GE(a.response, b.response) << i;
    if (a.response == b.response) {
      EXPECT_TRUE(a.y < b.y || (a.y == b.y && a.x <= b.x)) << i;
    }
  }
  FeatureSet resorted = features;
  SortByResponse(&resorted);
  test::ExpectIdentical(features, resorted);
}

TYPED_TEST(ComicSearchContract, OutputIsIdenticalWithOneAndTwoThreads) {
  const cv::Mat image = test::TexturedScene(10);
  typename TestFixture::Options one, two;
  one.num_threads = 1;
  two.num_threads = 2;
  const FeatureSet a = this->Detect(image, one);
  ASSERT_GT(a.size(), 30u);
  test::ExpectIdentical(a, this->Detect(image, two));
  test::ExpectIdentical(a, this->Detect(image, one));
}

TYPED_TEST(ComicSearchContract, StabilityThresholdCutsTheResponse) {
  const cv::Mat image = test::TexturedScene(8);
  const FeatureSet all = this->Detect(image);
  ASSERT_GT(all.size(), 20u);
  typename TestFixture::Options options;
  options.min_stability = all[all.size() / 2].response;
  const FeatureSet strong = this->Detect(image, options);
  FeatureSet expected;
  for (const Feature& f : all) {
    if (f.response >= options.min_stability) expected.push_back(f);
  }
  test::ExpectIdentical(strong, expected);
}

TYPED_TEST(ComicSearchContract, MaxFeaturesKeepsTheFirstOfTheOutput) {
  // The tracker's cap (TrackerOptions::max_features) keeps the strongest; on a detector's output,
  // sorted strongest first, that is the first features that fit a patch.
  const cv::Mat image = test::TexturedScene(8);
  const FeatureSet features = this->Detect(image);
  TrackerOptions uncapped;
  const FeatureSet trackable = SelectTrackableFeatures(features, image.size(), uncapped);
  ASSERT_GT(trackable.size(), 20u);
  for (int max_features : {1, 10, static_cast<int>(trackable.size()) - 1}) {
    TrackerOptions capped;
    capped.max_features = max_features;
    const FeatureSet kept = SelectTrackableFeatures(features, image.size(), capped);
    ASSERT_EQ(kept.size(), static_cast<size_t>(max_features));
    test::ExpectIdentical(kept, FeatureSet(trackable.begin(), trackable.begin() + max_features));
  }
}

}  // namespace
}  // namespace comic::frontend
