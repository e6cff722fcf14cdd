#include "frontend/combined_detector.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "frontend/detector_factory.h"
#include "io/core/error.h"

namespace comic::frontend {
namespace {

cv::Mat Texture() {
  cv::Mat noise(120, 160, CV_32F);
  cv::RNG rng(9);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Mat image;
  cv::normalize(noise, image, 10, 245, cv::NORM_MINMAX);
  image.convertTo(image, CV_8U);
  return image;
}

TEST(CombinedDetector, SplitsNames) {
  EXPECT_EQ(SplitCombinedDetectorName("comic+hessian"),
            (std::vector<std::string>{"comic", "hessian"}));
  EXPECT_EQ(SplitCombinedDetectorName("harris"), (std::vector<std::string>{"harris"}));
  EXPECT_EQ(SplitCombinedDetectorName("a++b"), (std::vector<std::string>{"a", "", "b"}));
}

TEST(CombinedDetector, DetectsWithEachComponentInOrder) {
  const cv::Mat image = Texture();
  const auto combined = MakeDetector("harris+fast");
  EXPECT_EQ(combined->Name(), "harris+fast");
  const FeatureSet all = combined->Detect(image);
  const FeatureSet harris = MakeDetector("harris")->Detect(image);
  const FeatureSet fast = MakeDetector("fast")->Detect(image);
  ASSERT_FALSE(harris.empty());
  ASSERT_FALSE(fast.empty());
  ASSERT_EQ(all.size(), harris.size() + fast.size());
  for (size_t i = 0; i < harris.size(); ++i) EXPECT_EQ(all[i].response, harris[i].response);
  for (size_t i = 0; i < fast.size(); ++i) {
    EXPECT_EQ(all[harris.size() + i].response, fast[i].response);
  }
}

TEST(CombinedDetector, FactoryAcceptsPlusListsAndRejectsBadOnes) {
  EXPECT_TRUE(IsDetectorName("comic+hessian"));
  EXPECT_TRUE(IsDetectorName("harris+hessian+fast"));
  EXPECT_FALSE(IsDetectorName("comic+bogus"));
  EXPECT_FALSE(IsDetectorName("comic+comic"));
  EXPECT_FALSE(IsDetectorName("comic+"));
  EXPECT_FALSE(IsDetectorName("+"));
  try {
    MakeDetector("comic+bogus");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'bogus' in 'comic+bogus'"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(ParseDetectorList("harris,comic+hessian"),
            (std::vector<std::string>{"harris", "comic+hessian"}));
  EXPECT_THROW(ParseDetectorList("harris,hessian+mser+bogus"), Error);
  // A component's options are checked as that detector's.
  DetectorOptions options;
  options.name = "harris+hessian";
  options.harris.integration_sigma = -1.0;
  EXPECT_THROW(options.Check(), Error);
  std::vector<std::unique_ptr<Detector>> one;
  one.push_back(MakeDetector("harris"));
  EXPECT_THROW(CombinedDetector(std::move(one)), Error);
}

}  // namespace
}  // namespace comic::frontend
