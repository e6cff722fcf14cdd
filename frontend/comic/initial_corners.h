// CoMIC's initialisation stage (paper §3, Algorithm 1 lines 4-6): in every B x B block (stride
// B/2) the component tree of both polarities gives each iso-curve portion in the block and its
// unweighted stability at δ/2; on the maximally stable ones (MSICS) the corners are the local
// maxima of κ at scale 2s. These initial corners only seed the feature convergence stage
// (corner_convergence.h), which re-detects everything at scale s.
//
//   InitialCornerDetector detector;           // one per thread: buffers are reused
//   std::vector<InitialCorner> corners;
//   detector.DetectInBlock(image, block_rect, /*upper_sets=*/false, options, &corners);
#pragma once

#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "frontend/comic/component_tree.h"
#include "frontend/comic/curve_cornerness.h"
#include "frontend/comic/iso_curve.h"
#include "frontend/feature.h"

namespace comic::frontend {

struct InitialCornerOptions {
  // δ used for the stability of the block's components, grey levels (Algorithm 1: δ/2).
  double delta = 2.5;
  // Samples (1 px apart) on either side of a corner in its segment, k at scale 2s.
  int half_length = 24;
  // Standard deviation of the Gaussian of κ along the curve, samples (∝ 2s).
  double sigma = 12.0;
  // Corners need κ >= this.
  double min_cornerness = 0.03;
  // Components need ρ >= this (1/px).
  double min_stability = 0.0;

  void Check() const;
};

struct InitialCorner {
  // Corner (apex of the κ maximum) in the coordinates of the image given.
  cv::Point2f position;
  // Grey level I of the curve: its dark side is {v <= I}, the curve is at I + 0.5.
  int level = 0;
  Polarity polarity = Polarity::kNone;
  // Unweighted ρ of the component (block boundary length / band area at δ/2).
  float stability = 0.0f;
  float cornerness = 0.0f;
  // The curve around the corner, resampled at 1 px, dark side on the left: up to
  // 2 * half_length samples on either side of `corner_index`.
  std::vector<cv::Point2f> curve;
  int corner_index = 0;
};

// Origins of blocks of length `block` every `stride` pixels covering [0, size): the last block
// is flush with the end. Empty if size < block.
std::vector<int> BlockOrigins(int size, int block, int stride);

// The part of [0, size) owned by block `index` of `origins` (blocks of length `block`): the
// points nearer to its centre than to any other block's, [begin, end). Overlapping blocks find
// the same corner several times; each block reports only the corners it owns, where it sees at
// least a quarter block of context on every side (except at the image border).
std::pair<int, int> OwnedRange(const std::vector<int>& origins, int block, int index, int size);

class InitialCornerDetector {
 public:
  // Appends to `corners` the initial corners of the block `block` of `image` (CV_8UC1) for the
  // lower (dark components) or upper (bright components) level sets whose position lies in
  // `owned` (image coordinates; see OwnedRange). Deterministic: the order depends only on the
  // block's content.
  void DetectInBlock(const cv::Mat& image, const cv::Rect& block, const cv::Rect& owned,
                     bool upper_sets, const InitialCornerOptions& options,
                     std::vector<InitialCorner>* corners);

 private:
  struct CornerContext {
    const cv::Rect* owned;
    int grey_level;
    double stability;
    const InitialCornerOptions* options;
  };
  // Appends the corners of curve_ (just traced) that lie in the owned part.
  void AddCornersOfCurve(const CornerContext& context, std::vector<InitialCorner>* corners);

  ComponentTree tree_;
  IsoCurve curve_;
  std::vector<int> edge_stamp_;
  // Seed crossings per stable component: (index in the stable list, 2 * pixel + direction).
  std::vector<int> stable_index_;  // per tree node: its index in the stable list, or -1
  // Per tree node: the node itself if it is stable, else its nearest stable ancestor, or -1.
  std::vector<int> stable_up_;
  std::vector<std::pair<int, int>> seeds_;
  std::vector<int> seed_start_;
  std::vector<int> seed_fill_;
  std::vector<int> sorted_seeds_;
  std::vector<double> arc_lengths_;
  std::vector<cv::Point2f> samples_;
  std::vector<cv::Point2f> part_;
  std::vector<double> kappa_;
  std::vector<double> part_kappa_;
  CornernessWorkspace cornerness_;
};

}  // namespace comic::frontend
