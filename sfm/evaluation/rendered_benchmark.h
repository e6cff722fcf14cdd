// The boundary question in SfM on a rendered sequence (a comic_render output folder, read through
// io/datasets/rendered_truth.h): for each detector, the tracks and model of the ordinary run
// (sfm/sequence_reconstruction.h, the options comic_sfm uses) judged against exact truth —
// features on occlusion boundaries, how long their tracks live, how many follow one surface point
// (sfm/evaluation/boundary_tracks.h), their share of the model's points and reprojection error —
// and the trajectory error with all tracks, without the boundary tracks, and without the tracks
// that slide (which only the truth can tell).
//
//   RenderedBenchmarkOptions options;
//   options.detectors = {"harris", "comic"};
//   const RenderedBenchmark result = RunRenderedBenchmark("out/orbit", options);
//   io::WriteFileAtomically("boundary.md", result.Table().ToMarkdown());
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "frontend/matching/track_side_change.h"
#include "io/image/image_sequence.h"
#include "io/report/report_table.h"
#include "sfm/evaluation/boundary_tracks.h"
#include "sfm/evaluation/reconstruction_stats.h"
#include "sfm/sequence_reconstruction.h"
#include "sfm/track_labels.h"

namespace comic::sfm {

struct RenderedBenchmarkOptions {
  // Detector names (frontend::DetectorNames(), or combinations such as "comic+hessian").
  std::vector<std::string> detectors = {"comic", "comic-paper", "harris",       "hessian",
                                        "mser",  "fast",        "comic+hessian"};
  // Which frames (first, last, stride); the frames are used at their rendered size.
  io::ImageSequenceOptions sequence;
  SequenceReconstructionOptions reconstruction;
  BoundaryTrackOptions tracks;
  // A feature is on a boundary within this many pixels of a depth discontinuity: the rendered
  // band (boundaries/, render_options.boundary_band_px in scene.json) widened to it. At least the
  // rendered band. 4 px: where a corner detector's integration window (sigma 1.5-2.5 px) meets
  // the discontinuity.
  double band_px = 4.0;
  // Threads for CoMIC's detection (0: every core); the output does not depend on it.
  int num_threads = 1;
  // Map again without the boundary tracks, and without the tracks that slide.
  bool without_boundary_tracks = true;
  bool without_sliding_tracks = true;
  // Label the tracks without truth (sfm/track_labels.h) and map again without those labelled
  // sliding: what a run without truth can do.
  bool without_labelled_sliding_tracks = true;
  TrackLabelOptions labels;

  void Check() const;
};

// One mapping of the sequence's tracks and its trajectory error.
struct ModelSummary {
  std::string status;  // sfm::ReconstructionStatusName
  int num_registered = 0;
  size_t num_points = 0;
  size_t num_tracks = 0;           // tracks given to the mapper
  std::optional<double> ate_rmse;  // metres, Sim(3)-aligned; none without 3 registered frames
  double ate_fraction_of_path = 0.0;
  double mapping_time_s = 0.0;
};

// One track as the truth judges it and as the evidence without truth sees it: how each side of
// its point changes along it (frontend/matching/track_side_change.h) and how far it strays from
// one point under the model's cameras (sfm/track_drift.h).
struct TrackScore {
  size_t length = 0;
  TrackTruth truth;
  frontend::SideChange sides;
  std::optional<double> model_drift_px;
  LabelledTrack labelled;
};

// The labeller's sliding verdicts against the truth's, over the tracks the truth classifies.
struct LabelAgreement {
  size_t num_labelled_sliding = 0;  // labelled sliding
  size_t num_true_sliding = 0;      // sliding in truth
  size_t num_both = 0;              // both
  double Precision() const {
    return num_labelled_sliding == 0 ? 0.0 : static_cast<double>(num_both) / num_labelled_sliding;
  }
  double Recall() const {
    return num_true_sliding == 0 ? 0.0 : static_cast<double>(num_both) / num_true_sliding;
  }
};

struct DetectorBenchmark {
  std::string detector;
  size_t num_features = 0;
  size_t num_boundary_features = 0;
  double boundary_area_fraction = 0.0;
  TrackSetSummary boundary_tracks;
  TrackSetSummary other_tracks;
  ModelSummary model;  // all tracks
  PointSetStats points;
  PointSetStats boundary_points;      // points observed mostly in the band
  double boundary_error_share = 0.0;  // of the model's summed reprojection error
  std::optional<ModelSummary> without_boundary;
  std::optional<ModelSummary> without_sliding;
  LabelAgreement labelled_sliding;
  std::optional<ModelSummary> without_labelled_sliding;
  double tracking_time_s = 0.0;
  std::vector<TrackScore> track_scores;  // one per track given to the mapper
};

struct RenderedBenchmark {
  std::string folder;
  int num_frames = 0;
  double band_px = 0.0;
  std::vector<DetectorBenchmark> detectors;

  // One row per detector (the docs' table); ToJson holds every number.
  io::ReportTable Table() const;
  nlohmann::json ToJson() const;
  // One row per track of detectors[d]: its truth and its evidence (track_scores).
  io::ReportTable TrackScoreTable(size_t d) const;
};

using BenchmarkProgress = std::function<void(const std::string& message)>;

// Throws comic::Error for an unreadable folder (io::OpenRenderedTruth) or bad options.
RenderedBenchmark RunRenderedBenchmark(const std::string& folder,
                                       const RenderedBenchmarkOptions& options,
                                       const BenchmarkProgress& progress = {});

}  // namespace comic::sfm
