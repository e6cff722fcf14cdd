#include "frontend/description/scale_levels.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::frontend {

double ScaleLevel::Sigma() const {
  return kSiftBaseSigma * std::pow(2.0, octave + static_cast<double>(layer) / kSiftLevelsPerOctave);
}

double ScaleLevel::OctaveSigma() const {
  return kSiftBaseSigma * std::pow(2.0, static_cast<double>(layer) / kSiftLevelsPerOctave);
}

double ScaleLevel::ToOctave(double coordinate) const {
  // Area averaging by 2^octave: input pixel centres 0 .. 2^o − 1 fall into octave pixel 0.
  const double factor = std::ldexp(1.0, octave);
  return (coordinate + 0.5) / factor - 0.5;
}

ScaleLevel NearestScaleLevel(double sigma) {
  COMIC_CHECK(std::isfinite(sigma) && sigma > 0, kInvalidArgument,
              "scale level: sigma must be > 0, got " << sigma);
  const double steps =
      std::log2(std::max(sigma, kSiftBaseSigma) / kSiftBaseSigma) * kSiftLevelsPerOctave;
  const int level = static_cast<int>(std::lround(std::min(steps, 60.0)));
  return {level / kSiftLevelsPerOctave, level % kSiftLevelsPerOctave};
}

int PackOpenCvOctave(const ScaleLevel& level) {
  // OpenCV's unpackOctave reads octave = low byte (signed), layer = next byte.
  return (level.octave & 255) | (level.layer << 8);
}

ScaleLevelImages::ScaleLevelImages(const cv::Mat& gray) : gray_(gray) {
  COMIC_CHECK(gray.type() == CV_8UC1, kInvalidArgument,
              "scale levels: expected an 8-bit grey image (CV_8UC1)");
}

const cv::Mat& ScaleLevelImages::Get(const ScaleLevel& level) {
  const std::pair<int, int> key(level.octave, level.layer);
  const auto found = blurred_.find(key);
  if (found != blurred_.end()) return found->second;
  auto octave = octaves_.find(level.octave);
  if (octave == octaves_.end()) {
    cv::Mat image;
    gray_.convertTo(image, CV_32F);
    const double factor = std::ldexp(1.0, level.octave);
    if (level.octave > 0) {
      const cv::Size size(std::max(1, static_cast<int>(std::lround(gray_.cols / factor))),
                          std::max(1, static_cast<int>(std::lround(gray_.rows / factor))));
      cv::resize(image, image, size, 0, 0, cv::INTER_AREA);
    }
    octave = octaves_.emplace(level.octave, image).first;
  }
  // The octave image is taken to hold a blur of 0.5 pixel (a sampled image); blur it up to the
  // level's σ.
  const double sigma = level.OctaveSigma();
  cv::Mat blurred;
  cv::GaussianBlur(octave->second, blurred, cv::Size(), std::sqrt(sigma * sigma - 0.25), 0,
                   cv::BORDER_REFLECT_101);
  return blurred_.emplace(key, blurred).first->second;
}

}  // namespace comic::frontend
