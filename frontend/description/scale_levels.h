// The blur levels at which features of any scale are described: SIFT's scale space (Lowe 2004
// §3), octaves of halved images with three levels each, σ = 1.6 · 2^(octave + layer / 3) in
// pixels of the input image. A feature is described on the level nearest its descriptor σ, so a
// descriptor window of 12σ always spans the same number of (octave) pixels, and the work per
// feature does not grow with its scale. OpenCV's cv::SIFT builds the same levels (it is told a
// feature's level through cv::KeyPoint::octave, PackOpenCvOctave), and the orientation
// (feature_orientation.h) is measured on them too.
//
//   const ScaleLevel level = NearestScaleLevel(sigma);
//   ScaleLevelImages images(gray);
//   const cv::Mat& blurred = images.Get(level);  // CV_32F, the octave's size, blurred to level
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <utility>

namespace comic::frontend {

// SIFT's base blur and levels per octave (OpenCV's and COLMAP's defaults).
inline constexpr double kSiftBaseSigma = 1.6;
inline constexpr int kSiftLevelsPerOctave = 3;

struct ScaleLevel {
  int octave = 0;  // the image is halved `octave` times (>= 0)
  int layer = 0;   // 0 .. kSiftLevelsPerOctave − 1
  // σ of the level in pixels of the input image, and in pixels of the octave's image.
  double Sigma() const;
  double OctaveSigma() const;
  // Input-image coordinates -> the octave's (pixel centres at integers in both).
  double ToOctave(double coordinate) const;
};

// The level nearest `sigma` (in log scale); sigma below kSiftBaseSigma gives octave 0, layer 0.
ScaleLevel NearestScaleLevel(double sigma);

// cv::KeyPoint::octave for a feature described at `level` by cv::SIFT::compute (OpenCV packs the
// octave into the low byte, the layer into the next).
int PackOpenCvOctave(const ScaleLevel& level);

// The blurred images of one grey image at the levels asked for, each made once on demand.
class ScaleLevelImages {
 public:
  // `gray`: CV_8UC1 (kept by reference counting, not copied).
  explicit ScaleLevelImages(const cv::Mat& gray);

  // CV_32F image of the octave's size (the input halved `octave` times, area averaging) blurred
  // to the level's σ.
  const cv::Mat& Get(const ScaleLevel& level);

 private:
  cv::Mat gray_;
  std::map<int, cv::Mat> octaves_;                  // octave -> its unblurred image
  std::map<std::pair<int, int>, cv::Mat> blurred_;  // (octave, layer) -> blurred image
};

}  // namespace comic::frontend
