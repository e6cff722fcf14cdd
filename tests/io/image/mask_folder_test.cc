#include "io/image/mask_folder.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

TEST(MaskFolder, ReadsBinaryMasksInNaturalOrder) {
  test::ScopedTempDir dir;
  for (int i : {0, 1, 10, 2}) {
    cv::Mat mask(8, 12, CV_8UC1, cv::Scalar(0));
    mask.at<uint8_t>(i % 8, 3) = static_cast<uint8_t>(i == 2 ? 1 : 255);  // any non-zero
    cv::imwrite(dir.File("m" + std::to_string(i) + ".png"), mask);
  }
  WriteFileAtomically(dir.File("notes.txt"), "not a mask");
  const MaskFolder masks = MaskFolder::Open(dir.path());
  ASSERT_EQ(masks.NumMasks(), 4u);
  EXPECT_EQ(masks.Names()[2], "m2.png");
  EXPECT_EQ(masks.Names()[3], "m10.png");
  const cv::Mat m2 = masks.Read(2, {12, 8});
  EXPECT_EQ(m2.type(), CV_8UC1);
  EXPECT_EQ(m2.at<uint8_t>(2, 3), 255);
  EXPECT_EQ(cv::countNonZero(m2), 1);
  EXPECT_NO_THROW(masks.CheckCount(4));
}

TEST(MaskFolder, WrongSizeCountOrFolderGiveErrors) {
  test::ScopedTempDir dir;
  cv::imwrite(dir.File("0.png"), cv::Mat(8, 12, CV_8UC1, cv::Scalar(255)));
  const MaskFolder masks = MaskFolder::Open(dir.path());
  try {
    masks.Read(0, {13, 8});
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("mask is 12x8 but the frames are 13x8"), std::string::npos)
        << e.what();
  }
  try {
    masks.CheckCount(5);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("1 masks for 5 frames"), std::string::npos) << e.what();
  }
  EXPECT_THROW(masks.Read(1, {}), Error);
  test::ScopedTempDir empty;
  EXPECT_THROW(MaskFolder::Open(empty.path()), Error);
  EXPECT_THROW(MaskFolder::Open(empty.File("missing")), Error);
}

TEST(MaskFolder, ReadsTheDavisMasks) {
  COMIC_REQUIRE_SHARED_DATA();
  const MaskFolder masks =
      MaskFolder::Open(test::SharedDataDir() + "/davis2016_car-shadow/Annotations/480p/car-shadow");
  EXPECT_NO_THROW(masks.CheckCount(40));
  const cv::Mat first = masks.Read(0, {854, 480});
  EXPECT_EQ(cv::countNonZero(first), 41790);  // SOURCE.md: 41,790 mask pixels in frame 0
}

}  // namespace
}  // namespace comic::io
