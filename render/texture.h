// A photograph (or a solid colour) as a texture: an 8-bit BGR mip-map pyramid sampled
// trilinearly, so that a surface seen from afar is filtered rather than aliased. Coordinates are
// continuous texel coordinates of level 0: texel (i, j) covers [i, i + 1) x [j, j + 1).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace comic::render {

class Texture {
 public:
  // `image`: 8-bit grey, BGR or BGRA (alpha ignored). Throws comic::Error(kInvalidArgument) for
  // an empty image or another type.
  static Texture FromImage(const cv::Mat& image, const std::string& name);
  // A 1x1 texture of one BGR colour (0..255).
  static Texture Solid(const cv::Vec3f& bgr, const std::string& name);

  int width() const { return sizes_.front().width; }
  int height() const { return sizes_.front().height; }
  const std::string& name() const { return name_; }
  int NumLevels() const { return static_cast<int>(levels_.size()); }

  // The colour at (x, y) (level-0 texel coordinates, clamped to the image) filtered for a
  // footprint of `footprint` level-0 texels (the size of the area one sample covers; <= 1 reads
  // level 0 bilinearly).
  cv::Vec3f Sample(double x, double y, double footprint) const;
  // Bilinear at one level (coordinates of level 0).
  cv::Vec3f SampleLevel(int level, double x, double y) const;

 private:
  std::string name_;
  // Level k is level k-1 halved (cv::pyrDown), stored as CV_8UC4 (BGR and a zero) with the last
  // column repeated once more, so that two neighbouring texels are always one 8-byte load.
  std::vector<cv::Mat> levels_;
  std::vector<cv::Size> sizes_;          // each level's size without the repeated column
  std::vector<cv::Vec2f> level_scales_;  // level k's texels per level-0 texel: 2^-k (x, y)
};

}  // namespace comic::render
