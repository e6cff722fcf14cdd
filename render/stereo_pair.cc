#include "render/stereo_pair.h"

#include <cmath>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "render/random.h"

namespace comic::render {
namespace {

// Middlebury 2003 stores disparity x 4 in 8 bits.
constexpr double kDisparityScale = 4.0;
// The right image's noise stream, apart from every frame's.
constexpr int kRightFrameOffset = 1 << 24;
enum StereoStream : uint64_t { kStereoSensor = 2 };

}  // namespace

void StereoPairOptions::Check() const {
  COMIC_CHECK(baseline > 0 && std::isfinite(baseline), kInvalidArgument,
              "stereo baseline must be > 0 m, got " << baseline);
  COMIC_CHECK(depth_tolerance > 0, kInvalidArgument,
              "stereo depth tolerance must be > 0, got " << depth_tolerance);
  boundary.Check();
}

void WriteStereoPair(const BuiltScene& built, const Rasterizer& rasterizer, uint64_t seed,
                     const SensorOptions& sensor, int frame, const StereoPairOptions& options,
                     const std::string& folder) {
  options.Check();
  const Lens& lens = rasterizer.lens();
  COMIC_CHECK(!lens.HasDistortion(), kInvalidArgument,
              "stereo pairs are rectified: the scene's camera must have no distortion");
  const Pose left = built.path.At(frame);
  Pose right = left;
  right.translation.x() -= options.baseline;  // centre moved by +baseline along the camera's x
  const Scene scene = built.scene.At(frame);
  const RenderedView left_view = rasterizer.Render(scene, left);
  const RenderedView right_view = rasterizer.Render(scene, right);
  const uint64_t sensor_seed = MixSeed(seed, kStereoSensor);
  const cv::Mat left_image = ExposeFrame(left_view.color, sensor, sensor_seed, frame);
  const cv::Mat right_image =
      ExposeFrame(right_view.color, sensor, sensor_seed, frame + kRightFrameOffset);
  const cv::Mat boundary =
      OcclusionBoundaryMask(scene, left, rasterizer, left_view, options.boundary);

  cv::Mat disparity = cv::Mat::zeros(left_view.depth.size(), CV_8UC1);
  cv::Mat nonocc = cv::Mat::zeros(left_view.depth.size(), CV_8UC1);
  cv::Mat disc = cv::Mat::zeros(left_view.depth.size(), CV_8UC1);
  for (int y = 0; y < lens.height; ++y) {
    for (int x = 0; x < lens.width; ++x) {
      const double z = left_view.depth.at<float>(y, x);
      if (!(z > 0)) continue;  // sky: disparity unknown
      const double d = lens.fx * options.baseline / z;
      const double stored = std::round(d * kDisparityScale);
      if (stored < 1 || stored > 255) continue;  // beyond what 8 bits hold
      disparity.at<uint8_t>(y, x) = static_cast<uint8_t>(stored);
      const int xr = static_cast<int>(std::lround(x - d));
      if (xr < 0 || xr >= lens.width) continue;
      const double zr = right_view.depth.at<float>(y, xr);
      if (!(zr > 0) || std::abs(zr - z) > options.depth_tolerance * z) continue;
      nonocc.at<uint8_t>(y, x) = 255;
      disc.at<uint8_t>(y, x) = boundary.at<uint8_t>(y, x) ? 255 : 128;
    }
  }
  io::EnsureWritableDirectory(folder);
  io::WriteImageAtomically(io::JoinPaths(folder, "im2.png"), left_image);
  io::WriteImageAtomically(io::JoinPaths(folder, "im6.png"), right_image);
  io::WriteImageAtomically(io::JoinPaths(folder, "groundtruth.png"), disparity);
  io::WriteImageAtomically(io::JoinPaths(folder, "nonocc.png"), nonocc);
  io::WriteImageAtomically(io::JoinPaths(folder, "disc.png"), disc);
}

}  // namespace comic::render
