// comic_render_eval: the boundary question in SfM on rendered sequences with exact truth
// (sfm/evaluation/rendered_benchmark.h): per detector, features on occlusion boundaries, their
// tracks' lifetime and whether they follow a surface point, their share of the model, and ATE with
// and without them. Flags -> RenderedBenchmarkOptions -> RunRenderedBenchmark -> files.
#include <iostream>
#include <string>
#include <vector>

#include "apps/common/arg_parser.h"
#include "apps/common/frame_range_flags.h"
#include "apps/common/list_flags.h"
#include "apps/common/matching_flags.h"
#include "apps/common/shared_flags.h"
#include "apps/common/thread_count.h"
#include "apps/common/tracker_flags.h"
#include "frontend/detector_factory.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/protected_inputs.h"
#include "io/core/staged_folder.h"
#include "io/datasets/rendered_truth.h"
#include "io/image/image_sequence.h"
#include "sfm/evaluation/rendered_benchmark.h"
#include "sfm/run/tracker_settings.h"

namespace {

namespace io = comic::io;
namespace sfm = comic::sfm;

// The command line, bound to the parser by AddFlags; Check() validates it and fills `options`
// (all but the tracker, which FitTrackerToFrames sets for the frames).
struct Flags {
  // Every core, as the other apps: the output does not depend on it.
  Flags() { options.num_threads = 0; }
  void Check(const comic::apps::ArgParser& parser);

  std::string folder;
  std::string detectors;
  std::string matching = "auto";
  std::string out_dir = "render_eval";
  bool quiet = false;
  bool no_remap = false;
  sfm::RenderedBenchmarkOptions options;
  comic::apps::TrackerFlags tracker;
  sfm::TrackerSettings tracker_settings;  // from `tracker` by Check()
};

void AddFlags(comic::apps::ArgParser& parser, Flags& flags) {
  parser.AddPositional("RENDERED", "a comic_render output folder (not --frames-only)",
                       &flags.folder);
  parser.AddOption("detectors", "LIST", "comma-separated detectors, one run each (empty = all)",
                   &flags.detectors);
  comic::apps::AddFrameRangeFlags(parser, &flags.options.sequence);
  comic::apps::AddMatchingFlag(parser, &flags.matching);
  comic::apps::AddTrackerFlags(parser, &flags.tracker);
  parser.AddOption("follow-tolerance", "PX",
                   "a track follows a surface point if one reprojects to an RMS within PX",
                   &flags.options.tracks.follow_tolerance_px);
  // The shared meaning of --boundary-band: here the region is the occlusion boundary's (the
  // rendered band widened to PX).
  parser.AddOption("boundary-band", "PX",
                   "boundary features: within PX pixels of the region's edge (either side)",
                   &flags.options.band_px);
  parser.AddOption("min-track-length", "N", "shorter tracks are not judged follow/slide",
                   &flags.options.tracks.min_track_length);
  parser.AddFlag("no-remap",
                 "skip the mappings without boundary, sliding or labelled-sliding tracks",
                 &flags.no_remap);
  comic::apps::AddThreadsFlag(parser, &flags.options.num_threads);
  comic::apps::AddOutputFolderFlag(parser, &flags.out_dir);
  comic::apps::AddQuietFlag(parser, &flags.quiet);
  parser.AddEpilog(
      "Outputs in DIR: boundary_benchmark.md, boundary_benchmark.csv, boundary_benchmark.json.\n"
      "Example (docs/rendered_benchmark.md; scripts/rendered_benchmark.sh runs it all):\n"
      "  comic_render scenes/orbit_object.json --photos PHOTOS -o out/orbit\n"
      "  comic_render_eval out/orbit --detectors harris,comic,comic+hessian -o out/orbit_eval");
}

void Flags::Check(const comic::apps::ArgParser& parser) {
  if (!detectors.empty()) {
    options.detectors = comic::frontend::ParseDetectorList(detectors);
  } else {
    options.detectors = comic::frontend::DetectorNames();
    options.detectors.push_back("comic+hessian");
  }
  options.without_boundary_tracks = options.without_sliding_tracks =
      options.without_labelled_sliding_tracks = !no_remap;
  comic::apps::CheckThreadCount("--threads", options.num_threads);
  options.sequence.Check();
  tracker_settings = comic::apps::ToTrackerSettings(tracker, parser);
  tracker_settings.ToTrackerOptions();  // bad flags fail before any work
  options.Check();
  io::CheckOutputsAvoidInputs({{"--output", out_dir}}, {{"RENDERED", folder}});
  io::CheckCreatableFolder(out_dir);
}

// Sets the tracker of `flags.options` for the rendered frames; returns the pairing it chose.
comic::frontend::PairingChoice FitTrackerToFrames(Flags& flags) {
  sfm::RenderedBenchmarkOptions& options = flags.options;
  // The tracker as comic_sfm sets it up for these frames (video or image set), and its mapper
  // defaults for known intrinsics: two-view tracks left out of video.
  const io::RenderedTruth truth = io::OpenRenderedTruth(flags.folder);
  const io::ImageSequence sequence =
      io::ImageSequence::Open(truth.ImagesFolder(), options.sequence);
  const comic::frontend::PairingChoice pairing =
      sfm::ChooseRunPairing(flags.matching, flags.tracker_settings, sequence);
  options.reconstruction.tracker = sfm::TrackerOptionsForRun(
      flags.tracker_settings, pairing, static_cast<int>(sequence.NumFrames()));
  options.reconstruction.mapper.mapper.ignore_two_view_tracks =
      options.reconstruction.tracker.match_window <= 1;
  options.Check();
  return pairing;
}

// boundary_benchmark.md, .csv and .json in `folder`; returns the table.
io::ReportTable WriteOutputs(const std::string& folder, const sfm::RenderedBenchmark& result,
                             const comic::frontend::PairingChoice& pairing) {
  const io::ReportTable table = result.Table();
  io::WriteFileAtomically(io::JoinPaths(folder, "boundary_benchmark.md"), table.ToMarkdown());
  io::WriteFileAtomically(io::JoinPaths(folder, "boundary_benchmark.csv"), table.ToCsv());
  nlohmann::json json = result.ToJson();
  json["matching"] = comic::frontend::PairingName(pairing.chosen);
  io::WriteFileAtomically(io::JoinPaths(folder, "boundary_benchmark.json"), json.dump(2) + "\n");
  for (size_t d = 0; d < result.detectors.size(); ++d) {
    io::WriteFileAtomically(
        io::JoinPaths(folder, "tracks_" + result.detectors[d].detector + ".csv"),
        result.TrackScoreTable(d).ToCsv());
  }
  return table;
}

int Run(int argc, char** argv) {
  Flags flags;
  comic::apps::ArgParser parser(
      "comic_render_eval", "RENDERED [options]",
      "The boundary question in SfM on a comic_render output (frames with exact truth): for\n"
      "each detector, the share of features on occlusion boundaries, how long their tracks live,\n"
      "how many follow one 3-D surface point (the true point re-projected through the true\n"
      "cameras) or slide along a silhouette, their share of the model's points and reprojection\n"
      "error, and the ATE with all tracks, without the boundary tracks, without the sliding\n"
      "ones and without those a labeller that sees no truth calls sliding. Tracking and mapping\n"
      "are comic_sfm's, with the true camera. Writes boundary_benchmark.{md,csv,json} and\n"
      "tracks_<detector>.csv (every track: its truth, its side changes, drift and label).");
  AddFlags(parser, flags);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  flags.Check(parser);
  const comic::frontend::PairingChoice pairing = FitTrackerToFrames(flags);

  io::StagedFolder out(flags.out_dir);
  const sfm::RenderedBenchmark result = sfm::RunRenderedBenchmark(
      flags.folder, flags.options, [quiet = flags.quiet](const std::string& message) {
        if (!quiet) std::cout << "comic_render_eval: " << message << std::endl;
      });
  const io::ReportTable table = WriteOutputs(out.path(), result, pairing);
  out.Commit();
  std::cout << table.ToMarkdown();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_render_eval", [&] { return Run(argc, argv); });
}
