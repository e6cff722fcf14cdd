// Textures (render/texture.h): bilinear lookups exact on level 0, and every mip level centred
// where level 0 is — a texture must not shift on its surface as distance changes its level
// (a shift of (2^k - 1)/2 texels at level k would make tracked corners slide).
#include "render/texture.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::render {
namespace {

TEST(Texture, Level0IsBilinearOverTexelCentres) {
  cv::Mat image(4, 4, CV_8UC1, cv::Scalar(0));
  image.at<uint8_t>(1, 1) = 200;
  const Texture texture = Texture::FromImage(image, "dot");
  EXPECT_EQ(texture.width(), 4);
  EXPECT_EQ(texture.height(), 4);
  // Texel (1, 1) covers [1, 2) x [1, 2): its centre is (1.5, 1.5).
  EXPECT_FLOAT_EQ(texture.Sample(1.5, 1.5, 1.0)[0], 200.0f);
  EXPECT_FLOAT_EQ(texture.Sample(2.0, 1.5, 1.0)[1], 100.0f);
  EXPECT_FLOAT_EQ(texture.Sample(2.0, 2.0, 1.0)[2], 50.0f);
  EXPECT_FLOAT_EQ(texture.Sample(3.5, 3.5, 1.0)[0], 0.0f);
}

TEST(Texture, EveryLevelIsCentredWhereLevel0Is) {
  // A bright 4x4 block on black, centred at (41, 27) in level-0 texel coordinates.
  cv::Mat image(64, 96, CV_8UC3, cv::Scalar::all(0));
  image(cv::Rect(39, 25, 4, 4)).setTo(cv::Scalar::all(255));
  const Texture texture = Texture::FromImage(image, "block");
  for (double footprint : {1.0, 2.0, 4.0, 8.0, 5.0}) {
    double sum = 0.0, sx = 0.0, sy = 0.0;
    for (double y = 0.25; y < 64; y += 0.5) {
      for (double x = 0.25; x < 96; x += 0.5) {
        const double v = texture.Sample(x, y, footprint)[0];
        sum += v;
        sx += v * x;
        sy += v * y;
      }
    }
    // The coarse levels sample the blurred block sparsely (level 3: every 8 texels, blur sigma
    // ~4.6), which moves the centroid by a little aliasing, under 0.2 texel; centring the levels
    // as their sizes' ratio would instead shifts level 3 by 3.5 texels.
    const double tolerance = 0.03 + 0.02 * footprint;
    EXPECT_NEAR(sx / sum, 41.0, tolerance) << "footprint " << footprint;
    EXPECT_NEAR(sy / sum, 27.0, tolerance) << "footprint " << footprint;
  }
}

TEST(Texture, SolidColoursAndBadImages) {
  const Texture solid = Texture::Solid({10.0f, 20.0f, 30.0f}, "solid");
  const cv::Vec3f c = solid.Sample(0.3, 0.9, 100.0);
  EXPECT_FLOAT_EQ(c[0], 10.0f);
  EXPECT_FLOAT_EQ(c[2], 30.0f);
  EXPECT_THROW(Texture::FromImage(cv::Mat(), "empty"), Error);
  EXPECT_THROW(Texture::FromImage(cv::Mat(3, 3, CV_32FC3), "float"), Error);
}

}  // namespace
}  // namespace comic::render
