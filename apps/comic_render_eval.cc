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

int Run(int argc, char** argv) {
  std::string folder;
  std::string detectors;
  std::string matching = "auto";
  std::string out_dir = "render_eval";
  bool quiet = false;
  bool no_remap = false;
  sfm::RenderedBenchmarkOptions options;
  options.num_threads = 0;  // every core, as the other apps: the output does not depend on it
  comic::apps::TrackerFlags tracker;
  comic::apps::ArgParser parser(
      "comic_render_eval", "RENDERED [options]",
      "The boundary question in SfM on a comic_render output (frames with exact truth): for\n"
      "each detector, the share of features on occlusion boundaries, how long their tracks live,\n"
      "how many follow one 3-D surface point (the true point re-projected through the true\n"
      "cameras) or slide along a silhouette, their share of the model's points and reprojection\n"
      "error, and the ATE with all tracks, without the boundary tracks and without the sliding\n"
      "ones. Tracking and mapping are comic_sfm's, with the true camera.");
  parser.AddPositional("RENDERED", "a comic_render output folder (not --frames-only)", &folder);
  parser.AddOption("detectors", "LIST", "comma-separated detectors, one run each (empty = all)",
                   &detectors);
  comic::apps::AddFrameRangeFlags(parser, &options.sequence);
  comic::apps::AddMatchingFlag(parser, &matching);
  comic::apps::AddTrackerFlags(parser, &tracker);
  parser.AddOption("follow-tolerance", "PX",
                   "a track follows a surface point if one reprojects to an RMS within PX",
                   &options.tracks.follow_tolerance_px);
  // The shared meaning of --boundary-band: here the region is the occlusion boundary's (the
  // rendered band widened to PX).
  parser.AddOption("boundary-band", "PX",
                   "boundary features: within PX pixels of the region's edge (either side)",
                   &options.band_px);
  parser.AddOption("min-track-length", "N", "shorter tracks are not judged follow/slide",
                   &options.tracks.min_track_length);
  parser.AddFlag("no-remap", "skip the mappings without boundary or sliding tracks", &no_remap);
  comic::apps::AddThreadsFlag(parser, &options.num_threads);
  comic::apps::AddOutputFolderFlag(parser, &out_dir);
  comic::apps::AddQuietFlag(parser, &quiet);
  parser.AddEpilog(
      "Outputs in DIR: boundary_benchmark.md, boundary_benchmark.csv, boundary_benchmark.json.\n"
      "Example (docs/rendered_benchmark.md; scripts/rendered_benchmark.sh runs it all):\n"
      "  comic_render scenes/orbit_object.json --photos PHOTOS -o out/orbit\n"
      "  comic_render_eval out/orbit --detectors harris,comic,comic+hessian -o out/orbit_eval");
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  if (!detectors.empty()) {
    options.detectors = comic::frontend::ParseDetectorList(detectors);
  } else {
    options.detectors = comic::frontend::DetectorNames();
    options.detectors.push_back("comic+hessian");
  }
  options.without_boundary_tracks = options.without_sliding_tracks = !no_remap;
  comic::apps::CheckThreadCount("--threads", options.num_threads);
  options.sequence.Check();
  const sfm::TrackerSettings tracker_settings = comic::apps::ToTrackerSettings(tracker, parser);
  tracker_settings.ToTrackerOptions();  // bad flags fail before any work
  options.Check();
  io::CheckOutputsAvoidInputs({{"--output", out_dir}}, {{"RENDERED", folder}});
  io::CheckCreatableFolder(out_dir);

  // The tracker as comic_sfm sets it up for these frames (video or image set), and its mapper
  // defaults for known intrinsics: two-view tracks left out of video.
  const io::RenderedTruth truth = io::OpenRenderedTruth(folder);
  const io::ImageSequence sequence =
      io::ImageSequence::Open(truth.ImagesFolder(), options.sequence);
  const comic::frontend::PairingChoice pairing =
      sfm::ChooseRunPairing(matching, tracker_settings, sequence);
  options.reconstruction.tracker =
      sfm::TrackerOptionsForRun(tracker_settings, pairing, static_cast<int>(sequence.NumFrames()));
  options.reconstruction.mapper.mapper.ignore_two_view_tracks =
      options.reconstruction.tracker.match_window <= 1;
  options.Check();

  io::StagedFolder out(out_dir);
  const sfm::RenderedBenchmark result =
      sfm::RunRenderedBenchmark(folder, options, [&](const std::string& message) {
        if (!quiet) std::cout << "comic_render_eval: " << message << std::endl;
      });
  const io::ReportTable table = result.Table();
  io::WriteFileAtomically(io::JoinPaths(out.path(), "boundary_benchmark.md"), table.ToMarkdown());
  io::WriteFileAtomically(io::JoinPaths(out.path(), "boundary_benchmark.csv"), table.ToCsv());
  nlohmann::json json = result.ToJson();
  json["matching"] = comic::frontend::PairingName(pairing.chosen);
  io::WriteFileAtomically(io::JoinPaths(out.path(), "boundary_benchmark.json"),
                          json.dump(2) + "\n");
  out.Commit();
  std::cout << table.ToMarkdown();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  comic::io::InstallInterruptCleanup();
  return comic::apps::RunMain("comic_render_eval", [&] { return Run(argc, argv); });
}
