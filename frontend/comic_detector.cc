#include "frontend/comic_detector.h"

#include "io/error.h"

namespace comic::frontend {

void ComicDetectorOptions::Check() const {
  COMIC_CHECK(scale > 0, kInvalidArgument, "comic: scale must be > 0, got " << scale);
  COMIC_CHECK(block_size >= 8, kInvalidArgument,
              "comic: block_size must be >= 8, got " << block_size);
  COMIC_CHECK(delta >= 1, kInvalidArgument, "comic: delta must be >= 1, got " << delta);
  COMIC_CHECK(half_length >= 2, kInvalidArgument,
              "comic: half_length must be >= 2, got " << half_length);
  COMIC_CHECK(max_iterations >= 1, kInvalidArgument,
              "comic: max_iterations must be >= 1, got " << max_iterations);
  COMIC_CHECK(convergence_tolerance >= 0, kInvalidArgument,
              "comic: convergence_tolerance must be >= 0");
  COMIC_CHECK(merge_radius >= 0, kInvalidArgument, "comic: merge_radius must be >= 0");
  COMIC_CHECK(min_stability >= 0, kInvalidArgument, "comic: min_stability must be >= 0");
  COMIC_CHECK(num_threads >= 0, kInvalidArgument, "comic: num_threads must be >= 0");
}

ComicDetector::ComicDetector(const ComicDetectorOptions& options) : options_(options) {
  options_.Check();
}

// PLACEHOLDER until the detector lands (issue "The CoMIC detector, faithful to the paper, fast,
// with comic_detect"): validates the input and returns no features.
FeatureSet ComicDetector::Detect(const cv::Mat& gray) const {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "comic: expected a non-empty 8-bit single-channel image");
  return {};
}

}  // namespace comic::frontend
