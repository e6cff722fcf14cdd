#include "frontend/detector_factory.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::frontend {
namespace {

TEST(DetectorFactory, BuildsEveryNamedDetector) {
  EXPECT_EQ(DetectorNames(), (std::vector<std::string>{"comic", "comic-paper", "harris", "hessian",
                                                       "mser", "fast"}));
  cv::Mat image(64, 64, CV_8UC1, cv::Scalar(0));
  image(cv::Rect(20, 20, 24, 24)).setTo(255);
  for (const std::string& name : DetectorNames()) {
    const std::unique_ptr<Detector> detector = MakeDetector(name);
    ASSERT_NE(detector, nullptr);
    EXPECT_EQ(detector->Name(), name);
    EXPECT_NO_THROW(detector->Detect(image));
  }
}

TEST(DetectorFactory, PassesOptionsThrough) {
  DetectorOptions options;
  options.name = "fast";
  options.fast.min_threshold = 250;
  cv::Mat image(64, 64, CV_8UC1, cv::Scalar(100));
  image(cv::Rect(20, 20, 24, 24)).setTo(150);
  EXPECT_TRUE(MakeDetector(options)->Detect(image).empty());
  options.fast.min_threshold = 10;
  EXPECT_FALSE(MakeDetector(options)->Detect(image).empty());
  options.harris.k = -1;  // not the named detector: not checked
  options.comic.delta = 0;
  options.comic_paper.delta = 0;
  EXPECT_NO_THROW(MakeDetector(options));
  options.name = "harris";
  EXPECT_THROW(MakeDetector(options), Error);
  // "comic" is the direct search with options.comic, "comic-paper" Algorithm 1 with comic_paper.
  options.name = "comic";
  EXPECT_THROW(MakeDetector(options), Error);
  options.comic.delta = 5;
  EXPECT_EQ(MakeDetector(options)->Name(), "comic");
  options.name = "comic-paper";
  EXPECT_THROW(MakeDetector(options), Error);
  options.comic_paper.delta = 5;
  EXPECT_EQ(MakeDetector(options)->Name(), "comic-paper");
}

TEST(DetectorFactory, UnknownNamesListTheValidOnes) {
  try {
    MakeDetector("sift");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("unknown detector 'sift' (valid: comic, comic-paper, "
                                         "harris, hessian, mser, fast)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(ParseDetectorList("harris,comic"), (std::vector<std::string>{"harris", "comic"}));
  EXPECT_EQ(ParseDetectorList("comic-paper,comic"),
            (std::vector<std::string>{"comic-paper", "comic"}));
  EXPECT_THROW(ParseDetectorList("harris,sift"), Error);
  EXPECT_THROW(ParseDetectorList("harris,,fast"), Error);
  EXPECT_THROW(ParseDetectorList("fast,fast"), Error);
  EXPECT_THROW(ParseDetectorList(""), Error);
}

}  // namespace
}  // namespace comic::frontend
