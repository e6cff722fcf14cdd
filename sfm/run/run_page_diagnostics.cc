#include "sfm/run/run_page_diagnostics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/report/number_text.h"
#include "io/report/page_charts.h"
#include "io/report/page_distributions.h"
#include "io/report/report_table.h"
#include "sfm/run/run_page_timeline.h"

namespace comic::sfm {

namespace {

constexpr int kHistogramBins = 20;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The frames of model `index` (RunModels' order) posed by rotation only, and interpolated.
const std::vector<int>& RotationOnlyFrames(const IncrementalReconstruction& mapping, int index) {
  return index == 0 ? mapping.rotation_only_frames
                    : mapping.other_models[index - 1].rotation_only_frames;
}
const std::vector<int>& InterpolatedFrames(const IncrementalReconstruction& mapping, int index) {
  return index == 0 ? mapping.interpolated_frames
                    : mapping.other_models[index - 1].interpolated_frames;
}

bool Contains(const std::vector<int>& ascending, int frame) {
  return std::binary_search(ascending.begin(), ascending.end(), frame);
}

// The observations of registered frame `frame` of `model` and their mean reprojection error.
void MeasureObservations(const Reconstruction& model, int frame, FrameDiagnostics* diagnostics) {
  const image_t id = static_cast<image_t>(frame + 1);
  const Image& image = model.image(id);
  double sum = 0.0;
  int count = 0;
  for (point2D_t k = 0; k < image.points2D.size(); ++k) {
    if (!image.points2D[k].HasPoint3D()) continue;
    sum += model.ReprojectionError(id, k);
    ++count;
  }
  diagnostics->observations = count;
  diagnostics->mean_error_px = count ? sum / count : kNaN;
}

// The smallest 1, 2 or 5 x 10^k at or above `value` (1 for none above 0).
double RoundUp(double value) {
  if (!(value > 0.0) || !std::isfinite(value)) return 1.0;
  const double power = std::pow(10.0, std::floor(std::log10(value)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * power >= value * (1.0 - 1e-12)) return m * power;
  }
  return 10.0 * power;
}

io::ReportTable FrameTable(const std::vector<FrameDiagnostics>& frames,
                           const std::vector<std::string>& frame_names) {
  io::ReportTable table({"frame", "name", "model", "pose", "observations", "PnP inliers",
                         "mean reprojection error (px)"});
  table.SetPrecision("mean reprojection error (px)", 3);
  for (const FrameDiagnostics& f : frames) {
    using Cell = io::ReportTable::Cell;
    const Cell model = f.HasPose() ? Cell("sparse/" + std::to_string(f.model)) : Cell();
    const bool observed = f.HasPose() && f.source != PoseSource::kInterpolated;
    const Cell observations = observed ? Cell(int64_t{f.observations}) : Cell();
    const Cell inliers = f.pnp_inliers >= 0 ? Cell(int64_t{f.pnp_inliers}) : Cell();
    const Cell error = std::isfinite(f.mean_error_px) ? Cell(f.mean_error_px) : Cell();
    const std::string name =
        f.frame < static_cast<int>(frame_names.size()) ? frame_names[f.frame] : "";
    table.AddRow({int64_t{f.frame}, name, model, PoseWords(f), observations, inliers, error});
  }
  return table;
}

// The frames without a pose and those with an interpolated one, as ticks under a chart.
std::vector<io::LineChartMarks> PoseMarks(const std::vector<FrameDiagnostics>& frames) {
  io::LineChartMarks none{"no pose", "#cf222e", {}};
  io::LineChartMarks interpolated{"interpolated pose", "#9a6700", {}};
  for (const FrameDiagnostics& f : frames) {
    if (!f.HasPose()) none.x.push_back(f.frame);
    if (f.HasPose() && f.source == PoseSource::kInterpolated) interpolated.x.push_back(f.frame);
  }
  std::vector<io::LineChartMarks> marks;
  for (const io::LineChartMarks& m : {none, interpolated}) {
    if (!m.x.empty()) marks.push_back(m);
  }
  return marks;
}

std::vector<io::LineChart> FrameCharts(const std::vector<FrameDiagnostics>& frames) {
  io::LineChartSeries observations{"observations (2-D points with a 3-D point)", "#2f7fd0", {}, {}};
  io::LineChartSeries inliers{"PnP inliers at registration", "#e8a317", {}, {}};
  io::LineChartSeries errors{"mean reprojection error", "#e0452b", {}, {}};
  for (const FrameDiagnostics& f : frames) {
    const bool observed = f.HasPose() && f.source != PoseSource::kInterpolated;
    for (io::LineChartSeries* s : {&observations, &inliers, &errors}) s->x.push_back(f.frame);
    observations.y.push_back(observed ? f.observations : kNaN);
    inliers.y.push_back(f.pnp_inliers >= 0 ? f.pnp_inliers : kNaN);
    errors.y.push_back(f.mean_error_px);
  }
  io::LineChart counts;
  counts.title = "Observations and inliers per frame";
  counts.x_label = "frame";
  counts.y_label = "2-D points";
  counts.series = {observations, inliers};
  counts.marks = PoseMarks(frames);
  counts.note =
      "Observations: the frame's 2-D points that hold a 3-D point of its model now. PnP inliers: "
      "of the frame's last registration by PnP as the mapper reported it (none for the initial "
      "pair, frames merged from another model and poses found without PnP).";
  io::LineChart error;
  error.title = "Mean reprojection error per frame";
  error.x_label = "frame";
  error.y_label = "mean reprojection error (px)";
  error.series = {errors};
  error.marks = counts.marks;
  error.note = "Over the frame's observations, in the input's pixels.";
  return {counts, error};
}

io::PageSection HistogramSection(const DetectorRun& run) {
  const std::vector<double> errors = RunReprojectionErrors(run);
  const ErrorHistogram histogram = HistogramOfErrors(errors, kHistogramBins);
  io::Histogram chart;
  chart.title = "Reprojection errors";
  chart.x_label = "reprojection error (px)";
  chart.y_label = "observations";
  chart.color = "#2f7fd0";
  for (size_t k = 0; k <= histogram.counts.size(); ++k) {
    chart.edges.push_back(k * histogram.bin_width_px);
  }
  chart.counts = histogram.counts;
  chart.overflow = histogram.overflow;
  const size_t num_models = RunModels(run).size();
  chart.note = std::to_string(histogram.total) + " observations of the " +
               std::to_string(num_models) + (num_models == 1 ? " model" : " models") +
               ", in bins of " + io::NumberText("%.4g", histogram.bin_width_px) + " px; " +
               std::to_string(histogram.overflow) + " beyond " +
               io::NumberText("%.4g", chart.edges.back()) +
               " px (the last bar, and any behind their camera).";
  return io::HistogramSection(chart);
}

}  // namespace

std::string PoseWords(const FrameDiagnostics& frame) {
  if (!frame.HasPose()) return "none";
  switch (frame.source) {
    case PoseSource::kRegistered:
      return "registered";
    case PoseSource::kRotationOnly:
      return "rotation only";
    case PoseSource::kInterpolated:
      return "interpolated";
  }
  return "none";
}

std::vector<FrameDiagnostics> RunFrameDiagnostics(const DetectorRun& run, int num_frames) {
  std::vector<FrameDiagnostics> frames(std::max(0, num_frames));
  for (int f = 0; f < num_frames; ++f) {
    frames[f].frame = f;
    frames[f].mean_error_px = kNaN;
    if (f < static_cast<int>(run.pose_inliers.size())) frames[f].pnp_inliers = run.pose_inliers[f];
  }
  const std::vector<const Reconstruction*> models = RunModels(run);
  for (size_t m = 0; m < models.size(); ++m) {
    const int index = static_cast<int>(m);
    for (int f : RegisteredFramesOf(*models[m])) {
      if (f < 0 || f >= num_frames || frames[f].HasPose()) continue;
      frames[f].model = index;
      frames[f].source = Contains(RotationOnlyFrames(run.run.mapping, index), f)
                             ? PoseSource::kRotationOnly
                             : PoseSource::kRegistered;
      MeasureObservations(*models[m], f, &frames[f]);
    }
  }
  // A guess, kept out of the models: only for frames no model holds.
  for (size_t m = 0; m < models.size(); ++m) {
    for (int f : InterpolatedFrames(run.run.mapping, static_cast<int>(m))) {
      if (f < 0 || f >= num_frames || frames[f].HasPose()) continue;
      frames[f].model = static_cast<int>(m);
      frames[f].source = PoseSource::kInterpolated;
    }
  }
  return frames;
}

ErrorHistogram HistogramOfErrors(std::vector<double> errors_px, int num_bins) {
  ErrorHistogram histogram;
  histogram.counts.assign(std::max(1, num_bins), 0);
  histogram.total = static_cast<int64_t>(errors_px.size());
  // Not a number cannot be sorted; counted beyond the scale with the infinite ones.
  const auto not_numbers =
      std::remove_if(errors_px.begin(), errors_px.end(), [](double e) { return std::isnan(e); });
  histogram.overflow = errors_px.end() - not_numbers;
  errors_px.erase(not_numbers, errors_px.end());
  std::sort(errors_px.begin(), errors_px.end());
  const double p99 = errors_px.empty()
                         ? 0.0
                         : errors_px[static_cast<size_t>(std::ceil(0.99 * (errors_px.size() - 1)))];
  const double top = RoundUp(p99);
  const int bins = static_cast<int>(histogram.counts.size());
  histogram.bin_width_px = top / bins;
  for (double e : errors_px) {
    if (!(e <= top)) {  // beyond, or infinite (behind the camera)
      ++histogram.overflow;
      continue;
    }
    // Scaled by the bin count before the division: round values stay on their edge.
    const int bin = std::min(bins - 1, static_cast<int>(std::floor(e * bins / top)));
    ++histogram.counts[std::max(0, bin)];
  }
  return histogram;
}

std::vector<double> RunReprojectionErrors(const DetectorRun& run) {
  std::vector<double> errors;
  for (const Reconstruction* model : RunModels(run)) {
    for (const auto& [id, point] : model->points3D()) {
      for (const TrackElement& element : point.track) {
        errors.push_back(model->ReprojectionError(element.image_id, element.point2D_idx));
      }
    }
  }
  return errors;
}

std::vector<io::PageSection> FrameDiagnosticsSections(const DetectorRun& run,
                                                      const std::vector<std::string>& frame_names) {
  if (RunModels(run).empty()) return {};
  const std::vector<FrameDiagnostics> frames =
      RunFrameDiagnostics(run, static_cast<int>(frame_names.size()));
  std::vector<io::PageSection> sections;
  for (const io::LineChart& chart : FrameCharts(frames)) {
    sections.push_back(io::LineChartSection(chart));
  }
  io::PageSection table = io::TableSection(
      "Per-frame diagnostics", FrameTable(frames, frame_names),
      "One row per frame. model: the sparse/<k> folder that holds the frame (or whose poses it "
      "was interpolated between); pose: registered (from its observations), rotation only (its "
      "rotation against the map, the centre of a neighbour), interpolated (a guess, not in the "
      "model) or none. Observations and the mean reprojection error are measured in the model as "
      "written; PnP inliers as the mapper reported the frame's registration.");
  table["scroll"] = true;  // every frame: a long table scrolls in its own box
  sections.push_back(table);
  sections.push_back(HistogramSection(run));
  return sections;
}

}  // namespace comic::sfm
