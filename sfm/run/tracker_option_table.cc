#include "sfm/run/tracker_option_table.h"

#include <algorithm>
#include <type_traits>
#include <utility>

#include "frontend/matching/track_builder.h"
#include "io/core/error.h"

namespace comic::sfm {
namespace {

using Options = frontend::TrackerOptions;
using Continuation = frontend::TrackContinuationOptions;

// The keyword is the flag's name with underscores, as every keyword of the Python module.
TrackerOption Entry(std::string flag, std::string metavar, std::string help,
                    TrackerOption::Field field) {
  std::string keyword = flag;
  std::replace(keyword.begin(), keyword.end(), '-', '_');
  return {std::move(flag), std::move(keyword), std::move(metavar), std::move(help), field};
}

// Parses `name` with `parse`, the error message prefixed with the flag it was given to.
template <typename Parse>
auto ParseNamed(const char* flag, const std::string& name, Parse parse) {
  try {
    return parse(name);
  } catch (const Error& e) {
    throw Error(e.kind(), std::string("--") + flag + ": " + e.what());
  }
}

// Where features are searched for and which frames are matched.
std::vector<TrackerOption> SearchOptions() {
  return {
      Entry("max-features", "N", "keep the N strongest features per frame (0 = all)",
            [](Options& o) -> int& { return o.max_features; }),
      Entry("search-radius", "PX",
            "matcher search radius r around a feature's (predicted) position (paper: 20)",
            [](Options& o) -> double& { return o.matcher.radius; }),
      Entry("unpredicted-radius", "PX",
            "tracker search radius where no motion predicts a feature (0 = --search-radius)",
            [](Options& o) -> double& { return o.unpredicted_radius; }),
      Entry("prediction", "P", "tracker motion prediction: none, velocity, coarse-to-fine",
            TrackerOption::Named{[](const Options& o) -> std::string {
                                   return frontend::MotionPredictionName(o.prediction);
                                 },
                                 [](Options& o, const std::string& name) {
                                   o.prediction = ParseNamed("prediction", name,
                                                             frontend::ParseMotionPrediction);
                                 }}),
      Entry("coarse-radius", "PX",
            "coarse-to-fine prediction: search radius of the coarse pass (pixels of the frames "
            "as used)",
            [](Options& o) -> double& { return o.coarse_radius; }),
      Entry("match-window", "K",
            "match each frame to the next K frames, not only the next one, and build the tracks "
            "from all the matches (sparse image sets: links views across a wide or failed step)",
            [](Options& o) -> int& { return o.match_window; }),
      Entry("track-conflicts", "RULE",
            "--match-window > 1: a set of matches holding two features of one frame is "
            "'drop'ped whole, or split 'greedy' (nearer frames' matches first, then lower cost; "
            "a match joining two features of one frame is refused)",
            TrackerOption::Named{[](const Options& o) -> std::string {
                                   return frontend::TrackConflictRuleName(o.conflict_rule);
                                 },
                                 [](Options& o, const std::string& name) {
                                   o.conflict_rule = ParseNamed("track-conflicts", name,
                                                                frontend::ParseTrackConflictRule);
                                 }}),
      Entry("verify-min-gap", "G",
            "verify the matches of frame pairs at least G frames apart with a fundamental matrix "
            "(RANSAC, 2 px); a pair no epipolar geometry explains loses its matches (0 = none)",
            [](Options& o) -> int& { return o.verify_min_gap; }),
      Entry("match-turned", "",
            "also match each verified pair with the later frame turned by 180 degrees and keep "
            "the hypothesis with more verified matches (Middlebury rings: views of the other "
            "latitude sign are upside down; needs --verify-min-gap)",
            [](Options& o) -> bool& { return o.match_turned_180; }),
      Entry("max-cost", "T", "SSD threshold T: a match's largest mean squared grey difference",
            [](Options& o) -> double& { return o.matcher.max_cost; }),
      Entry("min-window-eigenvalue", "E",
            "track only features whose 23x23 window has a gradient moment with both eigenvalues "
            ">= E (grey levels squared per pixel squared; 0 = all)",
            [](Options& o) -> double& { return o.min_window_eigenvalue; }),
  };
}

// The patch alignment and the continuation of lost tracks (track_continuation.h).
std::vector<TrackerOption> AlignmentOptions() {
  return {
      Entry("align-patches", "BOOL",
            "align each feature's patch into the next frame (pyramidal, gain and bias) and "
            "search detections near where it aligned: 1 or 0",
            [](Options& o) -> bool& { return o.align_patches; }),
      Entry("max-continued-frames", "N",
            "with --align-patches 1: a track whose feature is not re-detected continues at its "
            "aligned position for up to N consecutive frames (0 = never)",
            [](Options& o) -> int& { return o.continuation.max_continued_frames; }),
      Entry("max-alignment-residual", "T",
            "an alignment is trusted if its mean squared difference after gain and bias is at "
            "most T (grey levels squared)",
            [](Options& o) -> double& { return o.continuation.max_residual; }),
      Entry("aligned-radius", "PX", "search radius for detections around a trusted alignment",
            [](Options& o) -> double& { return o.continuation.aligned_radius; }),
      Entry("min-alignment-correlation", "C",
            "an alignment is trusted if its normalised cross-correlation is at least C",
            [](Options& o) -> double& { return o.continuation.min_correlation; }),
      Entry("alignment-min-eigenvalue", "E",
            "windows with a weaker gradient moment are not aligned",
            [](Options& o) -> double& { return o.continuation.alignment.min_eigenvalue; }),
      Entry("bridge-frames", "G",
            "with --align-patches 1: a track lost at frame i is looked for again in frames "
            "i+2 .. i+G (re-association after a gap; 0 = none)",
            [](Options& o) -> int& { return o.continuation.bridge_frames; }),
      Entry("alignment-max-fb", "PX",
            "an alignment counts only if aligning back returns within PX of the start (0 = no "
            "check)",
            [](Options& o) -> double& { return o.continuation.alignment.max_forward_backward_px; }),
      Entry("alignment-iterations", "N", "iterations per level of the patch alignment",
            [](Options& o) -> int& { return o.continuation.alignment.max_iterations; }),
      Entry("alignment-levels", "N", "pyramid levels of the patch alignment",
            [](Options& o) -> int& { return o.continuation.alignment.levels; }),
  };
}

}  // namespace

std::vector<TrackerOption> TrackerOptionTable() {
  std::vector<TrackerOption> table = SearchOptions();
  for (TrackerOption& entry : AlignmentOptions()) table.push_back(std::move(entry));
  return table;
}

TrackerOption FindTrackerOption(const std::string& flag) {
  const std::vector<TrackerOption> table = TrackerOptionTable();
  const auto it = std::find_if(table.begin(), table.end(),
                               [&](const TrackerOption& entry) { return entry.flag == flag; });
  COMIC_CHECK(it != table.end(), kInvalidArgument, "no tracker option --" << flag);
  return *it;
}

void CopyTrackerOption(const TrackerOption& entry, const frontend::TrackerOptions& from,
                       frontend::TrackerOptions& to) {
  Options source = from;  // the accessors take their struct by reference
  std::visit(
      [&](auto field) {
        if constexpr (std::is_same_v<decltype(field), TrackerOption::Named>) {
          field.set(to, field.get(source));
        } else {
          field(to) = field(source);
        }
      },
      entry.field);
}

}  // namespace comic::sfm
