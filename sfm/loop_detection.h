// Revisited places by appearance: a bag of visual words over the keyframes' descriptors
// (Sivic & Zisserman 2003; DBoW2 as ORB-SLAM uses it), tf-idf weighted and compared by cosine
// similarity. The vocabulary is trained on the sequence's own descriptors by a seeded k-means, so
// no trained file ships with the project and the result does not depend on the thread count.
// A candidate is only a hypothesis: the caller verifies it geometrically before closing the loop
// (sfm/pose_graph.h).
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

namespace comic::sfm {

struct LoopDetectionOptions {
  // Words of the vocabulary and Lloyd iterations of its k-means.
  int vocabulary_size = 256;
  int kmeans_iterations = 8;
  // Descriptors the vocabulary is trained on at most (evenly sampled over the keyframes).
  int max_training_descriptors = 20000;
  // A candidate lies at least this many frames before the query (closer frames are the odometry's).
  int min_frame_separation = 30;
  // Cosine similarity of the two tf-idf vectors a candidate needs...
  double min_similarity = 0.2;
  // ... and relative to the query's similarity with the keyframe before it (DBoW's normalised
  // score: a revisit looks at least about as much like the query as its own predecessor does).
  double min_ratio_to_previous = 0.8;
  // ORB-SLAM's consistency check: a candidate is reported once this many consecutive keyframes
  // have each passed the thresholds with matches within `consistency_window` keyframes of the
  // one before (a single look-alike does not close a loop).
  int min_consecutive = 2;
  int consistency_window = 2;
  // Places each keyframe may revisit: the most similar keyframes passing both thresholds, at
  // least consistency_window + 1 keyframes apart (not the neighbours of one place). On a route
  // of look-alike places the best one is often not the true revisit (docs/long_video.md); the
  // caller's geometric and odometry checks sort them out.
  int candidates_per_keyframe = 3;

  void Check() const;
};

struct LoopCandidate {
  int query = -1;  // keyframe index (into the descriptors given)
  int match = -1;  // the earlier keyframe it revisits
  double similarity = 0.0;
  double ratio_to_previous = 0.0;
  int consecutive = 0;  // consistent keyframes in a row up to this one (>= min_consecutive)
};

// A bag-of-words vocabulary: descriptors (rows of CV_8U, any width) to word indices.
class Vocabulary {
 public:
  // Trains on rows of `descriptors`, taken in order (deterministic). Throws comic::Error on no
  // descriptors or rows of another type.
  static Vocabulary Train(const std::vector<cv::Mat>& descriptors,
                          const LoopDetectionOptions& options);
  int Size() const { return centers_.rows; }
  // The nearest word of each row.
  std::vector<int> Words(const cv::Mat& descriptors) const;

 private:
  cv::Mat centers_;  // CV_32F, one word per row
};

// For each keyframe (in order), its best revisit candidates (up to candidates_per_keyframe, most
// similar first) among the keyframes at least min_frame_separation frames before it that pass
// both thresholds and the consistency check. `descriptors[k]` are the
// keyframe's descriptors (CV_8U rows), `frames[k]` its frame index (increasing). With
// `plausible`, only the earlier keyframes it accepts for a keyframe compete (the caller's prior,
// e.g. the odometry's bound on drift): a look-alike the prior rules out then cannot outrank the
// true revisit. It is asked only about pairs that pass both thresholds.
using RevisitPrior = std::function<bool(int query, int match)>;
std::vector<LoopCandidate> DetectLoopCandidates(const std::vector<cv::Mat>& descriptors,
                                                const std::vector<int>& frames,
                                                const LoopDetectionOptions& options,
                                                const RevisitPrior& plausible = nullptr);

}  // namespace comic::sfm
