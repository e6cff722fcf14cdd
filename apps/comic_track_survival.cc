// comic_track_survival: how long the SfM tracker's tracks live on a video (issue 30), for each
// detector beside OpenCV's pyramidal Lucas–Kanade on the same corners, and where the features
// that are lost go (frontend/evaluation/track_survival.h). Tracks with comic_sfm's tracker flags
// and defaults, at the frames' own size (as comic_sfm), and prints Markdown tables.
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/common/arg_parser.h"
#include "apps/common/frame_range_flags.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/progress_line.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "apps/common/tracker_flags.h"
#include "frontend/combined_detector.h"
#include "frontend/detector_factory.h"
#include "frontend/evaluation/epipolar_check.h"
#include "frontend/evaluation/track_survival.h"
#include "frontend/matching/combined_tracking.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/pixel_budget.h"
#include "io/datasets/kitti_odometry.h"
#include "io/image/image_sequence.h"

namespace {

namespace fe = comic::frontend;
namespace io = comic::io;
using comic::Error;
using comic::ErrorKind;

struct Flags {
  std::string frames;
  std::string detectors = "harris,hessian,fast,mser,comic,comic-paper,comic+hessian";
  io::ImageSequenceOptions sequence;
  int max_pixels = static_cast<int>(io::kDefaultMaxPixels);
  comic::apps::TrackerFlags tracker;
  int start_stride = 10;
  int horizon = 10;
  bool no_loss_split = false;
  bool no_lk = false;
  fe::LkReferenceOptions lk;
  int threads = 0;
  bool quiet = false;
  std::string json;
  std::string gt;     // KITTI poses.txt
  std::string calib;  // KITTI calib.txt
};

struct DetectorResult {
  std::string detector;
  double mean_track_length = 0.0;  // report.json's, over all tracks
  fe::SurvivalSummary ours;
  fe::SurvivalSummary lk;
  bool has_loss_split = false;
  fe::LossSplit losses;
  bool has_accuracy = false;
  fe::TrackAccuracy accuracy;
  double tracking_s = 0.0;
};

// Ground-truth cameras at the frames' size (KITTI), if given.
struct GroundTruth {
  bool known = false;
  cv::Matx33d K;
  std::vector<cv::Matx34d> world_from_camera;
};

std::string Fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string Percent(double share) { return Fixed(100.0 * share, 1); }

// Tracks the frames with one detector; fills the survival and the loss split.
DetectorResult RunDetector(const std::string& name, const std::vector<cv::Mat>& grays,
                           const Flags& flags, const fe::TrackerOptions& options,
                           const GroundTruth& truth) {
  fe::DetectorOptions detector_options;
  detector_options.name = name;
  detector_options.comic.num_threads = flags.threads;
  detector_options.comic_paper.num_threads = flags.threads;
  const std::unique_ptr<fe::Detector> detector = fe::MakeDetector(detector_options);
  comic::apps::ProgressLine progress("[" + name + "] tracking", flags.quiet);
  const auto start = std::chrono::steady_clock::now();
  fe::TrackingResult result;
  std::vector<fe::FeatureSet> detections;
  if (dynamic_cast<const fe::CombinedDetector*>(detector.get()) != nullptr) {
    result = fe::TrackFramesWithDetector(grays, *detector, options);
  } else {
    fe::Tracker tracker(options, detector->Name(), detector.get());
    for (size_t i = 0; i < grays.size(); ++i) {
      detections.push_back(detector->Detect(grays[i]));
      tracker.AddFrame(grays[i], fe::SelectTrackableFeatures(detections.back(), grays[i], options));
      progress.Update(i + 1, grays.size());
    }
    result = tracker.Result();
  }
  DetectorResult out;
  out.detector = name;
  out.tracking_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.mean_track_length = fe::MeanTrackLength(result.tracks);
  const std::vector<int> starts =
      fe::SurvivalStartFrames(static_cast<int>(grays.size()), flags.start_stride, flags.horizon);
  out.ours = fe::SummariseSurvival(fe::FramesFollowedFrom(result, starts));
  const fe::LkReferenceOptions& lk = flags.lk;
  if (!flags.no_lk) {
    out.lk = fe::SummariseSurvival(fe::LkFramesFollowedFrom(grays, result, starts, lk));
  }
  if (truth.known) {
    out.has_accuracy = true;
    out.accuracy = fe::EvaluateTrackAccuracy(result, truth.K, truth.world_from_camera, 2.0);
  }
  if (!flags.no_loss_split && !detections.empty()) {
    out.has_loss_split = true;
    for (int f = 0; f + 1 < static_cast<int>(grays.size()); ++f) {
      fe::Accumulate(fe::SplitLosses(result, f, grays[f], grays[f + 1], detections[f + 1], lk, {}),
                     &out.losses);
    }
  }
  return out;
}

void PrintSurvival(const std::vector<DetectorResult>& results, const Flags& flags) {
  std::cout << "\n| detector | mean track length (all tracks) | start-frame features | "
               "ours: mean length | ours ≥1 % | ≥5 % | ≥10 % |";
  if (!flags.no_lk) std::cout << " LK: mean length | LK ≥1 % | ≥5 % | ≥10 % |";
  std::cout << " tracking s |\n|---|---|---|---|---|---|---|";
  if (!flags.no_lk) std::cout << "---|---|---|---|";
  std::cout << "---|\n";
  for (const DetectorResult& r : results) {
    std::cout << "| " << r.detector << " | " << Fixed(r.mean_track_length, 2) << " | "
              << r.ours.num_features << " | " << Fixed(r.ours.mean_track_length, 2) << " | "
              << Percent(r.ours.share_followed[0]) << " | " << Percent(r.ours.share_followed[1])
              << " | " << Percent(r.ours.share_followed[2]) << " |";
    if (!flags.no_lk) {
      std::cout << " " << Fixed(r.lk.mean_track_length, 2) << " | "
                << Percent(r.lk.share_followed[0]) << " | " << Percent(r.lk.share_followed[1])
                << " | " << Percent(r.lk.share_followed[2]) << " |";
    }
    std::cout << " " << Fixed(r.tracking_s, 1) << " |\n";
  }
}

void PrintLossSplit(const std::vector<DetectorResult>& results) {
  std::cout << "\nWhere the features of frame i go in frame i+1 (% of all features of frames "
               "0..n-2; static / moving = within / beyond 2 px of the epipolar geometry of the "
               "LK motions):\n\n| detector | features |";
  for (int f = 0; f < fe::kNumFeatureFates; ++f) {
    std::cout << " " << fe::FeatureFateName(static_cast<fe::FeatureFate>(f)) << " |";
  }
  std::cout << " resumed later |\n|---|---|";
  for (int f = 0; f <= fe::kNumFeatureFates; ++f) std::cout << "---|";
  std::cout << "\n";
  for (const DetectorResult& r : results) {
    if (!r.has_loss_split) continue;
    const double n = std::max(1, r.losses.num_features);
    std::cout << "| " << r.detector << " | " << r.losses.num_features << " |";
    for (int f = 0; f < fe::kNumFeatureFates; ++f) {
      std::cout << " " << Percent(r.losses.counts[f][0] / n) << " / "
                << Percent(r.losses.counts[f][1] / n) << " |";
    }
    std::cout << " " << Percent(r.losses.resumed_later / n) << " |\n";
  }
}

void PrintAccuracy(const std::vector<DetectorResult>& results) {
  std::cout << "\nTracks of >= 3 observations triangulated with the true cameras: reprojection "
               "error of detected / continued observations:\n\n| detector | tracks | detected "
               "obs. | median px | > 2 px % | continued obs. | median px | > 2 px % |\n"
               "|---|---|---|---|---|---|---|---|\n";
  for (const DetectorResult& r : results) {
    if (!r.has_accuracy) continue;
    const fe::TrackAccuracy& a = r.accuracy;
    std::cout << "| " << r.detector << " | " << a.tracks;
    for (int k = 0; k < 2; ++k) {
      std::cout << " | " << a.observations[k] << " | " << Fixed(a.median_error_px[k], 2) << " | "
                << Percent(a.observations[k] > 0
                               ? static_cast<double>(a.beyond_tolerance[k]) / a.observations[k]
                               : 0.0);
    }
    std::cout << " |\n";
  }
}

nlohmann::json ToJson(const fe::SurvivalSummary& s) {
  return {{"features", s.num_features},
          {"mean_track_length", s.mean_track_length},
          {"mean_frames_followed", s.mean_frames_followed},
          {"share_followed_1", s.share_followed[0]},
          {"share_followed_5", s.share_followed[1]},
          {"share_followed_10", s.share_followed[2]}};
}

nlohmann::json ToJson(const std::vector<DetectorResult>& results) {
  nlohmann::json rows = nlohmann::json::array();
  for (const DetectorResult& r : results) {
    nlohmann::json row = {{"detector", r.detector},
                          {"mean_track_length", r.mean_track_length},
                          {"ours", ToJson(r.ours)},
                          {"lk", ToJson(r.lk)}};
    if (r.has_loss_split) {
      nlohmann::json fates = nlohmann::json::object();
      for (int f = 0; f < fe::kNumFeatureFates; ++f) {
        fates[fe::FeatureFateName(static_cast<fe::FeatureFate>(f))] = {
            {"static", r.losses.counts[f][0]}, {"moving", r.losses.counts[f][1]}};
      }
      row["loss_split"] = {{"features", r.losses.num_features},
                           {"fates", fates},
                           {"resumed_later", r.losses.resumed_later}};
    }
    rows.push_back(row);
  }
  return rows;
}

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("FRAMES", "folder of images or a video file", &flags.frames);
  comic::apps::AddDetectorListFlag(parser, &flags.detectors);
  comic::apps::AddMaxPixelsFlag(parser, &flags.max_pixels);
  comic::apps::AddFrameRangeFlags(parser, &flags.sequence, comic::apps::StrideFlag::kWithout);
  comic::apps::AddTrackerFlags(parser, &flags.tracker);
  parser.AddOption("start-stride", "K", "survival: start from the features of every K-th frame",
                   &flags.start_stride);
  parser.AddOption("horizon", "N",
                   "survival: only start frames with N frames after them (the >= N share)",
                   &flags.horizon);
  parser.AddFlag("no-loss-split", "skip where the features go (saves an LK pass per frame)",
                 &flags.no_loss_split);
  parser.AddFlag("no-lk", "skip the LK survival reference", &flags.no_lk);
  // With both, the tracks are triangulated with the true cameras and their reprojection errors
  // reported (the same flags as comic_track_eval's).
  parser.AddOption("poses", "FILE", "KITTI poses.txt (camera-to-world per frame) for precision",
                   &flags.gt);
  parser.AddOption("calib", "FILE", "KITTI calib.txt (P0 gives the intrinsics) for precision",
                   &flags.calib);
  parser.AddOption("lk-window", "PX", "LK reference: window side", &flags.lk.window);
  parser.AddOption("lk-levels", "N", "LK reference: pyramid levels above the frame",
                   &flags.lk.levels);
  parser.AddOption("lk-max-fb", "PX",
                   "LK reference: largest forward-backward error of a followed point",
                   &flags.lk.max_forward_backward_px);
  comic::apps::AddThreadsFlag(parser, &flags.threads);
  comic::apps::AddQuietFlag(parser, &flags.quiet);
  comic::apps::AddJsonFlag(parser, &flags.json);
}

// With --poses and --calib: the true cameras of the frames, at the frames' size.
GroundTruth ReadGroundTruth(const Flags& flags, const io::ImageSequence& sequence) {
  GroundTruth truth;
  COMIC_CHECK(flags.gt.empty() == flags.calib.empty(), kInvalidArgument,
              "--poses and --calib go together");
  if (!flags.gt.empty()) {
    truth.known = true;
    truth.K = fe::ScaleIntrinsics(io::ReadKittiIntrinsics(flags.calib, 0),
                                  sequence.SourceFrameSize(), sequence.FrameSize());
    const std::vector<cv::Matx34d> poses = io::ReadKittiPoses(flags.gt);
    for (size_t i = 0; i < sequence.NumFrames(); ++i) {
      const int source = flags.sequence.first_frame + static_cast<int>(i);
      COMIC_CHECK(source < static_cast<int>(poses.size()), kInvalidArgument,
                  flags.gt << ": no pose for frame " << source);
      truth.world_from_camera.push_back(poses[source]);
    }
  }
  return truth;
}

int Run(int argc, char** argv) {
  Flags flags;
  comic::apps::ArgParser parser(
      "comic_track_survival", "FRAMES [options]",
      "Tracks a video with comic_sfm's tracker for each detector and prints how long the tracks\n"
      "live (mean track length; share of the features of every --start-stride-th frame followed\n"
      ">= 1, 5, 10 frames) beside OpenCV's pyramidal Lucas-Kanade on the same corners, and where\n"
      "the features of each frame go in the next (continued, not re-detected, outside the search\n"
      "region, above the cost threshold, beaten under the one-to-one rule; LK is the reference).");
  AddFlags(parser, flags);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;

  const std::vector<std::string> detectors = fe::ParseDetectorList(flags.detectors);
  comic::apps::CheckThreadCount("--threads", flags.threads);
  COMIC_CHECK(flags.start_stride >= 1, kInvalidArgument, "--start-stride must be >= 1");
  COMIC_CHECK(flags.horizon >= 0, kInvalidArgument, "--horizon must be >= 0");
  io::CheckMaxPixels(flags.max_pixels);
  flags.sequence.max_pixels = flags.max_pixels;
  const fe::TrackerOptions options = comic::apps::ToTrackerOptions(flags.tracker);
  flags.lk.Check();
  const io::ImageSequence sequence = io::ImageSequence::Open(flags.frames, flags.sequence);
  std::vector<cv::Mat> grays;
  for (size_t i = 0; i < sequence.NumFrames(); ++i) grays.push_back(sequence.ReadFrame(i).gray);
  COMIC_CHECK(grays.size() >= 2, kInvalidArgument, flags.frames << ": needs at least 2 frames");

  const GroundTruth truth = ReadGroundTruth(flags, sequence);
  std::vector<DetectorResult> results;
  for (const std::string& name : detectors) {
    results.push_back(RunDetector(name, grays, flags, options, truth));
  }
  std::cout << "comic_track_survival " << flags.frames << ": " << grays.size()
            << " frames, prediction " << fe::MotionPredictionName(options.prediction)
            << ", start frames every " << flags.start_stride << " with " << flags.horizon
            << " frames after them\n";
  PrintSurvival(results, flags);
  if (!flags.no_loss_split) PrintLossSplit(results);
  if (truth.known) PrintAccuracy(results);
  if (!flags.json.empty()) {
    io::WriteFileAtomically(flags.json, ToJson(results).dump(2) + "\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return comic::apps::RunMain("comic_track_survival", [&] { return Run(argc, argv); });
}
