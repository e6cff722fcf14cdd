#include "sfm/evaluation/rendered_benchmark.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "frontend/detector_factory.h"
#include "io/core/error.h"
#include "io/datasets/rendered_truth.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/incremental_pipeline.h"
#include "sfm/track_drift.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {
namespace {

// A boundary band kept for a whole sequence at one bit per pixel (2000 frames of 640x480 in
// 77 MB rather than 600).
class PackedMask {
 public:
  explicit PackedMask(const cv::Mat& mask) : width_(mask.cols), height_(mask.rows) {
    bits_.assign((mask.total() + 63) / 64, 0);
    for (int y = 0; y < mask.rows; ++y) {
      for (int x = 0; x < mask.cols; ++x) {
        if (mask.at<uint8_t>(y, x) != 0) {
          const size_t i = static_cast<size_t>(y) * width_ + x;
          bits_[i / 64] |= uint64_t{1} << (i % 64);
        }
      }
    }
  }
  bool At(int x, int y) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return false;
    const size_t i = static_cast<size_t>(y) * width_ + x;
    return (bits_[i / 64] >> (i % 64)) & 1;
  }
  cv::Mat Unpack() const {
    cv::Mat mask(height_, width_, CV_8UC1);
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) mask.at<uint8_t>(y, x) = At(x, y) ? 255 : 0;
    }
    return mask;
  }

 private:
  int width_;
  int height_;
  std::vector<uint64_t> bits_;
};

// What one benchmark needs of the rendered folder, for the selected frames.
struct SequenceTruth {
  io::RenderedTruth files;
  std::vector<int> source_indices;
  Camera camera;
  std::vector<Rigid3d> cams_from_world;
  std::vector<std::optional<Rigid3d>> optional_poses;  // for EvaluateTrajectory
  std::vector<PackedMask> bands;
};

// The rendered band widened to `band_px` (a disc of the difference).
cv::Mat WidenBand(const cv::Mat& band, double rendered_px, double band_px) {
  const int extra = static_cast<int>(std::floor(band_px - rendered_px + 1e-9));
  if (extra <= 0) return band;
  cv::Mat wide;
  cv::dilate(band, wide,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * extra + 1, 2 * extra + 1)));
  return wide;
}

SequenceTruth LoadTruth(const std::string& folder, const io::ImageSequence& sequence,
                        const io::ImageSequenceOptions& options, double band_px) {
  SequenceTruth truth{io::OpenRenderedTruth(folder), {}, {}, {}, {}, {}};
  COMIC_CHECK(band_px >= truth.files.band_px, kInvalidArgument,
              "boundary band " << band_px << " px is narrower than the one rendered in " << folder
                               << " (" << truth.files.band_px << " px)");
  const io::CameraCalibration& c = truth.files.camera;
  const std::optional<CameraModelId> model = CameraModelFromName(c.model);
  COMIC_CHECK(model.has_value(), kInvalidData, folder << "/colmap/cameras.txt: model " << c.model);
  truth.camera = Camera::FromParams(*model, c.width, c.height, c.params);
  COMIC_CHECK(sequence.FrameSize() == cv::Size(c.width, c.height), kInvalidData,
              folder << ": frames are " << sequence.FrameSize().width << "x"
                     << sequence.FrameSize().height << ", the camera " << c.width << "x"
                     << c.height);
  for (size_t k = 0; k < sequence.NumFrames(); ++k) {
    const int source = options.first_frame + static_cast<int>(k) * options.stride;
    truth.source_indices.push_back(source);
    const io::GroundTruthCamera& camera = truth.files.cameras.cameras.at(source);
    truth.cams_from_world.emplace_back(camera.cam_from_world_rotation,
                                       camera.cam_from_world_translation);
    truth.optional_poses.push_back(truth.cams_from_world.back());
    truth.bands.emplace_back(
        WidenBand(truth.files.Boundaries(source), truth.files.band_px, band_px));
  }
  return truth;
}

ModelSummary Summarize(const IncrementalReconstruction& mapping, size_t num_tracks,
                       const io::ImageSequence& sequence, const SequenceTruth& truth) {
  ModelSummary summary;
  summary.status = ReconstructionStatusName(mapping.status);
  summary.num_tracks = num_tracks;
  summary.mapping_time_s = mapping.wall_time_s;
  if (mapping.status != ReconstructionStatus::kSuccess) return summary;
  summary.num_registered = static_cast<int>(mapping.reconstruction.NumRegisteredImages());
  summary.num_points = mapping.reconstruction.NumPoints3D();
  const auto evaluation = EvaluateTrajectory(
      RegisteredPosesByName(mapping.reconstruction, sequence.FrameNames()), truth.optional_poses);
  if (evaluation) {
    summary.ate_rmse = evaluation->ate_rmse;
    summary.ate_fraction_of_path = evaluation->ate_fraction_of_path;
  }
  return summary;
}

// The mapper again, on the tracks `keep` accepts.
ModelSummary MapAgain(const SequenceReconstruction& run, const std::function<bool(size_t)>& keep,
                      const RenderedBenchmarkOptions& options, const io::ImageSequence& sequence,
                      const SequenceTruth& truth) {
  frontend::FeatureTracks kept = run.tracks;
  kept.tracks.clear();
  for (size_t t = 0; t < run.tracks.tracks.size(); ++t) {
    if (keep(t)) kept.tracks.push_back(run.tracks.tracks[t]);
  }
  const IncrementalReconstruction mapping =
      ReconstructIncrementally(kept, truth.camera, options.reconstruction.mapper);
  return Summarize(mapping, kept.tracks.size(), sequence, truth);
}

// Each track's truth beside its side changes and its drift in the model.
std::vector<TrackScore> ScoreTracks(const SequenceReconstruction& run,
                                    const BoundaryTrackEvaluation& truth,
                                    const io::ImageSequence& sequence,
                                    const TrackLabelOptions& label_options) {
  const std::vector<frontend::SideChange> sides = frontend::MeasureTrackSideChanges(
      run.tracks, [&](int frame) { return sequence.ReadFrame(frame).gray; }, {});
  const std::vector<std::optional<double>> drift =
      MeasureTrackDrift(run.tracks, run.mapping.reconstruction);
  const std::vector<LabelledTrack> labels = LabelTracks(sides, drift, label_options);
  std::vector<TrackScore> scores(run.tracks.tracks.size());
  for (size_t t = 0; t < scores.size(); ++t) {
    scores[t] = {run.tracks.tracks[t].Length(), truth.tracks[t], sides[t], drift[t], labels[t]};
  }
  return scores;
}

LabelAgreement CompareLabels(const std::vector<TrackScore>& scores) {
  LabelAgreement agreement;
  for (const TrackScore& score : scores) {
    if (!score.truth.classified) continue;
    const bool labelled = score.labelled.label == TrackLabel::kSliding;
    const bool sliding = !score.truth.follows;
    agreement.num_labelled_sliding += labelled;
    agreement.num_true_sliding += sliding;
    agreement.num_both += labelled && sliding;
  }
  return agreement;
}

DetectorBenchmark RunDetector(const std::string& name, const RenderedBenchmarkOptions& options,
                              const io::ImageSequence& sequence, const SequenceTruth& truth,
                              const BenchmarkProgress& progress) {
  frontend::DetectorOptions detector_options;
  detector_options.name = name;
  detector_options.comic.num_threads = options.num_threads;
  detector_options.comic_paper.num_threads = options.num_threads;
  const auto detector = frontend::MakeDetector(detector_options);
  const SequenceReconstruction run =
      ReconstructSequence(sequence, *detector, truth.camera, options.reconstruction);
  DetectorBenchmark result;
  result.detector = name;
  result.tracking_time_s = run.tracking_time_s;
  const BoundaryTrackEvaluation tracks = EvaluateBoundaryTracks(
      run.tracks, truth.camera, truth.cams_from_world,
      [&](int frame) {
        return FrameTruth{truth.bands[frame].Unpack(),
                          truth.files.Depth(truth.source_indices[frame])};
      },
      options.tracks);
  result.num_features = tracks.num_features;
  result.num_boundary_features = tracks.num_boundary_features;
  result.boundary_area_fraction = tracks.boundary_area_fraction;
  result.boundary_tracks = tracks.boundary;
  result.other_tracks = tracks.other;
  result.model = Summarize(run.mapping, run.tracks.tracks.size(), sequence, truth);
  // Image k of the model is frame k - 1 (the mapper numbers them from 1).
  const ReconstructionStats stats = ComputeReconstructionStats(
      run.mapping.reconstruction, [&](const Image& image, const Eigen::Vector2d& xy) {
        const bool in = truth.bands[image.image_id - 1].At(static_cast<int>(std::lround(xy.x())),
                                                           static_cast<int>(std::lround(xy.y())));
        return in ? frontend::RegionLabel::kBoundary : frontend::RegionLabel::kInterior;
      });
  result.points = stats.all;
  if (stats.boundary) result.boundary_points = *stats.boundary;
  const double total_error = stats.all.mean_reprojection_error_px * stats.all.num_observations;
  if (total_error > 0) {
    result.boundary_error_share = result.boundary_points.mean_reprojection_error_px *
                                  result.boundary_points.num_observations / total_error;
  }
  result.track_scores = ScoreTracks(run, tracks, sequence, options.labels);
  result.labelled_sliding = CompareLabels(result.track_scores);
  if (progress) progress("[" + name + "] tracked and mapped; mapping again without some tracks");
  if (options.without_boundary_tracks) {
    result.without_boundary = MapAgain(
        run, [&](size_t t) { return !tracks.tracks[t].boundary; }, options, sequence, truth);
  }
  if (options.without_sliding_tracks) {
    result.without_sliding = MapAgain(
        run, [&](size_t t) { return !tracks.tracks[t].classified || tracks.tracks[t].follows; },
        options, sequence, truth);
  }
  if (options.without_labelled_sliding_tracks) {
    result.without_labelled_sliding = MapAgain(
        run,
        [&](size_t t) { return result.track_scores[t].labelled.label != TrackLabel::kSliding; },
        options, sequence, truth);
  }
  return result;
}

nlohmann::json SummaryToJson(const TrackSetSummary& s) {
  return {{"tracks", s.num_tracks},
          {"mean_length", s.mean_length},
          {"median_length", s.median_length},
          {"classified", s.num_classified},
          {"following", s.num_following},
          {"following_fraction", s.FollowingFraction()},
          {"median_drift_px", std::isfinite(s.median_drift_px) ? nlohmann::json(s.median_drift_px)
                                                               : nlohmann::json(nullptr)}};
}

nlohmann::json ModelToJson(const ModelSummary& m) {
  return {{"status", m.status},
          {"registered", m.num_registered},
          {"points", m.num_points},
          {"tracks", m.num_tracks},
          {"ate_rmse", m.ate_rmse ? nlohmann::json(*m.ate_rmse) : nlohmann::json(nullptr)},
          {"ate_fraction_of_path", m.ate_fraction_of_path},
          {"mapping_time_s", m.mapping_time_s}};
}

nlohmann::json PointsToJson(const PointSetStats& p) {
  return {{"points", p.num_points},
          {"observations", p.num_observations},
          {"mean_track_length", p.mean_track_length},
          {"mean_reprojection_error_px", p.mean_reprojection_error_px}};
}

io::ReportTable::Cell Ate(const std::optional<ModelSummary>& m) {
  if (!m || !m->ate_rmse) return std::monostate();
  return *m->ate_rmse;
}

double Percent(double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0.0; }

}  // namespace

void RenderedBenchmarkOptions::Check() const {
  COMIC_CHECK(!detectors.empty(), kInvalidArgument, "the benchmark needs at least one detector");
  for (const std::string& name : detectors) frontend::CheckDetectorName(name);
  sequence.Check();
  reconstruction.Check();
  tracks.Check();
  labels.Check();
  COMIC_CHECK(num_threads >= 0, kInvalidArgument, "threads must be >= 0, got " << num_threads);
  COMIC_CHECK(band_px >= 0 && band_px <= 50, kInvalidArgument,
              "boundary band must be in 0..50 px, got " << band_px);
}

io::ReportTable RenderedBenchmark::Table() const {
  io::ReportTable table({"detector",
                         "features",
                         "on boundary %",
                         "band area %",
                         "boundary tracks",
                         "boundary track length",
                         "other track length",
                         "boundary following %",
                         "other following %",
                         "boundary drift px",
                         "registered",
                         "points",
                         "boundary points %",
                         "boundary error %",
                         "ATE m",
                         "ATE w/o boundary m",
                         "ATE w/o sliding m",
                         "labelled sliding precision",
                         "labelled sliding recall",
                         "ATE w/o labelled sliding m"});
  for (const char* column : {"on boundary %", "band area %", "boundary following %",
                             "other following %", "boundary points %", "boundary error %"}) {
    table.SetPrecision(column, 1);
  }
  for (const char* column : {"boundary track length", "other track length", "boundary drift px"}) {
    table.SetPrecision(column, 2);
  }
  for (const char* column : {"labelled sliding precision", "labelled sliding recall"}) {
    table.SetPrecision(column, 2);
  }
  for (const char* column :
       {"ATE m", "ATE w/o boundary m", "ATE w/o sliding m", "ATE w/o labelled sliding m"}) {
    table.SetPrecision(column, 4);
  }
  for (const DetectorBenchmark& d : detectors) {
    table.AddRow({d.detector,
                  static_cast<int64_t>(d.num_features),
                  Percent(d.num_boundary_features, d.num_features),
                  100.0 * d.boundary_area_fraction,
                  static_cast<int64_t>(d.boundary_tracks.num_tracks),
                  d.boundary_tracks.mean_length,
                  d.other_tracks.mean_length,
                  100.0 * d.boundary_tracks.FollowingFraction(),
                  100.0 * d.other_tracks.FollowingFraction(),
                  d.boundary_tracks.median_drift_px,
                  static_cast<int64_t>(d.model.num_registered),
                  static_cast<int64_t>(d.points.num_points),
                  Percent(d.boundary_points.num_points, d.points.num_points),
                  100.0 * d.boundary_error_share,
                  Ate(d.model),
                  Ate(d.without_boundary),
                  Ate(d.without_sliding),
                  d.labelled_sliding.Precision(),
                  d.labelled_sliding.Recall(),
                  Ate(d.without_labelled_sliding)});
  }
  return table;
}

nlohmann::json RenderedBenchmark::ToJson() const {
  nlohmann::json runs = nlohmann::json::array();
  for (const DetectorBenchmark& d : detectors) {
    nlohmann::json run = {{"detector", d.detector},
                          {"features", d.num_features},
                          {"boundary_features", d.num_boundary_features},
                          {"boundary_area_fraction", d.boundary_area_fraction},
                          {"boundary_tracks", SummaryToJson(d.boundary_tracks)},
                          {"other_tracks", SummaryToJson(d.other_tracks)},
                          {"model", ModelToJson(d.model)},
                          {"points", PointsToJson(d.points)},
                          {"boundary_points", PointsToJson(d.boundary_points)},
                          {"boundary_error_share", d.boundary_error_share},
                          {"tracking_time_s", d.tracking_time_s}};
    if (d.without_boundary) run["without_boundary_tracks"] = ModelToJson(*d.without_boundary);
    if (d.without_sliding) run["without_sliding_tracks"] = ModelToJson(*d.without_sliding);
    run["labelled_sliding"] = {{"labelled", d.labelled_sliding.num_labelled_sliding},
                               {"true", d.labelled_sliding.num_true_sliding},
                               {"both", d.labelled_sliding.num_both},
                               {"precision", d.labelled_sliding.Precision()},
                               {"recall", d.labelled_sliding.Recall()}};
    if (d.without_labelled_sliding) {
      run["without_labelled_sliding_tracks"] = ModelToJson(*d.without_labelled_sliding);
    }
    runs.push_back(run);
  }
  return {{"folder", folder},
          {"frames", num_frames},
          {"band_px", band_px},
          {"table", Table().ToJson()},
          {"runs", runs}};
}

io::ReportTable RenderedBenchmark::TrackScoreTable(size_t d) const {
  io::ReportTable table({"track", "length", "boundary", "classified", "follows", "drift px",
                         "sides", "object side", "plus mean", "minus mean", "plus last",
                         "minus last", "model drift px", "label"});
  for (const char* column :
       {"drift px", "plus mean", "minus mean", "plus last", "minus last", "model drift px"}) {
    table.SetPrecision(column, 3);
  }
  const std::vector<TrackScore>& scores = detectors.at(d).track_scores;
  for (size_t t = 0; t < scores.size(); ++t) {
    const TrackScore& s = scores[t];
    table.AddRow({static_cast<int64_t>(t), static_cast<int64_t>(s.length),
                  static_cast<int64_t>(s.truth.boundary), static_cast<int64_t>(s.truth.classified),
                  static_cast<int64_t>(s.truth.follows), s.truth.drift_px,
                  static_cast<int64_t>(s.sides.measured),
                  static_cast<int64_t>(static_cast<int>(s.sides.object_side)),
                  static_cast<double>(s.sides.plus_mean), static_cast<double>(s.sides.minus_mean),
                  static_cast<double>(s.sides.plus_last), static_cast<double>(s.sides.minus_last),
                  s.model_drift_px ? io::ReportTable::Cell(*s.model_drift_px)
                                   : io::ReportTable::Cell(std::monostate()),
                  TrackLabelName(s.labelled.label)});
  }
  return table;
}

RenderedBenchmark RunRenderedBenchmark(const std::string& folder,
                                       const RenderedBenchmarkOptions& options,
                                       const BenchmarkProgress& progress) {
  options.Check();
  io::ImageSequenceOptions sequence_options = options.sequence;
  sequence_options.resize_height = 0;  // the truth is at the rendered size
  const io::ImageSequence sequence =
      io::ImageSequence::Open(io::OpenRenderedTruth(folder).ImagesFolder(), sequence_options);
  const SequenceTruth truth = LoadTruth(folder, sequence, sequence_options, options.band_px);
  RenderedBenchmark result;
  result.folder = folder;
  result.num_frames = static_cast<int>(sequence.NumFrames());
  result.band_px = options.band_px;
  for (const std::string& name : options.detectors) {
    if (progress) progress("[" + name + "] detecting and tracking " + folder);
    result.detectors.push_back(RunDetector(name, options, sequence, truth, progress));
  }
  return result;
}

}  // namespace comic::sfm
