#include "sfm/run/reconstruction_run.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>

#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/protected_inputs.h"
#include "io/core/staged_folder.h"
#include "io/image/frame_export.h"
#include "sfm/run/run_outputs.h"

namespace comic::sfm {

namespace {

// Where a run writes: --output's staging folder, and a --write-frames folder outside it.
class RunOutputFolders {
 public:
  RunOutputFolders(const ReconstructionRunOptions& options, const RunInputs& inputs) {
    if (!options.output.empty()) out_ = std::make_unique<io::StagedFolder>(options.output);
    // A video's frames as files: asked for, or needed by COLMAP for the database.
    std::string frames = options.write_frames;
    if (frames.empty() && inputs.sequence->IsVideo() && !options.colmap.colmap_db.empty()) {
      frames = kFramesInOutput;
    }
    if (frames == kFramesInOutput) {
      COMIC_CHECK(out_ != nullptr, kInvalidArgument,
                  "--colmap-db on a video needs --output or --write-frames DIR (COLMAP reads the "
                  "frames as image files)");
      frames_staging_ = io::JoinPaths(out_->path(), "images");
      frames_target_ = io::JoinPaths(options.output, "images");
    } else if (!frames.empty()) {
      frames_out_ = std::make_unique<io::StagedFolder>(frames);
      frames_staging_ = frames_out_->path();
      frames_target_ = frames;
    }
  }

  bool writes() const { return out_ != nullptr; }
  const io::StagedFolder& out() const { return *out_; }
  // The folder of `detector`'s outputs: --output, or --output/<detector>/ with --compare.
  std::string DetectorFolder(const ReconstructionRunOptions& options,
                             const std::string& detector) const {
    return options.compare ? io::JoinPaths(out_->path(), detector) : out_->path();
  }
  const std::string& frames_staging() const { return frames_staging_; }
  const std::string& frames_target() const { return frames_target_; }

  // Runs `body`, which writes into the staging folders; an error it throws (a full disk) names
  // the user's folders, not the staging ones (issue 29).
  void NamingTargets(const std::function<void()>& body) const {
    const auto in_frames = [&] { frames_out_ ? frames_out_->NamingTarget(body) : body(); };
    if (out_) {
      out_->NamingTarget(in_frames);
    } else {
      in_frames();
    }
  }

  void Commit() {
    if (out_) out_->Commit();
    if (frames_out_) frames_out_->Commit();
  }

 private:
  std::unique_ptr<io::StagedFolder> out_;
  std::unique_ptr<io::StagedFolder> frames_out_;  // a --write-frames folder outside --output
  std::string frames_staging_;                    // where the frames are written
  std::string frames_target_;                     // where they will be after the commit
};

// The absolute path, ".." and symlinks of its existing part resolved, without a trailing '/'.
std::filesystem::path NormalPath(const std::string& path) {
  std::error_code ec;
  std::filesystem::path normal =
      std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  if (ec) normal = std::filesystem::absolute(path).lexically_normal();
  return normal.filename().empty() ? normal.parent_path() : normal;
}

// `path` is `folder` or lies inside it: by device and inode where `folder` exists
// (io::IsSameOrInside), by name where it does not yet (the --output of a first run).
bool IsSameOrInsideFolder(const std::string& path, const std::string& folder) {
  if (io::IsSameOrInside(path, folder)) return true;
  const std::filesystem::path inner = NormalPath(path);
  const std::filesystem::path outer = NormalPath(folder);
  auto part = inner.begin();
  for (const std::filesystem::path& component : outer) {
    if (part == inner.end() || *part != component) return false;
    ++part;
  }
  return true;
}

// Where --colmap-db is written: inside --output, at its place in the staging folder (it moves
// into place with the other outputs, and --output may not exist yet; its folder is created
// there); elsewhere where it was asked for.
std::string DatabaseWritePath(const ReconstructionRunOptions& options,
                              const RunOutputFolders& folders) {
  if (!folders.writes() || !DatabaseInsideOutput(options)) return options.colmap.colmap_db;
  const std::filesystem::path relative =
      NormalPath(options.colmap.colmap_db).lexically_relative(NormalPath(options.output));
  const std::string path = io::JoinPaths(folders.out().path(), relative.generic_string());
  io::EnsureWritableDirectory(io::ParentPath(path));
  return path;
}

// --write-frames is for a video; a folder's images are COLMAP's already.
void CheckFramesOption(const ReconstructionRunOptions& options, const RunInputs& inputs) {
  COMIC_CHECK(options.write_frames.empty() || inputs.sequence->IsVideo(), kInvalidArgument,
              "--write-frames: " << options.frames
                                 << " is a folder of images already (COLMAP reads them there); "
                                    "--write-frames is for a video");
}

// Each detector in turn: its run, then its outputs.
void RunDetectors(const ReconstructionRunOptions& options, const RunOutputFolders& folders,
                  const RunCallbacks& callbacks, ReconstructionRunResult* result) {
  for (const std::string& detector : options.DetectorList()) {
    result->runs.push_back(
        RunDetector(detector, options, result->inputs, folders.writes(), callbacks));
    if (folders.writes()) {
      WriteDetectorOutputs(result->runs.back(), options, result->inputs,
                           folders.DetectorFolder(options, detector));
    }
  }
}

// --compare: one table of the runs.
void CompareDetectors(const ReconstructionRunOptions& options, const RunOutputFolders& folders,
                      ReconstructionRunResult* result) {
  if (!options.compare) return;
  result->comparison = ComparisonTable(result->runs);
  if (folders.writes()) {
    WriteComparisonOutputs(*result->comparison, result->runs, options, result->inputs,
                           folders.out().path());
  }
}

void WriteFrames(const RunOutputFolders& folders, const RunCallbacks& callbacks,
                 ReconstructionRunResult* result) {
  if (folders.frames_staging().empty()) return;
  if (callbacks.stage_started) callbacks.stage_started(RunStage::kWritingFrames, "");
  io::WriteSequenceFrames(*result->inputs.sequence, folders.frames_staging(), callbacks.frame_done);
  result->frames_folder = folders.frames_target();
}

// --colmap-db and --compare-colmap, on a single detector's model; --compare-colmap-sift, COLMAP's
// own pipeline on the frames, whatever became of ours.
void HandToColmap(const ReconstructionRunOptions& options, const RunOutputFolders& folders,
                  ReconstructionRunResult* result) {
  if (options.compare) return;
  if (options.compare_colmap_sift) {
    result->colmap_pipeline =
        RunColmapPipelineBeside(result->runs.front(), options, result->inputs, folders.out());
  }
  if (!result->runs.front().success()) return;
  const DetectorRun& run = result->runs.front();
  if (!options.colmap.colmap_db.empty()) {
    const std::string image_path =
        result->inputs.sequence->IsVideo() ? folders.frames_target() : options.frames;
    result->colmap_database = WriteRunColmapDatabase(run, options, result->inputs, image_path,
                                                     DatabaseWritePath(options, folders));
  }
  if (options.compare_colmap) {
    result->colmap_comparison = CompareRunWithColmap(run, options, result->inputs, folders.out());
  }
}

// The error line of a single detector's run that found no model (which check failed,
// by how much, and what to try).
std::string FailureLine(const ReconstructionRunOptions& options,
                        const ReconstructionRunResult& result) {
  if (options.compare) return "";
  const DetectorRun& run = result.runs.front();
  // The error line is a failed run's last line: it names the page too.
  const std::string report = options.output.empty()
                                 ? std::string()
                                 : " (report: " + io::JoinPaths(options.output, "report.json") +
                                       ", page: " + run.page_path + ")";
  if (run.success() && run.report.self_check.suspect) {
    // A model its own frame pairs contradict is written but never passed off as a result.
    return "suspect model: " + run.report.self_check.reason +
           " (every model is written; compare it with ground truth or try the other --matcher)" +
           report;
  }
  if (run.success()) {
    if (run.RegistersAtLeast(options.min_registered)) return "";
    // --min-registered: a partial model too small for the caller; its models are written.
    return "partial: the largest model holds " +
           std::to_string(std::lround(100.0 * run.report.registered_fraction)) +
           " % of the frames, --min-registered asks for " +
           std::to_string(std::lround(100.0 * options.min_registered)) +
           " % (every model is written; the unregistered frames and why: " +
           DescribeUnregisteredRanges(run.report.unregistered_ranges) + ")" + report;
  }
  const ReconstructionDiagnosis& diagnosis = run.diagnosis;
  return diagnosis.message + "; try " + diagnosis.suggestion + report;
}

}  // namespace

std::vector<io::NamedPath> RunInputPaths(const ReconstructionRunOptions& options) {
  return {{"FRAMES", options.frames},
          {"--gt", options.gt},
          {"--intrinsics", options.camera.intrinsics},
          {"--regions", options.regions},
          {"--masks", options.masks}};
}

void CheckRunOptions(const ReconstructionRunOptions& options) {
  options.Check();
  // Inputs are sacred (issue 29: `-o FRAMES` left trajectory.png among the frames).
  io::CheckOutputsAvoidInputs(
      {{"--output", options.output},
       {"--colmap-db", options.colmap.colmap_db},
       {"--write-frames", options.write_frames == kFramesInOutput ? "" : options.write_frames},
       {"--cache", options.cache}},
      RunInputPaths(options));
  io::CheckWrittenPathsAvoidInputs(RunWrittenPaths(options), RunInputPaths(options));
  CheckColmapOutputs(options);
  // --output is replaced as a whole when a run commits: a cache in it would be lost (or, being
  // --output itself, would lose the outputs).
  COMIC_CHECK(options.cache.empty() || options.output.empty() ||
                  !IsSameOrInsideFolder(options.cache, options.output),
              kInvalidArgument,
              "--cache " << options.cache << " is, or lies inside, --output " << options.output
                         << ", which each run replaces: keep the cache beside it (e.g. --cache "
                         << io::JoinPaths(io::ParentPath(options.output), "cache") << ")");
  // The cache is optional: a folder that cannot be written only costs keeping the tracks (a
  // warning), and a read-only one holding them is read; a path that can never be a folder is an
  // error of the command line.
  if (!options.cache.empty()) io::CheckFolderPath(options.cache);
  // Validate, then write, all or nothing: --output is checked but not created; the outputs go to
  // a staging folder beside it and move into place when the run is complete.
  if (!options.output.empty()) io::CheckCreatableFolder(options.output);
}

ReconstructionRunResult RunReconstruction(const ReconstructionRunOptions& options,
                                          const RunCallbacks& callbacks) {
  CheckRunOptions(options);
  ReconstructionRunResult result;
  result.inputs = ResolveRunInputs(options);
  CheckFramesOption(options, result.inputs);
  // A frame name no COLMAP model can hold fails now, not after the reconstruction (issue 29).
  for (const std::string& name : result.inputs.sequence->FrameNames()) {
    io::CheckColmapImageName(name, options.frames);
  }
  if (callbacks.inputs_resolved) callbacks.inputs_resolved(result.inputs);
  RunOutputFolders folders(options, result.inputs);
  folders.NamingTargets([&] {
    RunDetectors(options, folders, callbacks, &result);
    CompareDetectors(options, folders, &result);
    WriteFrames(folders, callbacks, &result);
    HandToColmap(options, folders, &result);
  });
  // A failed reconstruction commits its report.json (the documented exception): it says why.
  folders.Commit();
  result.failure = FailureLine(options, result);
  return result;
}

}  // namespace comic::sfm
