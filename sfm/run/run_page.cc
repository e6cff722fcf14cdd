#include "sfm/run/run_page.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "io/core/file_utils.h"
#include "io/datasets/ground_truth_cameras.h"
#include "io/report/bar_chart.h"
#include "io/report/number_text.h"
#include "io/report/page_charts.h"
#include "io/report/page_scene.h"
#include "io/report/page_sections.h"
#include "sfm/camera_model.h"
#include "sfm/run/run_page_diagnostics.h"
#include "sfm/run/run_page_frames.h"
#include "sfm/run/run_page_matches.h"
#include "sfm/run/run_page_scene.h"
#include "sfm/run/run_page_timeline.h"
#include "sfm/run/run_report.h"

namespace comic::sfm {

namespace {

io::PageTone StatusTone(const std::string& status) {
  if (status == "success") return io::PageTone::kGood;
  if (status == "partial") return io::PageTone::kWarning;
  return io::PageTone::kBad;
}

std::string CameraWords(const Camera& camera) {
  std::string words = CameraModelName(camera.model) + " " + std::to_string(camera.width) + "×" +
                      std::to_string(camera.height) + " px, f " + io::NumberText("%.1f", camera.fx);
  if (camera.fy != camera.fx) words += "/" + io::NumberText("%.1f", camera.fy);
  return words + " px, principal point (" + io::NumberText("%.1f", camera.cx) + ", " +
         io::NumberText("%.1f", camera.cy) + ")";
}

// The camera of the model (or the prior without one), where it came from and whether it moved.
std::vector<io::PageFact> CameraFacts(const DetectorRun& run, const RunInputs& inputs) {
  const Reconstruction& model = run.run.mapping.reconstruction;
  const bool has_model = run.success() && !model.cameras().empty();
  const Camera& camera = has_model ? model.cameras().begin()->second : inputs.camera.camera;
  std::vector<io::PageFact> facts = {{"camera", CameraWords(camera)},
                                     {"intrinsics from", inputs.camera.source}};
  if (!has_model) {
    facts.push_back({"refined by the run", "no model"});
  } else if (!run.report.intrinsics_rejection.empty()) {
    // In the summary line's words: self-calibration moved them out of the plausible range.
    facts.push_back({"refined by the run",
                     "no: held at the prior (" + run.report.intrinsics_rejection + ")",
                     io::PageTone::kWarning});
  } else if (run.run.mapping.intrinsics_refined) {
    facts.push_back({"refined by the run", "from the prior " + CameraWords(inputs.camera.camera),
                     io::PageTone::kWarning});
  } else {
    facts.push_back({"refined by the run", inputs.camera.refine_intrinsics
                                               ? "no (the motion did not constrain them)"
                                               : "no (held fixed)"});
  }
  return facts;
}

// After the largest model's count: what the other models hold, and how many of their frames the
// largest lacks (models may share frames: a frame is counted once).
std::string OtherModelsWords(const std::vector<const Reconstruction*>& models) {
  if (models.size() < 2) return "";
  std::string sizes;
  std::set<image_t> only_in_others;
  for (size_t m = 1; m < models.size(); ++m) {
    const size_t count = models[m]->NumRegisteredImages();
    sizes += (m == 1 ? "" : (m + 1 == models.size() ? " and " : ", ")) + std::to_string(count);
    for (const auto& [image_id, image] : models[m]->images()) {
      const bool in_largest =
          models[0]->ExistsImage(image_id) && models[0]->image(image_id).registered;
      if (image.registered && !in_largest) only_in_others.insert(image_id);
    }
  }
  const bool one = models.size() == 2;
  return " in the largest model; the " + std::string(one ? "other model holds " : "") +
         (one ? "" : std::to_string(models.size() - 1) + " other models hold ") + sizes +
         " frames, " + std::to_string(only_in_others.size()) + " of them not in the largest";
}

io::PageSection SummarySection(const DetectorRun& run, const ReconstructionRunOptions& options,
                               const RunInputs& inputs) {
  const SfmRunReport& report = run.report;
  const size_t frames = report.num_frames;
  const size_t registered = report.stats.num_registered;
  const std::vector<const Reconstruction*> models = RunModels(run);
  const std::string others = OtherModelsWords(models);
  std::vector<io::PageFact> facts = {
      {"status", report.status, StatusTone(report.status)},
      {"detector", run.detector},
      {"frames", options.frames + " · " + std::to_string(frames) + " frames of " +
                     std::to_string(inputs.sequence->FrameSize().width) + "×" +
                     std::to_string(inputs.sequence->FrameSize().height) + " px"},
      {"registered",
       std::to_string(registered) + " of " + std::to_string(frames) + " frames (" +
           io::NumberText("%.0f", frames ? 100.0 * registered / frames : 0.0) + " %)" + others,
       registered == frames ? io::PageTone::kGood
                            : (registered == 0 ? io::PageTone::kBad : io::PageTone::kWarning)},
      {"models", std::to_string(models.size())},
      {"3-D points", std::to_string(report.stats.all.num_points) + " · mean track length " +
                         io::NumberText("%.2f", report.stats.all.mean_track_length) +
                         " · mean reprojection error " +
                         io::NumberText("%.3f", report.stats.all.mean_reprojection_error_px) +
                         " px"},
      {"tracks", std::to_string(report.num_tracks) + " from the tracker, mean length " +
                     io::NumberText("%.2f", report.mean_tracker_track_length)}};
  if (run.run.mapping.status == ReconstructionStatus::kSuspect) {
    // Why the run's own check doubts the model (sfm/model_self_check.h, sfm/moving_object.h).
    facts.insert(facts.begin() + 1,
                 {"why suspect", run.run.mapping.self_check.reason, io::PageTone::kBad});
  }
  for (const io::PageFact& fact : CameraFacts(run, inputs)) facts.push_back(fact);
  if (run.evaluation) {
    const std::string unit = PlaceModels(run, inputs).unit;
    facts.push_back(
        {"ATE (RMSE)", io::NumberText("%.4g ", run.evaluation->ate_rmse) + unit + " (" +
                           io::NumberText("%.3g", 100 * run.evaluation->ate_fraction_of_path) +
                           " % of the " + io::NumberText("%.4g ", run.evaluation->path_length) +
                           unit + " path), max " +
                           io::NumberText("%.4g ", run.evaluation->ate_max) + unit});
    facts.push_back(
        {"rotation error", io::NumberText("%.3f", run.evaluation->mean_rotation_error_deg) +
                               " deg on average over " +
                               std::to_string(run.evaluation->frames.size()) + " frames"});
    facts.push_back({"end to start", io::NumberText("%.4g ", run.evaluation->end_to_start_error) +
                                         unit +
                                         " error of the last frame's position relative to the "
                                         "first's (after the alignment)"});
  } else if (!options.gt.empty()) {
    facts.push_back({"ground truth", "too few registered frames with a true pose to evaluate",
                     io::PageTone::kWarning});
  }
  if (report.loop_closure)
    facts.push_back({"loop closure", LoopClosureWords(*report.loop_closure)});
  return io::FactsSection("Summary", facts);
}

io::PageSection TimeSection(const SfmRunReport& report) {
  io::PageSection section = io::FactsSection(
      "Time per stage",
      {{"detection and tracking", io::NumberText("%.2f s", report.tracking_time_s)},
       {"mapping", io::NumberText("%.2f s", report.mapping_time_s) + " (local bundle adjustment " +
                       io::NumberText("%.2f s", report.local_ba_time_s) + " in " +
                       std::to_string(report.num_local_ba) + ", global " +
                       io::NumberText("%.2f s", report.global_ba_time_s) + " in " +
                       std::to_string(report.num_global_ba) + ")"},
       {"whole run",
        io::NumberText("%.2f s", report.wall_time_s) + " wall clock (this page not counted)"}});
  section[kDurationsKey] = true;
  return section;
}

// Why there is no model and what was kept; or which frames are missing from one.
void AppendDiagnosis(const DetectorRun& run, std::vector<io::PageSection>* sections) {
  if (run.diagnosis.failed) {
    std::string kept = run.keeps_tracks ? " The tracks are kept in tracks.db (a COLMAP database: "
                                          "colmap mapper or its GUI can try them)."
                                        : "";
    if (run.rotation_only && run.rotation_only->num_registered >= 2) {
      kept += " The camera only turned: its rotations are in rotation_only/.";
    }
    sections->push_back(io::NoticeSection(
        io::PageTone::kBad, "Why the reconstruction failed",
        run.diagnosis.message + ". Try " + run.diagnosis.suggestion + "." + kept));
  } else if (!run.report.unregistered_frames.empty()) {
    sections->push_back(
        io::NoticeSection(io::PageTone::kWarning, "Frames left out",
                          std::to_string(run.report.unregistered_frames.size()) +
                              " frames are in no model; the timeline shows which and why."));
  }
}

void AppendGeometry(const DetectorRun& run, const ReconstructionRunOptions& options,
                    const RunInputs& inputs, std::vector<io::PageSection>* sections) {
  const PlacedModels placed = PlaceModels(run, inputs);
  if (!placed.models.empty()) {
    sections->push_back(io::SceneSection(RunScene(placed, inputs, options.report_page.max_points)));
  }
  sections->push_back(io::TimelineSection(RunTimeline(run, inputs.sequence->FrameNames())));
  for (const io::LineChart& chart : RunErrorCharts(run, inputs)) {
    sections->push_back(io::LineChartSection(chart));
  }
  if (!placed.models.empty()) {
    sections->push_back(io::TopViewSection(RunTopView(placed, run, inputs)));
  }
}

// Per frame (observations, inliers, reprojection error, pose), the residuals of every model, and
// which frames share tracks.
void AppendDiagnostics(const DetectorRun& run, const ReconstructionRunOptions& options,
                       const RunInputs& inputs, std::vector<io::PageSection>* sections) {
  for (const io::PageSection& section :
       FrameDiagnosticsSections(run, inputs.sequence->FrameNames())) {
    sections->push_back(section);
  }
  if (const auto matrix = MatchMatrixSection(run, options.report_page)) {
    sections->push_back(*matrix);
  }
}

void AppendFrames(const DetectorRun& run, const ReconstructionRunOptions& options,
                  const RunInputs& inputs, std::vector<io::PageSection>* sections) {
  const RunFramePictures pictures = RunFramePicturesOf(run, inputs, options.report_page);
  if (!pictures.tracks.empty()) {
    sections->push_back(io::ImagesSection(
        "Frames with their tracks", pictures.tracks, pictures.legend,
        "Each track through the frame is drawn over its last 5 frames, ending in a dot at its "
        "feature; the first frame no model holds is among them when there is one."));
  }
  if (!pictures.thumbnails.empty()) {
    sections->push_back(io::ImagesSection("The clip", pictures.thumbnails, {},
                                          pictures.thumbnails_note, /*thumbnails=*/true));
  }
}

std::string PageTitle(const std::string& what, const ReconstructionRunOptions& options) {
  return "comic_sfm · " + what + " · " + io::FileName(options.frames);
}

// Points, ATE, registered frames and time per detector, one colour per detector.
io::BarChart DetectorChart(const std::vector<DetectorRun>& runs, const std::string& title,
                           const std::string& y_label, double (*value)(const DetectorRun&)) {
  io::BarChart chart;
  chart.title = title;
  chart.y_label = y_label;
  chart.groups = {title};
  for (const DetectorRun& run : runs) chart.series.push_back({run.detector, {value(run)}});
  return chart;
}

}  // namespace

std::string LoopClosureWords(const LoopClosureSummary& summary) {
  std::string rejected =
      summary.rejected.empty()
          ? ""
          : " · " + std::to_string(summary.rejected.size()) +
                " verified but rejected: inconsistent with the odometry (look-alike places)";
  if (summary.num_ruled_out_by_odometry > 0) {
    rejected += " · " + std::to_string(summary.num_ruled_out_by_odometry) +
                " look-alike pairs too far apart for the odometry";
  }
  if (summary.loops.empty()) {
    return "no loop found among " + std::to_string(summary.num_nodes) + " keyframes searched (" +
           std::to_string(summary.num_candidates) + " candidates by appearance)" + rejected;
  }
  std::string words = std::to_string(summary.loops.size()) +
                      (summary.loops.size() == 1 ? " loop" : " loops") + " closed: frames ";
  constexpr size_t kListed = 4;
  for (size_t k = 0; k < std::min(summary.loops.size(), kListed); ++k) {
    words += (k ? ", " : "") + std::to_string(summary.loops[k].query_frame) + " → " +
             std::to_string(summary.loops[k].match_frame);
  }
  if (summary.loops.size() > kListed) words += ", …";
  return words + " · " + std::to_string(summary.num_points_fused) +
         " points fused · cameras moved up to " + io::NumberText("%.3g", summary.max_correction) +
         " (model units)" + rejected;
}

io::HtmlPage RunPage(const DetectorRun& run, const ReconstructionRunOptions& options,
                     const RunInputs& inputs) {
  io::HtmlPage page;
  page.title = PageTitle(run.detector, options);
  page.subtitle = "report.html of comic_sfm: status " + run.report.status + ", " +
                  std::to_string(run.report.stats.num_registered) + "/" +
                  std::to_string(run.report.num_frames) + " frames registered";
  std::vector<io::PageSection> sections = {SummarySection(run, options, inputs)};
  AppendDiagnosis(run, &sections);
  sections.push_back(TimeSection(run.report));
  AppendGeometry(run, options, inputs, &sections);
  AppendDiagnostics(run, options, inputs, &sections);
  AppendFrames(run, options, inputs, &sections);
  if (run.report_json.contains("options")) {
    sections.push_back(io::KeyValuesSection("Options", run.report_json["options"]));
  }
  sections.push_back(io::JsonSection("report.json", run.report_json));
  page.sections = sections;
  return page;
}

io::HtmlPage ComparisonPage(const io::ReportTable& table, const std::vector<DetectorRun>& runs,
                            const ReconstructionRunOptions& options, const RunInputs& inputs) {
  io::HtmlPage page;
  page.title = PageTitle("--compare", options);
  page.subtitle = "report.html of comic_sfm --compare: " + std::to_string(runs.size()) +
                  " detectors on " + std::to_string(inputs.sequence->NumFrames()) + " frames";
  std::vector<std::string> links;
  for (const DetectorRun& run : runs) links.push_back(run.detector + "/report.html");
  io::PageSection table_section =
      io::TableSection("Detectors compared", table,
                       "Each detector's own page (3-D view, timeline, frames) is linked from its "
                       "name. Empty cells: no model, or no ground truth.",
                       links);
  table_section[kDurationsKey] = true;  // its time columns
  std::vector<io::PageSection> sections = {table_section};
  const auto ate = [](const DetectorRun& run) {
    return run.evaluation ? run.evaluation->ate_rmse : std::nan("");
  };
  const auto points = [](const DetectorRun& run) {
    return static_cast<double>(run.report.stats.all.num_points);
  };
  const auto registered = [](const DetectorRun& run) {
    return static_cast<double>(run.report.stats.num_registered);
  };
  const auto seconds = [](const DetectorRun& run) { return run.report.wall_time_s; };
  const std::string truth_unit = io::GroundTruthLengthUnit(inputs.gt_format);
  const std::string unit =
      "ATE RMSE (" + (truth_unit.empty() ? std::string("ground-truth units") : truth_unit) + ")";
  std::vector<io::BarChart> charts;
  if (inputs.ground_truth) charts.push_back(DetectorChart(runs, "ATE", unit, ate));
  charts.push_back(DetectorChart(runs, "3-D points", "points", points));
  charts.push_back(DetectorChart(runs, "registered frames", "frames", registered));
  sections.push_back(io::BarChartsSection("ATE, points and registered frames per detector", charts,
                                          "ATE: lower is better; no bar: no model to evaluate."));
  io::PageSection time = io::BarChartsSection(
      "Time per detector", {DetectorChart(runs, "wall time", "time (s)", seconds)},
      "Detection, tracking and mapping, wall clock.");
  time[kDurationsKey] = true;
  sections.push_back(time);
  for (const DetectorRun& run : runs) {
    io::Timeline timeline = RunTimeline(run, inputs.sequence->FrameNames());
    timeline.title = "Registration timeline: " + run.detector;
    sections.push_back(io::TimelineSection(timeline));
  }
  sections.push_back(io::KeyValuesSection("Options", RunOptionsToJson(options, inputs)));
  page.sections = sections;
  return page;
}

}  // namespace comic::sfm
