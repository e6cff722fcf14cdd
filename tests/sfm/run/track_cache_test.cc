// The track cache (--cache): its key follows the frames, the detector and the tracker and not the
// mapper; a re-run from the cache writes the same model files byte for byte without detecting; a
// changed tracker or detector option makes a second file; a corrupt file is tracked again with a
// warning; a cache among the inputs or in --output is refused before any work. The cache is
// optional: a failed write warns and leaves nothing behind, forged or non-regular files are
// recomputed with a warning, and a read-only cache holding the file is read.
#include "sfm/run/track_cache.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "frontend/feature_masks.h"
#include "frontend/matching/track_file.h"
#include "io/core/content_hash.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "sfm/run/reconstruction_run.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

namespace fs = std::filesystem;
using comic::test::ExampleDir;
using comic::test::ScopedTempDir;

// The first `count` example frames copied into `dir`/frames.
std::string CopyFrames(const ScopedTempDir& dir, int count) {
  const std::string frames = dir.File("frames");
  fs::create_directories(frames);
  const std::vector<std::string> names = io::ListFiles(ExampleDir() + "/image_l");
  for (int i = 0; i < count; ++i) {
    fs::copy_file(ExampleDir() + "/image_l/" + names[i], frames + "/" + names[i]);
  }
  return frames;
}

uint64_t KeyOf(const std::string& frames, const frontend::DetectorOptions& detector,
               const SequenceReconstructionOptions& options, int first = 0) {
  io::ImageSequenceOptions sequence_options;
  sequence_options.first_frame = first;
  return TrackCacheKey(detector, options, io::ImageSequence::Open(frames, sequence_options));
}

TEST(TrackCacheKey, FollowsTheFramesTheDetectorAndTheTrackerNotTheMapper) {
  ScopedTempDir dir;
  const std::string frames = CopyFrames(dir, 3);
  frontend::DetectorOptions detector;
  detector.name = "harris";
  const SequenceReconstructionOptions options;
  const uint64_t key = KeyOf(frames, detector, options);
  EXPECT_EQ(KeyOf(frames, detector, options), key);  // stable

  SequenceReconstructionOptions mapper = options;
  mapper.mapper.local_ba_num_images = 9;
  mapper.mapper.mapper.init_tri_angle_deg = 7.0;
  mapper.match_seams = false;
  EXPECT_EQ(KeyOf(frames, detector, mapper), key);
  frontend::DetectorOptions threads = detector;
  threads.comic.num_threads = 3;  // no output depends on a thread count
  EXPECT_EQ(KeyOf(frames, threads, options), key);

  frontend::DetectorOptions harris = detector;
  harris.harris.k = 0.05;
  EXPECT_NE(KeyOf(frames, harris, options), key);
  frontend::DetectorOptions pyramid = detector;
  pyramid.scale_space.level_factor = 3.0;  // with one level the factor changes nothing
  EXPECT_EQ(KeyOf(frames, pyramid, options), key);
  pyramid.scale_space.num_levels = 3;
  const uint64_t three_levels = KeyOf(frames, pyramid, options);
  EXPECT_NE(three_levels, key);
  pyramid.scale_space.duplicate_radius_px = 2.0;
  EXPECT_NE(KeyOf(frames, pyramid, options), three_levels);
  frontend::DetectorOptions fast = detector;
  fast.name = "fast";
  EXPECT_NE(KeyOf(frames, fast, options), key);
  SequenceReconstructionOptions tracker = options;
  tracker.tracker.matcher.max_cost = std::nextafter(tracker.tracker.matcher.max_cost, 1e9);
  EXPECT_NE(KeyOf(frames, detector, tracker), key);  // one bit of one double
  SequenceReconstructionOptions image_set = options;
  image_set.image_set.emplace();
  EXPECT_NE(KeyOf(frames, detector, image_set), key);
  EXPECT_NE(KeyOf(frames, detector, options, 1), key);  // other frames
  // Masks of moving objects decide which features exist (issue 47): their pixels and their
  // convention are in the key.
  const cv::Size size = io::ImageSequence::Open(frames).FrameSize();
  std::vector<cv::Mat> object(3, cv::Mat(size, CV_8UC1, cv::Scalar(0)));
  object[1] = cv::Mat(size, CV_8UC1, cv::Scalar(0));
  object[1](cv::Rect(10, 10, 40, 30)).setTo(255);
  SequenceReconstructionOptions masked = options;
  masked.feature_masks =
      std::make_shared<const frontend::FeatureMasks>(object, frontend::FeatureMaskOptions());
  const uint64_t masked_key = KeyOf(frames, detector, masked);
  EXPECT_NE(masked_key, key);
  SequenceReconstructionOptions colmap_convention = options;
  frontend::FeatureMaskOptions keeps_nonzero;
  keeps_nonzero.drop_nonzero = false;
  colmap_convention.feature_masks =
      std::make_shared<const frontend::FeatureMasks>(object, keeps_nonzero);
  EXPECT_NE(KeyOf(frames, detector, colmap_convention), masked_key);
  object[1](cv::Rect(10, 10, 41, 30)).setTo(255);  // one more column
  SequenceReconstructionOptions moved = options;
  moved.feature_masks =
      std::make_shared<const frontend::FeatureMasks>(object, frontend::FeatureMaskOptions());
  EXPECT_NE(KeyOf(frames, detector, moved), masked_key);

  // The same names with other bytes: another key.
  const std::string first = frames + "/" + io::ListFiles(frames).front();
  std::string bytes = io::ReadFileToString(first);
  bytes += "trailing bytes the PNG decoder ignores";
  io::WriteFileAtomically(first, bytes);
  EXPECT_NE(KeyOf(frames, detector, options), key);
}

TEST(TrackCacheKey, TextNamesEverySetting) {
  ScopedTempDir dir;
  const std::string frames = CopyFrames(dir, 2);
  frontend::DetectorOptions detector;
  detector.name = "comic+hessian";
  const std::string text =
      TrackCacheKeyText(detector, SequenceReconstructionOptions(), io::ImageSequence::Open(frames));
  for (const char* line :
       {"detector=comic+hessian\n", "comic.presmoothing_sigma=1.25\n", "hessian.sigma=2\n",
        "tracker.matcher.max_cost=400\n", "tracker.continuation.alignment.levels=3\n",
        "frames.size=1226x370\n", "frame=000001.png "}) {
    EXPECT_NE(text.find(line), std::string::npos) << line << " not in\n" << text;
  }
  EXPECT_EQ(text.find("harris."), std::string::npos);       // only the detectors run
  EXPECT_EQ(text.find("scale_space."), std::string::npos);  // one level: no pyramid
  EXPECT_EQ(TrackCacheFile("c", "harris", 0xabcull), "c/tracks-harris-0000000000000abc.bin");
}

ReconstructionRunOptions FiveFrames(const ScopedTempDir& dir) {
  ReconstructionRunOptions options;
  options.frames = ExampleDir() + "/image_l";
  options.gt = ExampleDir() + "/poses.txt";
  options.sequence.last_frame = 4;
  options.cache = dir.File("cache");
  options.model_format = "both";
  return options;
}

// What a run reported: whether the tracking stage ran, frames tracked, warnings.
struct Events {
  int tracking = 0;
  int from_cache = 0;
  int frames_done = 0;
  std::vector<std::string> warnings;

  RunCallbacks Callbacks() {
    RunCallbacks callbacks;
    callbacks.stage_started = [this](RunStage stage, const std::string&) {
      if (stage == RunStage::kTracking) ++tracking;
      if (stage == RunStage::kTracksFromCache) ++from_cache;
    };
    callbacks.frame_done = [this](size_t, size_t) { ++frames_done; };
    callbacks.warning = [this](const std::string& message) { warnings.push_back(message); };
    return callbacks;
  }
};

std::vector<std::string> CacheFiles(const ReconstructionRunOptions& options) {
  return io::ListFiles(options.cache);
}

// The model files of a run, every byte.
std::vector<std::string> ModelBytes(const std::string& output) {
  std::vector<std::string> bytes;
  for (const char* name :
       {"cameras.txt", "images.txt", "points3D.txt", "points.ply", "sparse/0/cameras.bin",
        "sparse/0/images.bin", "sparse/0/points3D.bin"}) {
    bytes.push_back(io::ReadFileToString(io::JoinPaths(output, name)));
    EXPECT_FALSE(bytes.back().empty()) << name;
  }
  return bytes;
}

TEST(TrackCache, AReRunReadsTheTracksAndWritesTheSameModel) {
  ScopedTempDir dir;
  ReconstructionRunOptions options = FiveFrames(dir);
  options.output = dir.File("first");
  Events first;
  const ReconstructionRunResult made = RunReconstruction(options, first.Callbacks());
  ASSERT_TRUE(made.success()) << made.failure;
  EXPECT_EQ(first.tracking, 1);
  EXPECT_EQ(first.frames_done, 5);
  EXPECT_FALSE(made.runs.front().track_cache.from_cache);
  EXPECT_EQ(made.runs.front().report_json["tracks_from_cache"], false);
  ASSERT_EQ(CacheFiles(options).size(), 1u);
  EXPECT_EQ(io::FileName(made.runs.front().track_cache.file), CacheFiles(options).front());

  options.output = dir.File("second");
  Events second;
  const ReconstructionRunResult reused = RunReconstruction(options, second.Callbacks());
  ASSERT_TRUE(reused.success()) << reused.failure;
  EXPECT_EQ(second.tracking, 0);  // nothing detected or tracked
  EXPECT_EQ(second.from_cache, 1);
  EXPECT_EQ(second.frames_done, 0);
  EXPECT_TRUE(second.warnings.empty());
  const nlohmann::json& report = reused.runs.front().report_json;
  EXPECT_EQ(report["tracks_from_cache"], true);
  EXPECT_EQ(report["track_cache"]["file"], made.runs.front().track_cache.file);
  EXPECT_EQ(report["track_building"], made.runs.front().report_json["track_building"]);
  EXPECT_EQ(ModelBytes(dir.File("second")), ModelBytes(dir.File("first")));
  EXPECT_EQ(CacheFiles(options).size(), 1u);
}

TEST(TrackCache, OtherTrackerOrDetectorOptionsMakeAnotherFileMapperOptionsDoNot) {
  ScopedTempDir dir;
  ReconstructionRunOptions options = FiveFrames(dir);
  Events events;
  RunReconstruction(options, events.Callbacks());
  ASSERT_EQ(CacheFiles(options).size(), 1u);

  ReconstructionRunOptions mapper = options;
  mapper.init_angle = 3.0;
  mapper.local_ba_images = 4;
  mapper.min_registered = 0.2;
  EXPECT_TRUE(RunReconstruction(mapper).runs.front().track_cache.from_cache);
  EXPECT_EQ(CacheFiles(options).size(), 1u);

  ReconstructionRunOptions tracker = options;
  tracker.tracker.Give("max-features", [](frontend::TrackerOptions& o) { o.max_features = 1500; });
  EXPECT_FALSE(RunReconstruction(tracker).runs.front().track_cache.from_cache);
  EXPECT_EQ(CacheFiles(options).size(), 2u);

  ReconstructionRunOptions detector = options;
  detector.detector_options.harris.integration_sigma = 2.5;
  EXPECT_FALSE(RunReconstruction(detector).runs.front().track_cache.from_cache);
  EXPECT_EQ(CacheFiles(options).size(), 3u);
  EXPECT_TRUE(RunReconstruction(detector).runs.front().track_cache.from_cache);
}

TEST(TrackCache, ACorruptFileIsTrackedAgainWithAWarning) {
  ScopedTempDir dir;
  ReconstructionRunOptions options = FiveFrames(dir);
  const ReconstructionRunResult made = RunReconstruction(options);
  const std::string file = made.runs.front().track_cache.file;
  const std::string bytes = io::ReadFileToString(file);
  io::WriteFileAtomically(file, bytes.substr(0, bytes.size() / 2));

  Events events;
  const ReconstructionRunResult again = RunReconstruction(options, events.Callbacks());
  ASSERT_TRUE(again.success());
  EXPECT_EQ(events.tracking, 1);
  ASSERT_EQ(events.warnings.size(), 1u);
  EXPECT_NE(events.warnings.front().find(file + ": track file is truncated or corrupt"),
            std::string::npos)
      << events.warnings.front();
  EXPECT_NE(events.warnings.front().find("detecting and tracking again"), std::string::npos);
  EXPECT_EQ(again.runs.front().report_json["track_cache"]["warning"], events.warnings.front());
  EXPECT_EQ(io::ReadFileToString(file), bytes);  // replaced by the same tracks
  EXPECT_TRUE(RunReconstruction(options).runs.front().track_cache.from_cache);
}

TEST(TrackCache, RefusedAmongTheInputsAndInTheOutput) {
  ScopedTempDir dir;
  const auto refusal = [](const ReconstructionRunOptions& options) -> std::string {
    try {
      CheckRunOptions(options);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
      return e.what();
    }
    return "";
  };
  ReconstructionRunOptions options = FiveFrames(dir);
  options.cache = options.frames + "/cache";
  EXPECT_NE(refusal(options).find("--cache lies inside the input FRAMES"), std::string::npos)
      << refusal(options);
  options.output = dir.File("out");  // not there yet
  for (const std::string& cache : {dir.File("out"), dir.File("out/cache"), dir.File("out/")}) {
    options.cache = cache;
    EXPECT_NE(refusal(options).find("lies inside, --output"), std::string::npos) << cache;
  }
  fs::create_directories(dir.File("out"));
  options.cache = dir.File("out/../out/cache");
  EXPECT_NE(refusal(options).find("which each run replaces"), std::string::npos);
  options.cache = dir.File("cache");  // beside it
  EXPECT_EQ(refusal(options), "");
  EXPECT_FALSE(io::PathExists(options.cache));  // checked, not created
}

// The tracks as (frame, feature) pairs, to compare two trackings.
std::vector<std::vector<std::pair<int, int>>> Observations(const SequenceTracking& tracking) {
  std::vector<std::vector<std::pair<int, int>>> tracks;
  for (const frontend::Track& track : tracking.tracks.tracks) {
    tracks.emplace_back();
    for (const frontend::TrackObservation& obs : track.observations) {
      tracks.back().emplace_back(obs.frame, obs.feature);
    }
  }
  return tracks;
}

// The cache without the mapping: the first three example frames, Harris, default tracking.
struct ThreeFrames {
  io::ImageSequence sequence = [] {
    io::ImageSequenceOptions options;
    options.last_frame = 2;
    return io::ImageSequence::Open(ExampleDir() + "/image_l", options);
  }();
  frontend::DetectorOptions detector_options = [] {
    frontend::DetectorOptions options;
    options.name = "harris";
    return options;
  }();
  std::unique_ptr<frontend::Detector> detector = frontend::MakeDetector(detector_options);
  SequenceReconstructionOptions options;
  int tracked = 0;  // how many times the frames were tracked, not read

  SequenceTracking Track(const std::string& folder, TrackCacheUse* use) {
    return TrackFramesThroughCache(
        folder, detector_options, *detector, sequence, options, [this] { ++tracked; }, {}, use);
  }
};

// A full disk (here: a file size limit, which fails the write as ENOSPC would) while the cache
// file is written: a warning, the tracks returned, and neither the file nor the folders the write
// created left behind.
TEST(TrackCache, AWriteFailureWarnsAndGoesOnLeavingNothing) {
  ScopedTempDir dir;
  ThreeFrames run;
  const std::string folder = dir.File("new/cache");
  TrackCacheUse use;
  struct rlimit saved;
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto saved_handler = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
  struct rlimit limit = saved;
  limit.rlim_cur = 1024;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
  SequenceTracking tracking;
  std::string error;
  try {
    tracking = run.Track(folder, &use);
  } catch (const std::exception& e) {
    error = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, saved_handler);
  ASSERT_EQ(error, "");
  EXPECT_EQ(run.tracked, 1);
  EXPECT_EQ(tracking.tracks.NumFrames(), 3u);
  EXPECT_FALSE(tracking.tracks.tracks.empty());
  EXPECT_FALSE(use.from_cache);
  EXPECT_NE(use.warning.find(use.file), std::string::npos) << use.warning;
  EXPECT_NE(use.warning.find("the tracks are not kept in --cache, the run goes on"),
            std::string::npos)
      << use.warning;
  EXPECT_EQ(use.warning.find('\n'), std::string::npos) << use.warning;
  EXPECT_FALSE(io::PathExists(dir.File("new")));  // no empty folder, no partial file
  // Without the limit the same call keeps them.
  EXPECT_EQ(Observations(run.Track(folder, &use)), Observations(tracking));
  EXPECT_EQ(use.warning, "");
  EXPECT_EQ(io::ListFiles(folder).size(), 1u);
}

// A folder that existed before keeps existing (only what the failed write made is removed).
TEST(TrackCache, AFailedWriteRemovesOnlyTheFoldersItMade) {
  ScopedTempDir dir;
  ThreeFrames run;
  fs::create_directories(dir.File("cache"));
  io::WriteFileAtomically(dir.File("cache/other.txt"), "kept\n");
  TrackCacheUse use;
  // The cache file's name taken by a folder: the rename fails.
  run.Track(dir.File("cache"), &use);
  ASSERT_EQ(use.warning, "");
  fs::remove(use.file);
  fs::create_directories(use.file + "/inside");
  run.Track(dir.File("cache"), &use);
  EXPECT_NE(use.warning.find("the run goes on"), std::string::npos) << use.warning;
  EXPECT_TRUE(io::IsDirectory(use.file + "/inside"));
  EXPECT_EQ(io::ReadFileToString(dir.File("cache/other.txt")), "kept\n");
}

// Files a hand or a tool made, with a valid checksum: treated as a miss, with a warning, tracked
// again and replaced; the next run reads the replacement.
TEST(TrackCache, ForgedFilesAreTrackedAgainAndReplaced) {
  ScopedTempDir dir;
  ThreeFrames run;
  const std::string folder = dir.File("cache");
  TrackCacheUse use;
  const SequenceTracking first = run.Track(folder, &use);
  const std::string file = use.file;
  const std::string good = io::ReadFileToString(file);
  frontend::TrackFile decoded = frontend::DecodeTrackFile(good, file);
  ASSERT_FALSE(decoded.tracks.features[0].empty());

  std::vector<std::pair<std::string, std::string>> forgeries;  // bytes, words of the warning
  frontend::TrackFile nan_position = decoded;
  nan_position.tracks.features[0][0].x = std::numeric_limits<float>::quiet_NaN();
  forgeries.push_back({frontend::EncodeTrackFile(nan_position), "feature position nan"});
  frontend::TrackFile inf_position = decoded;
  inf_position.tracks.features[1][0].y = std::numeric_limits<float>::infinity();
  forgeries.push_back({frontend::EncodeTrackFile(inf_position), "inf"});
  // Descriptors of 2^31 - 1 rows behind a valid checksum (a 256 GB matrix if allocated).
  frontend::TrackFile described = decoded;
  for (const frontend::FeatureSet& frame : described.tracks.features) {
    described.tracks.descriptors.push_back(
        cv::Mat(static_cast<int>(frame.size()), 128, CV_8UC1, cv::Scalar(7)));
  }
  std::string huge = frontend::EncodeTrackFile(described);
  const int32_t rows = static_cast<int32_t>(decoded.tracks.features[0].size());
  const int32_t columns = 128;
  const std::string size = std::string(reinterpret_cast<const char*>(&rows), 4) +
                           std::string(reinterpret_cast<const char*>(&columns), 4) +
                           std::string(4, '\7');
  const size_t at = huge.find(size);
  ASSERT_NE(at, std::string::npos);
  const int32_t max_rows = std::numeric_limits<int32_t>::max();
  std::memcpy(huge.data() + at, &max_rows, 4);
  const uint64_t checksum = io::HashBytes(huge.substr(0, huge.size() - 8));
  std::memcpy(huge.data() + huge.size() - 8, &checksum, 8);
  forgeries.push_back({huge, "descriptors: 2147483647 x 128"});

  for (const auto& [bytes, words] : forgeries) {
    SCOPED_TRACE(words);
    io::WriteFileAtomically(file, bytes);
    const int tracked = run.tracked;
    const SequenceTracking again = run.Track(folder, &use);
    EXPECT_FALSE(use.from_cache);
    EXPECT_EQ(run.tracked, tracked + 1);
    EXPECT_EQ(Observations(again), Observations(first));
    EXPECT_NE(use.warning.find(file + ": track file is"), std::string::npos) << use.warning;
    EXPECT_NE(use.warning.find(words), std::string::npos) << use.warning;
    EXPECT_NE(use.warning.find("detecting and tracking again"), std::string::npos);
    EXPECT_EQ(io::ReadFileToString(file), good);  // replaced
  }
  run.Track(folder, &use);
  EXPECT_TRUE(use.from_cache);
}

// A link to /dev/zero, or a FIFO, in the cache file's place: not read (no endless read, no
// wait), a warning, tracked again, and the entry replaced by the real file.
TEST(TrackCache, ANonRegularCacheFileIsNotRead) {
  ScopedTempDir dir;
  ThreeFrames run;
  const std::string folder = dir.File("cache");
  TrackCacheUse use;
  run.Track(folder, &use);
  const std::string file = use.file;
  const std::string good = io::ReadFileToString(file);
  for (const std::string kind : {"link", "fifo"}) {
    SCOPED_TRACE(kind);
    fs::remove(file);
    if (kind == "link") {
      fs::create_symlink("/dev/zero", file);
    } else {
      ASSERT_EQ(::mkfifo(file.c_str(), 0644), 0);
    }
    run.Track(folder, &use);
    EXPECT_FALSE(use.from_cache);
    EXPECT_NE(use.warning.find(file + ": not a regular file"), std::string::npos) << use.warning;
    EXPECT_NE(use.warning.find("detecting and tracking again"), std::string::npos);
    EXPECT_FALSE(fs::is_symlink(fs::symlink_status(file)));
    EXPECT_EQ(io::ReadFileToString(file), good);
  }
}

// A read-only cache folder holding the right file: accepted up front and read. (As root, where
// permissions do not hold, the run is the same.)
TEST(TrackCache, AReadOnlyCacheHoldingTheTracksIsRead) {
  ScopedTempDir dir;
  ReconstructionRunOptions options = FiveFrames(dir);
  options.output = dir.File("first");
  ASSERT_TRUE(RunReconstruction(options).success());
  fs::permissions(options.cache, fs::perms::owner_read | fs::perms::owner_exec);
  options.output = dir.File("second");
  EXPECT_NO_THROW(CheckRunOptions(options));
  Events events;
  const ReconstructionRunResult again = RunReconstruction(options, events.Callbacks());
  fs::permissions(options.cache, fs::perms::owner_all);
  ASSERT_TRUE(again.success()) << again.failure;
  EXPECT_EQ(events.from_cache, 1);
  EXPECT_EQ(events.tracking, 0);
  EXPECT_TRUE(events.warnings.empty());
  // A cache path that can never be a folder is still refused before any work.
  options.cache = options.frames + "/000000.png/cache";
  EXPECT_THROW(CheckRunOptions(options), Error);
}

}  // namespace
}  // namespace comic::sfm
