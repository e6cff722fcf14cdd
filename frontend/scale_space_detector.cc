#include "frontend/scale_space_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <unordered_map>
#include <utility>

#include "frontend/grid_cell_key.h"
#include "io/core/error.h"

namespace comic::frontend {

void ScaleSpaceDetectorOptions::Check() const {
  COMIC_CHECK(num_levels >= 1 && num_levels <= 16, kInvalidArgument,
              "scale space: num_levels must be in [1, 16], got " << num_levels);
  COMIC_CHECK(std::isfinite(level_factor) && level_factor > 1.0 && level_factor <= 4.0,
              kInvalidArgument,
              "scale space: level_factor must be in (1, 4], got " << level_factor);
  COMIC_CHECK(std::isfinite(duplicate_radius_px) && duplicate_radius_px >= 0.0, kInvalidArgument,
              "scale space: duplicate_radius_px must be >= 0, got " << duplicate_radius_px);
  COMIC_CHECK(min_level_size >= 8, kInvalidArgument,
              "scale space: min_level_size must be >= 8, got " << min_level_size);
}

std::vector<cv::Mat> BuildScaleLevels(const cv::Mat& gray,
                                      const ScaleSpaceDetectorOptions& options) {
  options.Check();
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "scale space: expected a non-empty 8-bit single-channel image");
  std::vector<cv::Mat> levels = {gray};
  const double shrink = 1.0 / options.level_factor;
  while (static_cast<int>(levels.size()) < options.num_levels) {
    const cv::Mat& previous = levels.back();
    // The size cv::resize gives for fx = fy = shrink and an empty dsize.
    const int width = cvRound(previous.cols * shrink);
    const int height = cvRound(previous.rows * shrink);
    if (std::min(width, height) < options.min_level_size) break;
    // Area averaging rather than cv::pyrDown: (1) a level pixel is then exactly the mean of the
    // level-0 pixels it covers, so positions map back by the pixel-area rule of ToLevelZero,
    // whereas pyrDown keeps every second pixel of a 5-tap blur (level pixel i centred on pixel
    // 2i, a different mapping); (2) any factor works, not just 2; (3) it is how the descriptor's
    // levels are made (frontend/description/scale_levels.h), so a coarse feature is described on
    // the pixels it was detected on. pyrDown's Gaussian suppresses aliasing better than the box,
    // but every base detector smooths in level pixels before it differentiates (Harris σ_D,
    // Hessian σ, CoMIC's pre-smoothing), which removes what the box lets through.
    // An empty dsize makes cv::resize use exactly `shrink` as the scale (not the rounded size's
    // ratio), so the mapping is exact for odd sizes too.
    cv::Mat next;
    cv::resize(previous, next, cv::Size(), shrink, shrink, cv::INTER_AREA);
    levels.push_back(std::move(next));
  }
  return levels;
}

Feature MapToLevelZero(Feature feature, double factor) {
  const cv::Point level_centre(static_cast<int>(std::lround(feature.x)),
                               static_cast<int>(std::lround(feature.y)));
  feature.x = static_cast<float>(ToLevelZero(feature.x, factor));
  feature.y = static_cast<float>(ToLevelZero(feature.y, factor));
  feature.scale = static_cast<float>(feature.scale * factor);
  for (cv::Point2f& point : feature.curve) {
    point = cv::Point2f(static_cast<float>(ToLevelZero(point.x, factor)),
                        static_cast<float>(ToLevelZero(point.y, factor)));
  }
  if (feature.HasSideMask()) {
    // The matcher reads the mask on the level-0 patch around the rounded level-0 position: each
    // of its pixels takes the label of the level pixel whose area holds the pixel's centre. The
    // level-0 patch spans 23 / factor level pixels, inside the level's 23x23 mask. Pixels within
    // half a level pixel of the curve stay kNone (mixed values), as at the level.
    const cv::Point centre(static_cast<int>(std::lround(feature.x)),
                           static_cast<int>(std::lround(feature.y)));
    std::vector<PatchSide> mask(kPatchSize * kPatchSize, PatchSide::kNone);
    for (int v = -kPatchRadius; v <= kPatchRadius; ++v) {
      const double level_y = (centre.y + v + 0.5) / factor - 0.5;
      const int dv = static_cast<int>(std::floor(level_y + 0.5)) - level_centre.y;
      if (dv < -kPatchRadius || dv > kPatchRadius) continue;
      for (int u = -kPatchRadius; u <= kPatchRadius; ++u) {
        const double level_x = (centre.x + u + 0.5) / factor - 0.5;
        const int du = static_cast<int>(std::floor(level_x + 0.5)) - level_centre.x;
        if (du < -kPatchRadius || du > kPatchRadius) continue;
        mask[(v + kPatchRadius) * kPatchSize + (u + kPatchRadius)] =
            feature.side_mask[(dv + kPatchRadius) * kPatchSize + (du + kPatchRadius)];
      }
    }
    feature.side_mask = std::move(mask);
  }
  return feature;
}

FeatureSet MergeScaleLevels(const std::vector<FeatureSet>& levels, double duplicate_radius_px) {
  COMIC_CHECK(std::isfinite(duplicate_radius_px) && duplicate_radius_px >= 0.0, kInvalidArgument,
              "scale space: duplicate_radius_px must be >= 0, got " << duplicate_radius_px);
  // (level, index) of every feature in SortByResponse's order, the finer level first on ties.
  std::vector<std::pair<int, size_t>> order;
  for (size_t l = 0; l < levels.size(); ++l) {
    for (size_t i = 0; i < levels[l].size(); ++i) order.emplace_back(static_cast<int>(l), i);
  }
  auto at = [&](const std::pair<int, size_t>& id) -> const Feature& {
    return levels[id.first][id.second];
  };
  std::sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
    const Feature& fa = at(a);
    const Feature& fb = at(b);
    if (fa.response != fb.response) return fa.response > fb.response;
    if (fa.y != fb.y) return fa.y < fb.y;
    if (fa.x != fb.x) return fa.x < fb.x;
    return a < b;
  });

  // Greedy, strongest first: the level where a corner responds most keeps it (scale selection,
  // Lindeberg 1998). Not "the finest level wins": Detect returns every candidate, and at level 0
  // of a blurred image weak candidates lie everywhere, which would suppress the coarse corners
  // the pyramid is there to find.
  const double r = duplicate_radius_px;
  const double r2 = r * r;
  std::unordered_map<uint64_t, std::vector<std::pair<cv::Point2f, int>>> kept_cells;
  auto cell = [&](double c) { return static_cast<int64_t>(std::floor(c / r)); };
  FeatureSet merged;
  merged.reserve(order.size());
  for (const auto& id : order) {
    const Feature& f = at(id);
    if (r > 0.0) {
      const int64_t cx = cell(f.x), cy = cell(f.y);
      bool duplicate = false;
      for (int64_t dy = -1; dy <= 1 && !duplicate; ++dy) {
        for (int64_t dx = -1; dx <= 1 && !duplicate; ++dx) {
          const auto found = kept_cells.find(GridCellKey(cx + dx, cy + dy));
          if (found == kept_cells.end()) continue;
          for (const auto& [point, level] : found->second) {
            if (level == id.first) continue;
            const double ex = point.x - f.x, ey = point.y - f.y;
            if (ex * ex + ey * ey < r2) {
              duplicate = true;
              break;
            }
          }
        }
      }
      if (duplicate) continue;
      kept_cells[GridCellKey(cx, cy)].emplace_back(f.Position(), id.first);
    }
    merged.push_back(f);
  }
  return merged;
}

ScaleSpaceDetector::ScaleSpaceDetector(std::unique_ptr<Detector> base,
                                       const ScaleSpaceDetectorOptions& options)
    : base_(std::move(base)), options_(options) {
  COMIC_CHECK(base_ != nullptr, kInvalidArgument, "scale space: null base detector");
  options_.Check();
}

std::vector<FeatureSet> ScaleSpaceDetector::DetectLevels(const cv::Mat& gray) const {
  // Level 0 first: the base detector's own check of the image (type, size) comes before ours.
  std::vector<FeatureSet> features = {base_->Detect(gray)};
  if (options_.num_levels == 1) return features;
  const std::vector<cv::Mat> levels = BuildScaleLevels(gray, options_);
  for (size_t l = 1; l < levels.size(); ++l) {
    const double factor = std::pow(options_.level_factor, static_cast<double>(l));
    FeatureSet level = base_->Detect(levels[l]);
    for (Feature& f : level) f = MapToLevelZero(std::move(f), factor);
    features.push_back(std::move(level));
  }
  return features;
}

FeatureSet ScaleSpaceDetector::Detect(const cv::Mat& gray) const {
  if (options_.num_levels == 1) return base_->Detect(gray);
  return MergeScaleLevels(DetectLevels(gray), options_.duplicate_radius_px);
}

}  // namespace comic::frontend
