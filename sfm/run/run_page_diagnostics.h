// The per-frame diagnostics of report.html (sfm/run/run_page.h): for every frame the model that
// holds it and how it got its pose (registered, by rotation only, interpolated, none), its
// observations in that model (2-D points with a 3-D point), the PnP inliers of its registration
// and the mean reprojection error of its observations, as a table and as charts along the frames;
// and the reprojection error of every observation of every model as a histogram. Everything is
// read from the run's models and what the mapper reported, never estimated again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/report/page_sections.h"
#include "sfm/run/detector_run.h"

namespace comic::sfm {

struct FrameDiagnostics {
  int frame = 0;
  // The model that holds the frame (index into RunModels: 0 is sparse/0), or interpolates its
  // pose; -1 for none. The first such model, largest first, as on the timeline.
  int model = -1;
  PoseSource source = PoseSource::kRegistered;  // meaningful only with a model
  int observations = 0;                         // 2-D points of the frame with a 3-D point
  int pnp_inliers = -1;                         // DetectorRun::pose_inliers; -1: unknown
  double mean_error_px = 0.0;                   // NaN without observations
  bool HasPose() const { return model >= 0; }
};

// One per frame of a run of `num_frames` frames.
std::vector<FrameDiagnostics> RunFrameDiagnostics(const DetectorRun& run, int num_frames);

// The page's word for a frame's pose: "registered", "rotation only", "interpolated" or "none".
std::string PoseWords(const FrameDiagnostics& frame);

struct ErrorHistogram {
  double bin_width_px = 0.0;
  std::vector<int64_t> counts;  // bin k: [k, k + 1) x bin_width_px (the last closed)
  int64_t overflow = 0;         // errors beyond the last bin, and infinite ones (behind a camera)
  int64_t total = 0;
};

// `errors_px` in `num_bins` bins of equal width from 0 up to a round value (1, 2 or 5 x 10^k px)
// at or above their 99th percentile, so that a few wild errors do not squeeze the rest into the
// first bin; the errors beyond it are counted as overflow.
ErrorHistogram HistogramOfErrors(std::vector<double> errors_px, int num_bins);

// The reprojection error of every observation of every model of the run, model by model.
std::vector<double> RunReprojectionErrors(const DetectorRun& run);

// The sections: observations and inliers along the frames, the mean reprojection error along the
// frames, the table of every frame, and the histogram of all reprojection errors. None without a
// model.
std::vector<io::PageSection> FrameDiagnosticsSections(const DetectorRun& run,
                                                      const std::vector<std::string>& frame_names);

}  // namespace comic::sfm
