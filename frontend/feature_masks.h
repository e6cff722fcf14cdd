// Per-frame masks that remove detected features before tracking or matching (issue 47: moving
// objects are not scene). A feature on a moving object, tracked or matched, is a track the mapper
// must either reject or, worse, triangulate; removed at detection, it never links anything.
//
// Convention: our masks are DAVIS-style object annotations, non-zero = the moving object = the
// features there are dropped (`drop_nonzero`, the default). COLMAP's ImageReader.mask_path is the
// opposite (0 = ignore): drop_nonzero = false reads such masks. Features within `margin_px` of
// the dropped region are dropped too: a corner on the silhouette belongs to the object's edge,
// and annotations are a pixel or two off.
//
//   FeatureMaskOptions options;                       // DAVIS: non-zero dropped, 2 px margin
//   FeatureMasks masks(object_masks, options);        // one CV_8UC1 mask per frame
//   FeatureSet kept = masks.Keep(frame, detector.Detect(gray));
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/feature.h"

namespace comic::frontend {

// Applied by the tracker and the image-set matcher to each frame's detection (every candidate,
// before the response cut and the max_features cap, so that the cap's budget goes to the features
// kept): returns the features to use, in their order. Empty: every feature is used. May be called
// from several threads at once, for different frames.
using DetectionFilter = std::function<FeatureSet(int frame, FeatureSet detected)>;

struct FeatureMaskOptions {
  // true: non-zero pixels are dropped (DAVIS annotations, our --masks); false: zero pixels are
  // dropped (COLMAP's mask_path).
  bool drop_nonzero = true;
  // Features within this distance of a dropped pixel are dropped too (pixels, a disc).
  int margin_px = 2;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

class FeatureMasks {
 public:
  // `masks`: one CV_8UC1 mask per frame, all of one size (the frames' as tracked). Throws
  // comic::Error(kInvalidArgument) for masks of another type or of different sizes.
  FeatureMasks(const std::vector<cv::Mat>& masks, const FeatureMaskOptions& options);

  size_t NumFrames() const { return dropped_.size(); }
  cv::Size MaskSize() const { return size_; }
  // CV_8UC1, 255 where features of `frame` are dropped (the margin included), 0 elsewhere.
  const cv::Mat& DroppedRegion(int frame) const { return dropped_.at(frame); }
  // A feature at (x, y) of `frame` (sub-pixel, rounded to its pixel) is dropped. Positions outside
  // the mask are kept.
  bool Drops(int frame, double x, double y) const;
  // The features of `detected` that `frame` keeps, in their order.
  FeatureSet Keep(int frame, FeatureSet detected) const;
  // FNV-1a 64 of every dropped region (their size and pixels): what decides the features kept,
  // for a cache key (sfm/run/track_cache.h).
  uint64_t Hash() const;
  // Keep as a DetectionFilter that adds the number of features it drops to `*num_dropped` (which
  // must outlive the filter, as must this object; null: not counted).
  DetectionFilter Filter(std::atomic<int64_t>* num_dropped) const;

 private:
  cv::Size size_;
  std::vector<cv::Mat> dropped_;
};

}  // namespace comic::frontend
