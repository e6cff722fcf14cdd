#include "frontend/matching/usac_params.h"

#include "io/core/error.h"

namespace comic::frontend {

cv::UsacParams DeterministicUsacParams(double threshold, double confidence, int max_iterations,
                                       uint32_t random_seed) {
  COMIC_CHECK(threshold > 0, kInvalidArgument, "USAC threshold must be > 0, got " << threshold);
  COMIC_CHECK(confidence > 0 && confidence < 1, kInvalidArgument,
              "USAC confidence must be in (0, 1), got " << confidence);
  COMIC_CHECK(max_iterations > 0, kInvalidArgument,
              "USAC max_iterations must be > 0, got " << max_iterations);
  COMIC_CHECK(random_seed <= 0x7fffffffu, kInvalidArgument, "USAC random_seed must be < 2^31");
  cv::UsacParams params;
  params.confidence = confidence;
  params.isParallel = false;  // OpenCV's parallel USAC is not deterministic
  params.loIterations = 10;
  params.loMethod = cv::LOCAL_OPTIM_INNER_LO;
  params.loSampleSize = 14;
  params.maxIterations = max_iterations;
  params.neighborsSearch = cv::NEIGH_GRID;
  params.randomGeneratorState = static_cast<int>(random_seed);
  params.sampler = cv::SAMPLING_UNIFORM;
  params.score = cv::SCORE_METHOD_MSAC;
  params.threshold = threshold;
  return params;
}

}  // namespace comic::frontend
