#include "frontend/feature_masks.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "io/core/content_hash.h"
#include "io/core/error.h"

namespace comic::frontend {

void FeatureMaskOptions::Check() const {
  COMIC_CHECK(margin_px >= 0, kInvalidArgument,
              "feature masks: margin_px must be >= 0, got " << margin_px);
}

FeatureMasks::FeatureMasks(const std::vector<cv::Mat>& masks, const FeatureMaskOptions& options) {
  options.Check();
  if (!masks.empty()) size_ = masks.front().size();
  // A disc: the margin is a distance, the same in every direction.
  const cv::Mat disc = cv::getStructuringElement(
      cv::MORPH_ELLIPSE, cv::Size(2 * options.margin_px + 1, 2 * options.margin_px + 1));
  dropped_.reserve(masks.size());
  for (size_t frame = 0; frame < masks.size(); ++frame) {
    const cv::Mat& mask = masks[frame];
    COMIC_CHECK(mask.type() == CV_8UC1 && mask.size() == size_, kInvalidArgument,
                "feature masks: mask " << frame << " is not CV_8UC1 of the first's size "
                                       << size_.width << "x" << size_.height);
    cv::Mat dropped;
    cv::compare(mask, 0, dropped, options.drop_nonzero ? cv::CMP_NE : cv::CMP_EQ);
    if (options.margin_px > 0) {
      cv::dilate(dropped, dropped, disc, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, 0);
    }
    dropped_.push_back(std::move(dropped));
  }
}

bool FeatureMasks::Drops(int frame, double x, double y) const {
  const cv::Mat& dropped = DroppedRegion(frame);
  const long col = std::lround(x);
  const long row = std::lround(y);
  if (col < 0 || row < 0 || col >= dropped.cols || row >= dropped.rows) return false;
  return dropped.at<uint8_t>(static_cast<int>(row), static_cast<int>(col)) != 0;
}

FeatureSet FeatureMasks::Keep(int frame, FeatureSet detected) const {
  FeatureSet kept;
  kept.reserve(detected.size());
  for (Feature& feature : detected) {
    if (!Drops(frame, feature.x, feature.y)) kept.push_back(std::move(feature));
  }
  return kept;
}

uint64_t FeatureMasks::Hash() const {
  io::ContentHash hash;
  const int header[3] = {size_.width, size_.height, static_cast<int>(dropped_.size())};
  hash.Add(header, sizeof(header));
  for (const cv::Mat& dropped : dropped_) {
    for (int row = 0; row < dropped.rows; ++row) hash.Add(dropped.ptr(row), dropped.cols);
  }
  return hash.value();
}

DetectionFilter FeatureMasks::Filter(std::atomic<int64_t>* num_dropped) const {
  return [this, num_dropped](int frame, FeatureSet detected) {
    const size_t detected_count = detected.size();
    FeatureSet kept = Keep(frame, std::move(detected));
    if (num_dropped != nullptr) {
      *num_dropped += static_cast<int64_t>(detected_count - kept.size());
    }
    return kept;
  };
}

}  // namespace comic::frontend
