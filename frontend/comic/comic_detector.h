// CoMIC: Corners on Maximally-stable Iso-intensity Curves (Ravindran & Mittal; the paper in
// ../shared/paper/comic_paper.tex is the specification, ../shared/DESIGN.md the decisions on its
// open points).
//
//   comic::frontend::ComicDetectorOptions options;   // paper defaults: s = 8.4, B = 100, δ = 5
//   options.min_stability = 0.0;                     // ρ threshold, the main knob
//   comic::frontend::ComicDetector detector(options);
//   comic::frontend::FeatureSet features = detector.Detect(gray);  // strongest ρ first
#pragma once

#include <string>

#include "frontend/detector.h"

namespace comic::frontend {

struct ComicDetectorOptions {
  // Documented ranges, checked by Check() before any work (docs/robustness.md).
  static constexpr double kMaxScale = 64.0;
  static constexpr int kMaxBlockSize = 4096;
  static constexpr int kMaxDelta = 127;
  static constexpr int kMaxHalfLength = 500;
  static constexpr int kMaxIterations = 1000;

  // Final detection scale s in pixels (paper §3: s = 8.4). Initialisation runs at 2s. The
  // along-curve Gaussians (ρ weights, κ window) have σ = s/√2 samples, ≈ k/2 at the defaults, so
  // that the segment of ±k points spans ±2σ.
  double scale = 8.4;
  // Block size B in pixels (paper §3: B = 100). Initialisation blocks are B x B with stride B/2;
  // convergence blocks are B/2 x B/2 centred on the corner.
  int block_size = 100;
  // Intensity offset δ of the Up/Down iso-curves in grey levels (paper Fig. 3: δ = 5).
  // Initialisation uses δ/2 (Algorithm 1).
  int delta = 5;
  // Points on either side of the centre of an iso-curve segment, k (≈25 points per ICS, §3).
  int half_length = 12;
  // Feature-convergence iterations before a corner that keeps moving is dropped (Algorithm 1).
  int max_iterations = 5;
  // A corner has settled when its last move was at most this far, in pixels.
  double convergence_tolerance = 1.0;
  // Convergence iterations stop early once the corner moves at most this far, in pixels
  // (Algorithm 1 iterates "while d > 0"; sub-pixel positions need a small positive bound).
  double stop_tolerance = 0.05;
  // Features closer than this (pixels) are duplicates; the one with the higher ρ is kept.
  double merge_radius = 2.0;
  // Stability threshold on ρ = len / ΔA (Eq. 1): features below it are not returned. 0 returns
  // every candidate, so threshold equalisation can pick its own cut-off.
  double min_stability = 0.0;
  // Worker threads over blocks (0 = all hardware threads). Output is identical for any value.
  int num_threads = 1;
  // Cornerness threshold: a corner needs κ = det(Σ)/trace(Σ)² >= this (κ is 0 on a straight line,
  // ~0.2 at a right angle, 0.25 at most). The paper takes every local maximum of κ; without a floor
  // the noise wiggles of straight edges would be corners. 0.03 keeps turns of more than ~35°.
  double min_cornerness = 0.03;
  // Run the initialisation stage (scale 2s) on the image downsampled by 2 (2x2 means), with
  // blocks, segments and Gaussians halved in pixels: the same physical scale at a quarter of the
  // pixels. false runs it at full resolution as written in Algorithm 1.
  bool coarse_initialisation = true;
  // Also converge, once, from the other corners found on each converged MSICS: corners closer
  // together than the initialisation scale (2s) can share one initial corner, and Algorithm 1
  // would keep only the nearest.
  bool seed_neighbouring_corners = true;
  // Stop a seed's convergence when it reaches (within stop_tolerance and half a grey level) a
  // state another seed has been in, resuming it only if that seed is lost: from the same state
  // the iteration goes the same way, to a corner the final merge would fold into the other's.
  // Saves ~10 % of the time; false converges every seed to the end.
  bool skip_duplicate_paths = true;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// Where one detection spent its work, for benchmarks and diagnostics (the features do not depend
// on whether it is asked for). Times are wall-clock milliseconds.
struct ComicDetectionStats {
  double initialisation_ms = 0.0;  // block trees, MSICS, initial corners (Algorithm 1 lines 4-6)
  double convergence_ms = 0.0;     // both convergence rounds (lines 7-17), merge included
  double output_ms = 0.0;          // side masks and sorting
  int num_seeds = 0;               // initial corners converged (both rounds)
  int num_iterations = 0;          // convergence iterations over all seeds
  int num_settled = 0;             // seeds that settled, before duplicates are merged
};

class ComicDetector : public Detector {
 public:
  explicit ComicDetector(const ComicDetectorOptions& options = {});

  std::string Name() const override { return "comic-paper"; }
  FeatureSet Detect(const cv::Mat& gray) const override { return Detect(gray, nullptr); }
  // The same, filling `stats` when it is not null.
  FeatureSet Detect(const cv::Mat& gray, ComicDetectionStats* stats) const;

  const ComicDetectorOptions& options() const { return options_; }

 private:
  ComicDetectorOptions options_;
};

}  // namespace comic::frontend
