#include "sfm/run/track_cache.h"

#include <chrono>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>
#include <vector>

#include "frontend/combined_detector.h"
#include "frontend/matching/track_file.h"
#include "io/core/content_hash.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/version.h"

namespace comic::sfm {

namespace {

// A tripwire, not a proof: a field added to one of these structs changes its size (unless it
// fits in padding), and this build stops until the field is added to the key below; otherwise a
// cache made with the old value would be reused with the new one. Sizes of x86-64 with libstdc++
// (gcc and clang alike); other platforms skip the check.
#if defined(__x86_64__) && defined(__GLIBCXX__)
#define COMIC_KEY_COVERS(Type, size)                               \
  static_assert(sizeof(Type) == (size), #Type                      \
                " changed: add its new fields to the track "       \
                "cache key (sfm/run/track_cache.cc), then update " \
                "this size")
COMIC_KEY_COVERS(frontend::ComicDirectDetectorOptions, 104);
COMIC_KEY_COVERS(frontend::ComicDetectorOptions, 80);
COMIC_KEY_COVERS(frontend::HarrisDetectorOptions, 40);
COMIC_KEY_COVERS(frontend::HessianDetectorOptions, 24);
COMIC_KEY_COVERS(frontend::MserDetectorOptions, 32);
COMIC_KEY_COVERS(frontend::FastDetectorOptions, 8);
COMIC_KEY_COVERS(frontend::ScaleSpaceDetectorOptions, 32);
COMIC_KEY_COVERS(frontend::DetectorOptions, 352);
COMIC_KEY_COVERS(frontend::TrackerOptions, 312);
COMIC_KEY_COVERS(frontend::PatchMatcherOptions, 80);
COMIC_KEY_COVERS(frontend::MatchVerificationOptions, 40);
COMIC_KEY_COVERS(frontend::TrackContinuationOptions, 104);
COMIC_KEY_COVERS(frontend::PatchAlignmentOptions, 56);
COMIC_KEY_COVERS(frontend::ImageSetMatchingOptions, 184);
COMIC_KEY_COVERS(frontend::DescriptorOptions, 64);
COMIC_KEY_COVERS(frontend::OrientationOptions, 24);
COMIC_KEY_COVERS(frontend::DescriptorMatchOptions, 24);
#undef COMIC_KEY_COVERS
#endif

// name=value lines; doubles (floats too, widened exactly) with 17 significant digits.
class KeyText {
 public:
  explicit KeyText(std::ostringstream* out) : out_(out) { *out_ << std::setprecision(17); }

  template <typename T>
  void Add(const std::string& name, const T& value) {
    if constexpr (std::is_enum_v<T>) {
      *out_ << name << '=' << static_cast<int>(value) << '\n';
    } else if constexpr (std::is_floating_point_v<T>) {
      *out_ << name << '=' << static_cast<double>(value) << '\n';
    } else {
      *out_ << name << '=' << value << '\n';
    }
  }

 private:
  std::ostringstream* out_;
};

#define COMIC_KEY(prefix, options, field) key.Add(std::string(prefix) + #field, (options).field)

// The options of each detector the name holds (num_threads left out: no output depends on it).
void AddDetector(const frontend::DetectorOptions& options, KeyText& key) {
  key.Add("detector", options.name);
  for (const std::string& name : frontend::SplitCombinedDetectorName(options.name)) {
    const std::string p = name + ".";
    if (name == "comic") {
      const frontend::ComicDirectDetectorOptions& o = options.comic;
      COMIC_KEY(p, o, scale);
      COMIC_KEY(p, o, delta);
      COMIC_KEY(p, o, half_length);
      COMIC_KEY(p, o, min_cornerness);
      COMIC_KEY(p, o, max_arm_rms);
      COMIC_KEY(p, o, level_radius);
      COMIC_KEY(p, o, bridge_levels);
      COMIC_KEY(p, o, link_radius);
      COMIC_KEY(p, o, level_step);
      COMIC_KEY(p, o, max_level_gap);
      COMIC_KEY(p, o, min_run_levels);
      COMIC_KEY(p, o, consensus_fraction);
      COMIC_KEY(p, o, presmoothing_sigma);
      COMIC_KEY(p, o, merge_radius);
      COMIC_KEY(p, o, min_stability);
    } else if (name == "comic-paper") {
      const frontend::ComicDetectorOptions& o = options.comic_paper;
      COMIC_KEY(p, o, scale);
      COMIC_KEY(p, o, block_size);
      COMIC_KEY(p, o, delta);
      COMIC_KEY(p, o, half_length);
      COMIC_KEY(p, o, max_iterations);
      COMIC_KEY(p, o, convergence_tolerance);
      COMIC_KEY(p, o, stop_tolerance);
      COMIC_KEY(p, o, merge_radius);
      COMIC_KEY(p, o, min_stability);
      COMIC_KEY(p, o, min_cornerness);
      COMIC_KEY(p, o, coarse_initialisation);
      COMIC_KEY(p, o, seed_neighbouring_corners);
      COMIC_KEY(p, o, skip_duplicate_paths);
    } else if (name == "harris") {
      const frontend::HarrisDetectorOptions& o = options.harris;
      COMIC_KEY(p, o, derivative_sigma);
      COMIC_KEY(p, o, integration_sigma);
      COMIC_KEY(p, o, k);
      COMIC_KEY(p, o, nms_radius);
      COMIC_KEY(p, o, border);
      COMIC_KEY(p, o, min_response);
    } else if (name == "hessian") {
      const frontend::HessianDetectorOptions& o = options.hessian;
      COMIC_KEY(p, o, sigma);
      COMIC_KEY(p, o, nms_radius);
      COMIC_KEY(p, o, border);
      COMIC_KEY(p, o, min_response);
    } else if (name == "mser") {
      const frontend::MserDetectorOptions& o = options.mser;
      COMIC_KEY(p, o, delta);
      COMIC_KEY(p, o, min_area);
      COMIC_KEY(p, o, max_area);
      COMIC_KEY(p, o, max_variation);
      COMIC_KEY(p, o, merge_radius);
    } else if (name == "fast") {
      const frontend::FastDetectorOptions& o = options.fast;
      COMIC_KEY(p, o, min_threshold);
      COMIC_KEY(p, o, nonmax_suppression);
    } else {
      // A detector added to the factory must be added here before any cache is made with it.
      throw Error(ErrorKind::kInvalidArgument,
                  "track cache: the options of detector '" + name + "' are not in the key");
    }
  }
  // The pyramid only when there is one: with one level the other fields change nothing, and the
  // keys of caches made before the pyramid existed stay as they were.
  const frontend::ScaleSpaceDetectorOptions& s = options.scale_space;
  if (s.num_levels > 1) {
    COMIC_KEY("scale_space.", s, num_levels);
    COMIC_KEY("scale_space.", s, level_factor);
    COMIC_KEY("scale_space.", s, duplicate_radius_px);
    COMIC_KEY("scale_space.", s, min_level_size);
  }
}

void AddVerification(const std::string& p, const frontend::MatchVerificationOptions& o,
                     KeyText& key) {
  COMIC_KEY(p, o, max_error_px);
  COMIC_KEY(p, o, min_num_inliers);
  COMIC_KEY(p, o, min_inlier_ratio);
  COMIC_KEY(p, o, confidence);
  COMIC_KEY(p, o, max_num_iterations);
  COMIC_KEY(p, o, random_seed);
}

void AddPatchMatcher(const std::string& p, const frontend::PatchMatcherOptions& o, KeyText& key) {
  COMIC_KEY(p, o, gate);
  COMIC_KEY(p, o, radius);
  COMIC_KEY(p, o, row_tolerance);
  COMIC_KEY(p, o, min_disparity);
  COMIC_KEY(p, o, max_disparity);
  COMIC_KEY(p, o, cost);
  COMIC_KEY(p, o, min_side_overlap);
  COMIC_KEY(p, o, min_side_fraction);
  COMIC_KEY(p, o, side_noise_sigma);
  COMIC_KEY(p, o, side_noise_from_pair);
  COMIC_KEY(p, o, like_sides_without_object);
  COMIC_KEY(p, o, max_cost);
}

void AddContinuation(const std::string& p, const frontend::TrackContinuationOptions& o,
                     KeyText& key) {
  const frontend::PatchAlignmentOptions& a = o.alignment;
  const std::string q = p + "alignment.";
  COMIC_KEY(q, a, levels);
  COMIC_KEY(q, a, window);
  COMIC_KEY(q, a, max_iterations);
  COMIC_KEY(q, a, min_step_px);
  COMIC_KEY(q, a, min_eigenvalue);
  COMIC_KEY(q, a, min_gain);
  COMIC_KEY(q, a, max_gain);
  COMIC_KEY(q, a, max_forward_backward_px);
  COMIC_KEY(p, o, max_residual);
  COMIC_KEY(p, o, min_correlation);
  COMIC_KEY(p, o, aligned_radius);
  COMIC_KEY(p, o, max_continued_frames);
  COMIC_KEY(p, o, min_separation);
  COMIC_KEY(p, o, bridge_frames);
}

void AddTracker(const frontend::TrackerOptions& o, KeyText& key) {
  const std::string p = "tracker.";
  AddPatchMatcher(p + "matcher.", o.matcher, key);
  COMIC_KEY(p, o, min_response);
  COMIC_KEY(p, o, max_features);
  COMIC_KEY(p, o, min_window_eigenvalue);
  COMIC_KEY(p, o, prediction);
  COMIC_KEY(p, o, unpredicted_radius);
  COMIC_KEY(p, o, velocity_neighbours);
  COMIC_KEY(p, o, velocity_neighbour_radius);
  COMIC_KEY(p, o, coarse_factor);
  COMIC_KEY(p, o, coarse_radius);
  COMIC_KEY(p, o, coarse_features);
  COMIC_KEY(p, o, match_window);
  COMIC_KEY(p, o, conflict_rule);
  COMIC_KEY(p, o, verify_min_gap);
  AddVerification(p + "verification.", o.verification, key);
  COMIC_KEY(p, o, match_turned_180);
  COMIC_KEY(p, o, align_patches);
  AddContinuation(p + "continuation.", o.continuation, key);
}

// num_threads left out, as the detectors'.
void AddImageSet(const frontend::ImageSetMatchingOptions& o, KeyText& key) {
  const std::string p = "image_set.";
  COMIC_KEY(p, o, min_response);
  COMIC_KEY(p, o, max_features);
  COMIC_KEY(p, o, window);
  COMIC_KEY(p, o, quadratic_overlap);
  key.Add(p + "descriptor", o.descriptor.has_value());
  if (o.descriptor) {
    const frontend::DescriptorOptions& d = *o.descriptor;
    const std::string q = p + "descriptor.";
    COMIC_KEY(q, d, sigma_per_scale);
    COMIC_KEY(q, d, curve_sigma_per_scale);
    COMIC_KEY(q, d, min_sigma);
    COMIC_KEY(q, d, max_sigma);
    COMIC_KEY(q + "orientation.", d.orientation, mode);
    COMIC_KEY(q + "orientation.", d.orientation, num_bins);
    COMIC_KEY(q + "orientation.", d.orientation, weight_sigma_factor);
    COMIC_KEY(q + "orientation.", d.orientation, radius_factor);
    COMIC_KEY(q, d, normalization);
  }
  COMIC_KEY(p + "matching.", o.matching, max_distance);
  COMIC_KEY(p + "matching.", o.matching, max_ratio);
  COMIC_KEY(p + "matching.", o.matching, cross_check);
  AddVerification(p + "verification.", o.verification, key);
  COMIC_KEY(p, o, guided_matching);
  COMIC_KEY(p, o, guided_max_ratio);
  COMIC_KEY(p, o, guided_max_error_px);
  COMIC_KEY(p, o, conflict_rule);
}

#undef COMIC_KEY

// The frames as worked on: their size, their names, and their bytes (a folder's files one by
// one; a video's file once, its frame numbers being in the names).
void AddFrames(const io::ImageSequence& sequence, KeyText& key) {
  key.Add("frames.video", sequence.IsVideo());
  key.Add("frames.size", std::to_string(sequence.FrameSize().width) + "x" +
                             std::to_string(sequence.FrameSize().height));
  key.Add("frames.source_size", std::to_string(sequence.SourceFrameSize().width) + "x" +
                                    std::to_string(sequence.SourceFrameSize().height));
  key.Add("frames.count", sequence.NumFrames());
  if (sequence.IsVideo()) {
    io::ContentHash hash;
    hash.AddFile(sequence.path());
    key.Add("frames.video_bytes", io::HexDigits(hash.value()));
  }
  for (size_t i = 0; i < sequence.NumFrames(); ++i) {
    std::string line = sequence.FrameNames()[i];
    if (!sequence.IsVideo()) {
      io::ContentHash hash;
      hash.AddFile(sequence.FramePath(i));
      line += " " + io::HexDigits(hash.value());
    }
    key.Add("frame", line);
  }
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The cached tracking of `file` if it holds `key`; none (and `warning` saying why, unless the file
// is simply not there) otherwise.
std::optional<SequenceTracking> ReadCachedTracking(const std::string& file, uint64_t key,
                                                   const io::ImageSequence& sequence,
                                                   std::string* warning) {
  if (!io::PathExists(file)) return std::nullopt;
  const auto start = std::chrono::steady_clock::now();
  try {
    frontend::TrackFile read = frontend::ReadTrackFile(file);
    COMIC_CHECK(read.key == key, kInvalidData,
                file << ": holds the tracks of key " << io::HexDigits(read.key)
                     << ", not those of its name");
    COMIC_CHECK(read.tracks.NumFrames() == sequence.NumFrames() &&
                    read.tracks.image_size == sequence.FrameSize(),
                kInvalidData,
                file << ": holds tracks of " << read.tracks.NumFrames() << " frames of "
                     << read.tracks.image_size.width << "x" << read.tracks.image_size.height
                     << ", not of these frames");
    SequenceTracking tracking;
    tracking.tracks = std::move(read.tracks);
    tracking.track_building = read.track_building;
    tracking.image_set_matching = read.image_set_matching;
    tracking.masked_features = read.masked_features;
    tracking.time_s = Seconds(start);
    return tracking;
  } catch (const Error& e) {
    *warning = std::string(e.what()) + "; detecting and tracking again, and replacing it";
  } catch (const std::exception& e) {
    // Whatever else reading a damaged file meets (memory, a library's exception) costs a
    // recomputation, never the run: the cache is optional.
    *warning = file + ": cannot read the track file (" + e.what() +
               "); detecting and tracking again, and replacing it";
  }
  return std::nullopt;
}

// Writes `file` into `folder`, creating it if needed. A failure (a full disk, a read-only folder)
// removes the folders this call created, so nothing empty is left behind, and is returned as one
// line: the tracks exist, and the run goes on without keeping them.
std::string KeepTracking(const std::string& folder, const std::string& path,
                         const frontend::TrackFile& file) {
  std::vector<std::string> created;
  for (std::string missing = folder; !missing.empty() && !io::PathExists(missing);
       missing = io::ParentPath(missing)) {
    created.push_back(missing);
  }
  try {
    io::EnsureWritableDirectory(folder);
    frontend::WriteTrackFile(path, file);
    return "";
  } catch (const std::exception& e) {
    for (const std::string& made : created) {
      std::error_code ec;
      std::filesystem::remove(made, ec);  // only when empty
    }
    return std::string(e.what()) + "; the tracks are not kept in --cache, the run goes on";
  }
}

}  // namespace

std::string TrackCacheKeyText(const frontend::DetectorOptions& detector,
                              const SequenceReconstructionOptions& options,
                              const io::ImageSequence& sequence) {
  std::ostringstream out;
  KeyText key(&out);
  key.Add("comic_track_cache", frontend::kTrackFileVersion);
  // Another build may detect or track otherwise: its cache is not reused.
  key.Add("version", Version());
  AddDetector(detector, key);
  if (options.image_set) {
    AddImageSet(*options.image_set, key);
  } else {
    AddTracker(options.tracker, key);
  }
  // The masks decide which features exist: their dropped regions (the convention and the margin
  // applied) as a hash, or none.
  key.Add("feature_masks", options.feature_masks ? io::HexDigits(options.feature_masks->Hash())
                                                 : std::string("none"));
  AddFrames(sequence, key);
  return out.str();
}

uint64_t TrackCacheKey(const frontend::DetectorOptions& detector,
                       const SequenceReconstructionOptions& options,
                       const io::ImageSequence& sequence) {
  return io::HashBytes(TrackCacheKeyText(detector, options, sequence));
}

std::string TrackCacheFile(const std::string& folder, const std::string& detector, uint64_t key) {
  return io::JoinPaths(folder, "tracks-" + detector + "-" + io::HexDigits(key) + ".bin");
}

SequenceTracking TrackFramesThroughCache(
    const std::string& folder, const frontend::DetectorOptions& detector_options,
    const frontend::Detector& detector, const io::ImageSequence& sequence,
    const SequenceReconstructionOptions& options, const std::function<void()>& tracking_started,
    const frontend::TrackingProgress& tracking_progress, TrackCacheUse* use) {
  COMIC_CHECK(use != nullptr, kInvalidArgument, "track cache: no TrackCacheUse");
  *use = TrackCacheUse();
  if (!folder.empty()) {
    use->key = TrackCacheKey(detector_options, options, sequence);
    use->file = TrackCacheFile(folder, detector_options.name, use->key);
    std::optional<SequenceTracking> cached =
        ReadCachedTracking(use->file, use->key, sequence, &use->warning);
    if (cached) {
      use->from_cache = true;
      return std::move(*cached);
    }
  }
  if (tracking_started) tracking_started();
  SequenceTracking tracking = TrackFrames(sequence, detector, options, tracking_progress);
  if (!folder.empty()) {
    // Written as soon as the tracks exist, before the mapping: a run stopped while mapping is
    // resumed from here.
    frontend::TrackFile file;
    file.key = use->key;
    file.tracks = std::move(tracking.tracks);  // lent, not copied: a long clip's tracks are large
    file.track_building = tracking.track_building;
    file.image_set_matching = tracking.image_set_matching;
    file.masked_features = tracking.masked_features;
    // Measured CPU times are left out: the same frames and options give the same file, byte for
    // byte, and a run read from the cache spent no time matching.
    if (file.image_set_matching) {
      frontend::ImageSetMatchingSummary& s = *file.image_set_matching;
      s.detection_cpu_s = s.description_cpu_s = s.matching_cpu_s = s.verification_cpu_s =
          s.track_building_cpu_s = 0.0;
    }
    const std::string failure = KeepTracking(folder, use->file, file);
    if (!failure.empty()) use->warning += (use->warning.empty() ? "" : "; then ") + failure;
    tracking.tracks = std::move(file.tracks);
  }
  return tracking;
}

}  // namespace comic::sfm
