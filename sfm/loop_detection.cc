#include "sfm/loop_detection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/core/error.h"

namespace comic::sfm {
namespace {

void CheckDescriptors(const std::vector<cv::Mat>& descriptors) {
  int width = -1;
  for (const cv::Mat& d : descriptors) {
    if (d.empty()) continue;
    COMIC_CHECK(d.type() == CV_8UC1, kInvalidArgument,
                "loop detection: descriptors must be CV_8U rows, got type " << d.type());
    COMIC_CHECK(width < 0 || d.cols == width, kInvalidArgument,
                "loop detection: descriptors of width " << d.cols << " and " << width);
    width = d.cols;
  }
}

// Every step-th row over all keyframes, in order, as CV_32F.
cv::Mat TrainingSample(const std::vector<cv::Mat>& descriptors, int max_rows) {
  int total = 0;
  for (const cv::Mat& d : descriptors) total += d.rows;
  COMIC_CHECK(total > 0, kInvalidArgument, "loop detection: no descriptors to train on");
  const int step = std::max(1, (total + max_rows - 1) / max_rows);
  cv::Mat sample;
  int index = 0;
  for (const cv::Mat& d : descriptors) {
    for (int r = 0; r < d.rows; ++r, ++index) {
      if (index % step != 0) continue;
      cv::Mat row;
      d.row(r).convertTo(row, CV_32F);
      sample.push_back(row);
    }
  }
  return sample;
}

// The nearest centre of each row (CV_32F both): argmin over c of |c|² − 2 x·c, one matrix
// product for all rows; ties keep the lower index.
std::vector<int> NearestCenters(const cv::Mat& rows, const cv::Mat& centers) {
  cv::Mat products;
  cv::gemm(rows, centers, -2.0, cv::noArray(), 0.0, products, cv::GEMM_2_T);
  cv::Mat center_norms;
  cv::reduce(centers.mul(centers), center_norms, 1, cv::REDUCE_SUM, CV_32F);
  std::vector<int> nearest(rows.rows, 0);
  for (int r = 0; r < rows.rows; ++r) {
    const float* row = products.ptr<float>(r);
    float best = std::numeric_limits<float>::max();
    for (int c = 0; c < centers.rows; ++c) {
      const float distance = row[c] + center_norms.at<float>(c);
      if (distance < best) {
        best = distance;
        nearest[r] = c;
      }
    }
  }
  return nearest;
}

// Lloyd's k-means from evenly spaced rows; an empty cluster keeps its centre.
cv::Mat KMeans(const cv::Mat& sample, int k, int iterations) {
  k = std::min(k, sample.rows);
  cv::Mat centers(k, sample.cols, CV_32F);
  for (int c = 0; c < k; ++c) sample.row(int(int64_t(c) * sample.rows / k)).copyTo(centers.row(c));
  for (int it = 0; it < iterations; ++it) {
    const std::vector<int> assignment = NearestCenters(sample, centers);
    cv::Mat sums = cv::Mat::zeros(k, sample.cols, CV_64F);
    std::vector<int> counts(k, 0);
    for (int r = 0; r < sample.rows; ++r) {
      cv::Mat row;
      sample.row(r).convertTo(row, CV_64F);
      sums.row(assignment[r]) += row;
      ++counts[assignment[r]];
    }
    for (int c = 0; c < k; ++c) {
      if (counts[c] > 0) cv::Mat(sums.row(c) / counts[c]).convertTo(centers.row(c), CV_32F);
    }
  }
  return centers;
}

// tf-idf bag-of-words vectors, L2-normalised, one per keyframe.
std::vector<std::vector<double>> BagsOfWords(const std::vector<std::vector<int>>& words,
                                             int vocabulary_size) {
  const int keyframes = static_cast<int>(words.size());
  std::vector<int> keyframes_with_word(vocabulary_size, 0);
  std::vector<std::vector<double>> bags(keyframes, std::vector<double>(vocabulary_size, 0.0));
  for (int k = 0; k < keyframes; ++k) {
    for (int w : words[k]) bags[k][w] += 1.0;
    for (int w = 0; w < vocabulary_size; ++w) keyframes_with_word[w] += bags[k][w] > 0 ? 1 : 0;
  }
  for (int k = 0; k < keyframes; ++k) {
    double norm = 0.0;
    for (int w = 0; w < vocabulary_size; ++w) {
      if (bags[k][w] == 0.0) continue;
      bags[k][w] *= std::log(double(keyframes) / keyframes_with_word[w]);
      norm += bags[k][w] * bags[k][w];
    }
    if (norm > 0) {
      for (double& v : bags[k]) v /= std::sqrt(norm);
    }
  }
  return bags;
}

// The most similar candidates (ties: the earlier keyframe), at most candidates_per_keyframe, none
// within consistency_window keyframes of a more similar one.
std::vector<LoopCandidate> DistinctBest(std::vector<LoopCandidate> passed,
                                        const LoopDetectionOptions& options) {
  std::stable_sort(
      passed.begin(), passed.end(),
      [](const LoopCandidate& a, const LoopCandidate& b) { return a.similarity > b.similarity; });
  std::vector<LoopCandidate> best;
  for (const LoopCandidate& candidate : passed) {
    if (static_cast<int>(best.size()) == options.candidates_per_keyframe) break;
    const bool near_a_better_one =
        std::any_of(best.begin(), best.end(), [&](const LoopCandidate& kept) {
          return std::abs(kept.match - candidate.match) <= options.consistency_window;
        });
    if (!near_a_better_one) best.push_back(candidate);
  }
  return best;
}

double Cosine(const std::vector<double>& a, const std::vector<double>& b) {
  double dot = 0.0;
  for (size_t w = 0; w < a.size(); ++w) dot += a[w] * b[w];
  return dot;
}

}  // namespace

void LoopDetectionOptions::Check() const {
  COMIC_CHECK(vocabulary_size >= 2 && kmeans_iterations >= 1 && max_training_descriptors >= 1,
              kInvalidArgument,
              "loop detection: vocabulary_size >= 2, kmeans_iterations >= 1 and "
              "max_training_descriptors >= 1 needed, got "
                  << vocabulary_size << ", " << kmeans_iterations << ", "
                  << max_training_descriptors);
  COMIC_CHECK(min_consecutive >= 1 && consistency_window >= 0, kInvalidArgument,
              "loop detection: min_consecutive >= 1 and consistency_window >= 0 needed, got "
                  << min_consecutive << ", " << consistency_window);
  COMIC_CHECK(
      candidates_per_keyframe >= 1, kInvalidArgument,
      "loop detection: candidates_per_keyframe must be >= 1, got " << candidates_per_keyframe);
  COMIC_CHECK(min_frame_separation >= 1, kInvalidArgument,
              "loop detection: min_frame_separation must be >= 1, got " << min_frame_separation);
  COMIC_CHECK(min_similarity >= 0 && min_similarity <= 1 && min_ratio_to_previous >= 0,
              kInvalidArgument,
              "loop detection: min_similarity in [0, 1] and min_ratio_to_previous >= 0 needed, got "
                  << min_similarity << ", " << min_ratio_to_previous);
}

Vocabulary Vocabulary::Train(const std::vector<cv::Mat>& descriptors,
                             const LoopDetectionOptions& options) {
  options.Check();
  CheckDescriptors(descriptors);
  Vocabulary vocabulary;
  vocabulary.centers_ = KMeans(TrainingSample(descriptors, options.max_training_descriptors),
                               options.vocabulary_size, options.kmeans_iterations);
  return vocabulary;
}

std::vector<int> Vocabulary::Words(const cv::Mat& descriptors) const {
  if (descriptors.empty()) return {};
  cv::Mat rows;
  descriptors.convertTo(rows, CV_32F);
  return NearestCenters(rows, centers_);
}

std::vector<LoopCandidate> DetectLoopCandidates(const std::vector<cv::Mat>& descriptors,
                                                const std::vector<int>& frames,
                                                const LoopDetectionOptions& options,
                                                const RevisitPrior& plausible) {
  options.Check();
  COMIC_CHECK(descriptors.size() == frames.size(), kInvalidArgument,
              "loop detection: " << descriptors.size() << " descriptor sets for " << frames.size()
                                 << " frames");
  for (size_t k = 1; k < frames.size(); ++k) {
    COMIC_CHECK(frames[k] > frames[k - 1], kInvalidArgument,
                "loop detection: keyframe frames must increase, got " << frames[k - 1] << ", "
                                                                      << frames[k]);
  }
  std::vector<LoopCandidate> candidates;
  if (descriptors.size() < 2) return candidates;
  const Vocabulary vocabulary = Vocabulary::Train(descriptors, options);
  std::vector<std::vector<int>> words;
  for (const cv::Mat& d : descriptors) words.push_back(vocabulary.Words(d));
  const std::vector<std::vector<double>> bags = BagsOfWords(words, vocabulary.Size());

  std::vector<LoopCandidate> previous_passed;  // the previous keyframe's, that passed
  for (size_t q = 1; q < bags.size(); ++q) {
    const double previous = Cosine(bags[q], bags[q - 1]);
    std::vector<LoopCandidate> passed;
    for (size_t c = 0; c < q; ++c) {
      if (frames[q] - frames[c] < options.min_frame_separation) break;
      LoopCandidate candidate;
      candidate.query = static_cast<int>(q);
      candidate.match = static_cast<int>(c);
      candidate.similarity = Cosine(bags[q], bags[c]);
      candidate.ratio_to_previous = previous > 0 ? candidate.similarity / previous : 1e9;
      if (candidate.similarity > 0 && candidate.similarity >= options.min_similarity &&
          candidate.ratio_to_previous >= options.min_ratio_to_previous &&
          (!plausible || plausible(candidate.query, candidate.match))) {
        passed.push_back(candidate);
      }
    }
    passed = DistinctBest(std::move(passed), options);
    for (LoopCandidate& candidate : passed) {
      candidate.consecutive = 1;
      for (const LoopCandidate& before : previous_passed) {
        if (std::abs(before.match - candidate.match) <= options.consistency_window) {
          candidate.consecutive = std::max(candidate.consecutive, before.consecutive + 1);
        }
      }
      if (candidate.consecutive >= options.min_consecutive) candidates.push_back(candidate);
    }
    previous_passed = std::move(passed);
  }
  return candidates;
}

}  // namespace comic::sfm
