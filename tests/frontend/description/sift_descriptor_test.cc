#include "frontend/description/sift_descriptor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/colmap/colmap_database.h"
#include "io/core/error.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

cv::Mat Texture(int width, int height, int seed = 5) {
  cv::Mat noise(height, width, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.5);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat gray;
  noise.convertTo(gray, CV_8U);
  return gray;
}

// Angle between two stored descriptors (radians), as the matcher measures it.
double DescriptorAngle(const cv::Mat& a, const cv::Mat& b) {
  double dot = 0.0;
  for (int c = 0; c < kDescriptorSize; ++c) dot += a.at<uint8_t>(c) * b.at<uint8_t>(c);
  return std::acos(std::min(1.0, dot / (512.0 * 512.0)));
}

double Length(const cv::Mat& row) { return cv::norm(row, cv::NORM_L2); }

FeatureSet RandomFeatures(int count, int width, int height, float scale, int seed) {
  cv::RNG rng(seed);
  FeatureSet features;
  for (int k = 0; k < count; ++k) {
    Feature f;
    f.x = static_cast<float>(rng.uniform(40, width - 40));
    f.y = static_cast<float>(rng.uniform(40, height - 40));
    f.scale = scale;
    features.push_back(f);
  }
  return features;
}

TEST(SiftDescriptor, OneRowOf128BytesOfLength512PerFeature) {
  const cv::Mat gray = Texture(200, 160);
  const FeatureSet features = RandomFeatures(30, 200, 160, 2.0f, 1);
  const cv::Mat descriptors = DescribeFeatures(gray, features);
  ASSERT_EQ(descriptors.rows, 30);
  EXPECT_EQ(descriptors.cols, kDescriptorSize);
  EXPECT_EQ(descriptors.type(), CV_8UC1);
  for (int r = 0; r < descriptors.rows; ++r) {
    // RootSIFT has unit L2 length before the x512 scaling (rounding and the 255 cap aside).
    EXPECT_NEAR(Length(descriptors.row(r)), 512.0, 6.0) << r;
  }
  EXPECT_EQ(DescribeFeatures(gray, {}).rows, 0);
  EXPECT_EQ(DescribeFeatures(gray, {}).cols, kDescriptorSize);
  // A uniform region has no gradient: a zero row, which matches nothing.
  const cv::Mat flat = DescribeFeatures(cv::Mat(100, 100, CV_8UC1, cv::Scalar(7)), features);
  EXPECT_EQ(cv::countNonZero(flat.reshape(1, 1)), 0);
  EXPECT_THROW(DescribeFeatures(cv::Mat(10, 10, CV_8UC3), features), Error);
}

TEST(SiftDescriptor, SameDescriptorInAViewTurnedInItsPlane) {
  const cv::Mat gray = Texture(200, 160);
  cv::Mat turned;
  cv::rotate(gray, turned, cv::ROTATE_90_COUNTERCLOCKWISE);  // (x, y) -> (y, w - 1 - x)
  const FeatureSet features = RandomFeatures(40, 200, 160, 2.0f, 2);
  FeatureSet turned_features = features;
  for (Feature& f : turned_features) {
    const float x = f.x;
    f.x = f.y;
    f.y = static_cast<float>(gray.cols - 1) - x;
  }
  for (OrientationMode mode : {OrientationMode::kGradient, OrientationMode::kUpright}) {
    DescriptorOptions options;
    options.orientation.mode = mode;
    const cv::Mat a = DescribeFeatures(gray, features, options);
    const cv::Mat b = DescribeFeatures(turned, turned_features, options);
    int near = 0;
    for (int k = 0; k < a.rows; ++k) near += DescriptorAngle(a.row(k), b.row(k)) < 0.15;
    if (mode == OrientationMode::kGradient) {
      // Oriented: the same point gives the same descriptor (OpenCV samples the turned window
      // with interpolation, hence "nearly").
      EXPECT_GE(near, 38) << "of 40";
    } else {
      // Upright: the turned window is a different descriptor.
      EXPECT_LE(near, 4) << "of 40";
    }
  }
}

TEST(SiftDescriptor, ScaleFollowsTheFeatureScale) {
  // The same texture at half size, its features at half the scale: the same descriptors.
  const cv::Mat gray = Texture(320, 320, 7);
  cv::Mat half;
  cv::resize(gray, half, cv::Size(160, 160), 0, 0, cv::INTER_AREA);
  const FeatureSet features = RandomFeatures(30, 320, 320, 8.0f, 3);
  FeatureSet half_features = features;
  for (Feature& f : half_features) {
    f.x = (f.x + 0.5f) / 2 - 0.5f;
    f.y = (f.y + 0.5f) / 2 - 0.5f;
    f.scale /= 2;
  }
  DescriptorOptions options;
  options.sigma_per_scale = 1.0;  // sigma 8 (octave 2) and 4 (octave 1): the same level structure
  const cv::Mat a = DescribeFeatures(gray, features, options);
  const cv::Mat b = DescribeFeatures(half, half_features, options);
  int near = 0, near_other = 0;
  for (int k = 0; k < a.rows; ++k) {
    near += DescriptorAngle(a.row(k), b.row(k)) < 0.25;
    near_other += DescriptorAngle(a.row(k), b.row((k + 1) % b.rows)) < 0.25;
  }
  EXPECT_GE(near, 27) << "of 30";
  EXPECT_LE(near_other, 2);
}

TEST(SiftDescriptor, SameResultWhateverOpenCvsThreadCount) {
  const cv::Mat gray = Texture(300, 240);
  const FeatureSet features = RandomFeatures(200, 300, 240, 2.0f, 4);
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const cv::Mat one = DescribeFeatures(gray, features);
  cv::setNumThreads(4);
  const cv::Mat four = DescribeFeatures(gray, features);
  cv::setNumThreads(threads);
  EXPECT_EQ(cv::norm(one, four, cv::NORM_INF), 0.0);
}

TEST(SiftDescriptor, NormalizesAsColmapStoresSift) {
  cv::Mat raw(1, kDescriptorSize, CV_32F, cv::Scalar(0));
  raw.at<float>(0) = 3.0f;
  raw.at<float>(5) = 1.0f;
  // RootSIFT: sqrt(3/4) * 512 = 443.4 -> 255 (cap); sqrt(1/4) * 512 = 256 -> 255.
  cv::Mat root = NormalizeSiftDescriptors(raw, DescriptorNormalization::kL1Root);
  EXPECT_EQ(root.at<uint8_t>(0), 255);
  EXPECT_EQ(root.at<uint8_t>(5), 255);
  raw.at<float>(0) = 9.0f;
  raw.at<float>(5) = 1.0f;
  raw.at<float>(7) = 90.0f;  // L1 = 100: sqrt(.09) = .3 -> 153.6 -> 154; .1 -> 51.2 -> 51
  root = NormalizeSiftDescriptors(raw, DescriptorNormalization::kL1Root);
  EXPECT_EQ(root.at<uint8_t>(0), 154);
  EXPECT_EQ(root.at<uint8_t>(5), 51);
  EXPECT_EQ(root.at<uint8_t>(7), 255);  // sqrt(.9) * 512 = 485.7, capped
  // L2: (1, 2, 2) / 3 * 512 = 170.7, 341.3 -> 171, 255 (cap).
  cv::Mat l2_raw(1, kDescriptorSize, CV_32F, cv::Scalar(0));
  l2_raw.at<float>(1) = 1.0f;
  l2_raw.at<float>(2) = 2.0f;
  l2_raw.at<float>(3) = 2.0f;
  const cv::Mat l2 = NormalizeSiftDescriptors(l2_raw, DescriptorNormalization::kL2);
  EXPECT_EQ(l2.at<uint8_t>(1), 171);
  EXPECT_EQ(l2.at<uint8_t>(2), 255);
  EXPECT_EQ(cv::countNonZero(l2), 3);
}

// The real `colmap feature_extractor` on a bundled KITTI frame: at COLMAP's own key points (its
// position - 0.5, σ and orientation from the 6-column keypoints) our descriptors are the ones
// COLMAP stored — same layout (Lowe's 4x4x8, as COLMAP turns VLFeat's into), same RootSIFT
// normalisation, same orientation convention — up to interpolation (key points of σ >= 2).
TEST(SiftDescriptor, EqualsColmapsOwnSiftAtColmapsKeyPoints) {
  if (test::RunCommand("command -v colmap").exit_code != 0) GTEST_SKIP() << "no colmap";
  test::ScopedTempDir dir;
  std::filesystem::create_directories(dir.File("images"));
  const cv::Mat gray = cv::imread(test::ExampleDir() + "/image_l/000000.png",
                                  cv::IMREAD_GRAYSCALE)(cv::Rect(300, 0, 500, 370));
  ASSERT_TRUE(cv::imwrite(dir.File("images/a.png"), gray));
  const test::CommandResult run =
      test::RunCommand("QT_QPA_PLATFORM=offscreen colmap feature_extractor --database_path " +
                       dir.File("db.db") + " --image_path " + dir.File("images") +
                       " --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads 1");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const io::ColmapDatabase database = io::ColmapDatabase::Open(dir.File("db.db"));
  const io::ColmapKeypoints keypoints = database.ReadKeypoints(1);
  const io::ColmapDescriptors colmap = database.ReadDescriptors(1);
  ASSERT_EQ(keypoints.cols(), 6);
  ASSERT_GT(keypoints.rows(), 200);
  std::vector<OrientedPoint> points;
  std::vector<int> rows;
  for (int i = 0; i < keypoints.rows(); i += 3) {
    const double a11 = keypoints(i, 2), a12 = keypoints(i, 3), a21 = keypoints(i, 4),
                 a22 = keypoints(i, 5);
    OrientedPoint point;
    point.x = static_cast<float>(io::FromColmapPixel(keypoints(i, 0)));
    point.y = static_cast<float>(io::FromColmapPixel(keypoints(i, 1)));
    point.sigma = static_cast<float>(std::sqrt(std::abs(a11 * a22 - a12 * a21)));
    // COLMAP describes σ < 2 on the image doubled in size (first_octave -1); ours start at the
    // image itself, which interpolates those finest windows differently.
    if (point.sigma < 2.0f) continue;
    point.angle_deg =
        static_cast<float>(std::fmod(std::atan2(a21, a11) * 180.0 / M_PI + 360.0, 360.0));
    points.push_back(point);
    rows.push_back(i);
  }
  const cv::Mat ours = DescribeOrientedPoints(gray, points, DescriptorNormalization::kL1Root);
  double sum_cosine = 0.0;
  int near = 0;
  for (size_t k = 0; k < rows.size(); ++k) {
    double dot = 0.0, a = 0.0, b = 0.0;
    for (int c = 0; c < kDescriptorSize; ++c) {
      const double x = ours.at<uint8_t>(static_cast<int>(k), c), y = colmap(rows[k], c);
      dot += x * y;
      a += x * x;
      b += y * y;
    }
    const double cosine = dot / std::sqrt(a * b);
    sum_cosine += cosine;
    near += cosine > 0.95;
  }
  EXPECT_GT(sum_cosine / rows.size(), 0.98);
  EXPECT_GT(near, 0.9 * rows.size());
}

TEST(SiftDescriptor, OptionsPerDetector) {
  EXPECT_EQ(DescriptorOptionsFor("harris").sigma_per_scale, 1.5);
  EXPECT_EQ(DescriptorOptionsFor("hessian").sigma_per_scale, 1.5);
  EXPECT_EQ(DescriptorOptionsFor("fast").sigma_per_scale, 1.0);
  EXPECT_EQ(DescriptorOptionsFor("mser").sigma_per_scale, 1.0);
  EXPECT_EQ(DescriptorOptionsFor("comic").curve_sigma_per_scale, 0.5);
  EXPECT_EQ(DescriptorOptionsFor("comic+fast").sigma_per_scale, 1.0);
  Feature comic;
  comic.scale = 8.4f;
  comic.curve = {{1, 1}, {2, 2}};
  Feature harris;
  harris.scale = 2.0f;
  const DescriptorOptions options = DescriptorOptionsFor("comic+harris");
  EXPECT_NEAR(DescriptorSigma(comic, options), 4.2, 1e-6);
  EXPECT_NEAR(DescriptorSigma(harris, options), 3.0, 1e-6);
  harris.scale = 0.0f;  // no scale: the smallest sigma
  EXPECT_EQ(DescriptorSigma(harris, options), options.min_sigma);
  DescriptorOptions bad;
  bad.max_sigma = 1.0;
  EXPECT_THROW(bad.Check(), Error);
  bad = {};
  bad.sigma_per_scale = -1;
  EXPECT_THROW(bad.Check(), Error);
  EXPECT_EQ(ParseDescriptorNormalization("l2"), DescriptorNormalization::kL2);
  EXPECT_THROW(ParseDescriptorNormalization("l3"), Error);
}

}  // namespace
}  // namespace comic::frontend
