// Trajectory plots: both trajectories drawn in their colours, equal scale, deterministic; the
// plane of a ring of cameras found from the centres.
#include "sfm/evaluation/trajectory_plot.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

int CountColor(const cv::Mat& image, const cv::Vec3b& color, int tolerance) {
  int count = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const cv::Vec3b& p = image.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - color[0]) <= tolerance && std::abs(p[1] - color[1]) <= tolerance &&
          std::abs(p[2] - color[2]) <= tolerance) {
        ++count;
      }
    }
  }
  return count;
}

TEST(TrajectoryPlot, DrawsBothTrajectoriesDeterministically) {
  std::vector<std::optional<Eigen::Vector3d>> estimated, truth;
  for (int i = 0; i < 20; ++i) {
    truth.push_back(Eigen::Vector3d(0.1 * i, 0, 1.2 * i));
    estimated.push_back(Eigen::Vector3d(0.1 * i + 0.3, 0, 1.2 * i));
  }
  estimated[5].reset();
  TrajectoryPlotOptions options;
  options.title = "test";
  const cv::Mat image = RenderTrajectoryPlot(estimated, truth, PlotPlaneFromAxes(0, 2), options);
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.cols, 900);
  EXPECT_EQ(image.rows, 900);
  EXPECT_GT(CountColor(image, {30, 30, 210}, 10), 100);     // estimate, red
  EXPECT_GT(CountColor(image, {150, 215, 150}, 10), 1000);  // truth, broad green
  const cv::Mat again = RenderTrajectoryPlot(estimated, truth, PlotPlaneFromAxes(0, 2), options);
  EXPECT_EQ(cv::norm(image, again, cv::NORM_INF), 0.0);
  // The path runs up the page: the top rows hold the last frames, drawn near the horizontal
  // middle (equal scale squeezes the 2 m of x into a narrow band).
  int left = image.cols, right = 0;
  for (int y = 70; y < image.rows; ++y) {  // below the title and legend
    for (int x = 0; x < image.cols; ++x) {
      if (image.at<cv::Vec3b>(y, x) == cv::Vec3b(150, 215, 150)) {
        left = std::min(left, x);
        right = std::max(right, x);
      }
    }
  }
  // 1.9 m of x at 790 px / 22.8 m = 66 px, plus the dots.
  EXPECT_LT(right - left, 90);
  EXPECT_GT(right - left, 60);
}

// Rows of the image holding near-black (text) pixels between columns x0 and x1.
std::vector<int> InkRows(const cv::Mat& image, int x0, int x1, int y0, int y1) {
  std::vector<int> rows;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const cv::Vec3b& p = image.at<cv::Vec3b>(y, x);
      if (p[0] < 60 && p[1] < 60 && p[2] < 60) {
        rows.push_back(y);
        break;
      }
    }
  }
  return rows;
}

TEST(TrajectoryPlot, WrapsTheTitleMarksUnregisteredFramesAndDrawsAGrid) {
  std::vector<std::optional<Eigen::Vector3d>> estimated, truth;
  for (int i = 0; i < 20; ++i) {
    truth.push_back(Eigen::Vector3d(0.1 * i, 0, 1.2 * i));
    estimated.push_back(Eigen::Vector3d(0.1 * i, 0, 1.2 * i));
  }
  TrajectoryPlotOptions options;
  options.title = "comic_sfm --detector comic " + std::string(120, 'x') + "/a/long/path/image_l";
  options.unit = "m";
  const cv::Mat all = RenderTrajectoryPlot(estimated, truth, PlotPlaneFromAxes(0, 2), options);
  // The title goes on over a second line instead of running off the right edge.
  EXPECT_FALSE(InkRows(all, 20, 880, 30, 46).empty());
  EXPECT_TRUE(InkRows(all, 885, 900, 0, 46).empty());
  const cv::Vec3b amber(0, 160, 240), grid(232, 232, 232);
  EXPECT_EQ(CountColor(all, amber, 10), 0);
  EXPECT_GT(CountColor(all, grid, 2), 1000);  // grid lines at the ticks
  // Frames 7-9 not registered: amber crosses where they truly were, and the legend counts them.
  for (int i = 7; i < 10; ++i) estimated[i].reset();
  const cv::Mat missing = RenderTrajectoryPlot(estimated, truth, PlotPlaneFromAxes(0, 2), options);
  EXPECT_GT(CountColor(missing, amber, 10), 3 * 20);
}

TEST(TrajectoryPlot, EmptyInputAndBadOptions) {
  const cv::Mat image = RenderTrajectoryPlot({}, {}, PlotPlaneFromAxes(0, 2), {});
  EXPECT_EQ(image.rows, 900);
  TrajectoryPlotOptions small;
  small.width = 10;
  EXPECT_THROW(RenderTrajectoryPlot({}, {}, PlotPlaneFromAxes(0, 2), small), Error);
  EXPECT_THROW(PlotPlaneFromAxes(1, 1), Error);
}

TEST(TrajectoryPlot, PlaneOfARingOfCameras) {
  // A ring in the plane through x and (0, 1, 1), like a tilted turntable.
  const Eigen::Vector3d u = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d v = Eigen::Vector3d(0, 1, 1).normalized();
  std::vector<Eigen::Vector3d> centers;
  for (int i = 0; i < 16; ++i) {
    const double a = 2 * M_PI * i / 16;
    centers.push_back(std::cos(a) * u + std::sin(a) * v + Eigen::Vector3d(3, 2, 1));
  }
  const PlotPlane plane = PlotPlaneFromCenters(centers);
  const Eigen::Vector3d normal = plane.right.cross(plane.up);
  EXPECT_NEAR(std::abs(normal.dot(u.cross(v))), 1.0, 1e-9);
  EXPECT_NEAR(plane.right.norm(), 1.0, 1e-12);
  EXPECT_NEAR(plane.right.dot(plane.up), 0.0, 1e-12);
}

}  // namespace
}  // namespace comic::sfm
