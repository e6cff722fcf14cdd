// CoMIC by direct search of the paper's definition (§2, "Corner Definition"): p is a corner at
// scale s if ICS(I, p, c·s) is maximally stable according to ρ (Eq. 1, Gaussian weights of
// §2.1) and p is a local maximum of κ (§2.2, §3's iterated box filter) along ICS(I). No seeds and
// no fixed-point iterations (Algorithm 1, ComicDetector, is the paper's approximation of this
// search and stays as the detector "comic-paper"):
//
//   1. one component tree per polarity of the (lightly smoothed) image; its maximally stable
//      lineage maxima (unweighted ρ, §3) say which iso-curves can hold a feature;
//   2. on those curves, at every second grey level around each stable maximum, κ maxima at
//      scale s (with the straight-arm vertex correction of curve_cornerness.h);
//   3. κ maxima linked across consecutive traced levels into runs, both trees' on one scale of
//      grey levels: one run is one corner seen at several levels, and a run must span 5 levels.
//      ρ_w (Eq. 1 with §2.1's weights) of every member, smoothed across levels;
//      the run's ρ_w peak is its MSICS wherever it lies in the run, and the position is the
//      mean vertex of the levels around the peak that are equally stable (robust to one grey
//      level of noise, docs/comic_detector.md).
//
//   comic::frontend::ComicDirectDetectorOptions options;  // paper defaults: s = 8.4, δ = 5
//   comic::frontend::ComicDirectDetector detector(options);
//   comic::frontend::FeatureSet features = detector.Detect(gray);  // strongest ρ_w first
#pragma once

#include <string>
#include <vector>

#include "frontend/detector.h"

namespace comic::frontend {

struct ComicDirectDetectorOptions {
  // Detection scale s in pixels (paper §3: s = 8.4). The along-curve Gaussians (ρ weights, κ
  // window) have σ = s/√2 samples, ≈ k/2 at the defaults.
  double scale = 8.4;
  // Intensity offset δ of the Up/Down iso-curves in grey levels (paper Fig. 3: δ = 5).
  int delta = 5;
  // Points on either side of the centre of an iso-curve segment, k (≈25 points per ICS, §3).
  int half_length = 12;
  // Cornerness floor κ >= this (as ComicDetectorOptions::min_cornerness: 0.03 keeps turns of
  // more than ~35°; without it the noise wiggles of straight edges would be corners).
  double min_cornerness = 0.03;
  // The vertex correction (curve_cornerness.h, RefineCurveCorner) fades out as the arms' RMS
  // distance from their fitted lines grows from 0.03 px to this (px). Above RefineCurveCorner's
  // 0.1: the arms of an acute corner on a textured background wiggle by ~0.1-0.2 px around the
  // run's middle levels while the apex lies ~2 px inside the vertex (more so under the
  // pre-smoothing below, which rounds the apex further).
  double max_arm_rms = 0.2;
  // Levels traced on either side of each stable lineage maximum of the tree: the levels whose
  // curves can carry the same corner as the component's MSICS (a run's ρ_w peak may lie a few
  // levels from the component's, since ρ of a segment peaks where its own edge is steepest).
  int level_radius = 5;
  // Two stable maxima of one lineage at most this many levels apart: the levels between them are
  // traced too, so that a corner's run does not break where no maximum happened to be near (255:
  // always; on the cones at height 700 that adds 0.2 % to the curves traced, 20 levels would
  // leave runs of rendered polygons broken at the foot of their edges).
  int bridge_levels = 255;
  // κ maxima of consecutive traced levels (or, with none at the next one, of the one after it,
  // max_level_gap) closer than this (px) are the same corner, linked into a run.
  double link_radius = 1.5;
  // Curves are traced (and κ maxima linked) at the grey levels that are multiples of this only:
  // a corner's iso-curves change little from one level to the next (the [1 2 1] smoothing of ρ_w
  // across levels and the consensus average them anyway), and every second level halves the
  // curves and the ρ_w evaluations. Measured on the cones and KITTI 06/0 (docs/comic_detector.md):
  // repeatability at most 0.7 points below tracing every level (up to 2.1 above, with 5-level
  // runs and consensus 0.85), at half the instructions.
  int level_step = 2;
  // Up to this many consecutive traced levels without the corner's κ maximum are bridged by a
  // link (noise removes a maximum at a level; a level may be traced by neither tree).
  int max_level_gap = 1;
  // A run must span at least this many grey levels (first to last member) to give a feature: a κ
  // maximum seen at a few levels only is a wiggle of one curve (noise, fine texture), not a
  // corner of the level lines, and one grey level of noise removes it (on the cones, 55 % of the
  // runs of the full search spanned one or two levels).
  int min_run_levels = 5;
  // The levels of a run whose smoothed ρ_w is at least this fraction of the peak's, contiguous
  // with the peak, are equally stable: the feature is the mean of their vertices over a window
  // symmetric about the middle of those levels.
  double consensus_fraction = 0.85;
  // Standard deviation of the Gaussian pre-smoothing of the image, px (0: none). Harris and
  // Hessian smooth internally too; it keeps one grey level of noise off the iso-curves and keeps
  // a half-pixel shift from breaking runs. Larger values repeat better still but round acute
  // corners beyond what the vertex correction recovers (docs/comic_detector.md).
  double presmoothing_sigma = 1.25;
  // Features closer than this (px) are duplicates; the one with the higher ρ_w is kept.
  double merge_radius = 2.0;
  // Stability threshold on ρ_w (Eq. 1): features below it are not returned (0: all).
  double min_stability = 0.0;
  // Worker threads (0 = all hardware threads). Output is identical for any value.
  int num_threads = 1;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// One run of linked κ maxima and what became of it (diagnostics: where repeatability is lost).
struct ComicDirectRunRecord {
  // kOutsideImage: the run's consensus position (an extrapolated vertex near the border) lies
  // outside the image's pixel area.
  enum class Fate { kOutput, kNoStability, kBelowThreshold, kMerged, kThinSide, kOutsideImage };
  int tree = 0;         // 0: dark components, 1: bright
  int first_level = 0;  // grey levels of the run's first and last member
  int last_level = 0;
  int peak_level = 0;    // grey level of the smoothed ρ_w peak
  int window_begin = 0;  // grey levels of the consensus window's ends
  int window_end = 0;
  Polarity polarity = Polarity::kNone;
  cv::Point2f position;     // the feature's position (consensus vertex)
  cv::Point2f peak_vertex;  // the vertex of the peak member
  double stability = 0.0;   // smoothed ρ_w at the peak
  Fate fate = Fate::kOutput;
};

// Where one detection spent its work (the features do not depend on whether it is asked for).
struct ComicDirectDetectionStats {
  // Input: record every run in `runs` (costs memory; off by default).
  bool record_runs = false;
  std::vector<ComicDirectRunRecord> runs;
  double trees_ms = 0.0;      // smoothing, both component trees, stable maxima
  double curves_ms = 0.0;     // traced curves, κ maxima
  double stability_ms = 0.0;  // linking, ρ_w of every run member, consensus
  double output_ms = 0.0;     // merge, side masks, sorting
  int num_curves = 0;         // curves traced
  int num_maxima = 0;         // κ maxima over all levels
  int num_runs = 0;           // runs of linked maxima
};

class ComicDirectDetector : public Detector {
 public:
  explicit ComicDirectDetector(const ComicDirectDetectorOptions& options = {});

  std::string Name() const override { return "comic"; }
  FeatureSet Detect(const cv::Mat& gray) const override { return Detect(gray, nullptr); }
  // The same, filling `stats` when it is not null.
  FeatureSet Detect(const cv::Mat& gray, ComicDirectDetectionStats* stats) const;

  const ComicDirectDetectorOptions& options() const { return options_; }

 private:
  ComicDirectDetectorOptions options_;
};

}  // namespace comic::frontend
