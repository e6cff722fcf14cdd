// The track cache behind `comic_sfm --cache DIR` (issue 26, "Resume"): a run's detections,
// descriptors and tracks are kept in DIR/tracks-<detector>-<key>.bin (frontend/matching/
// track_file.h), and a re-run whose key is the same reads them instead of detecting and tracking
// again, so that trying other mapper options on a long clip costs only the mapping.
//
// The key is FNV-1a 64 of a canonical text (TrackCacheKeyText) of everything that decides the
// tracks: the program's version, the detector's name and options, the tracker's options (or the
// image-set matching's), the masks of moving objects (their dropped regions, hashed), the
// frames' size as worked on, and the frames themselves (each file's name
// and bytes; a video's bytes and the frame numbers used). Mapper options are not in it: changing
// them is what the cache is for. Thread counts are not in it either: no output depends on them
// (docs/sfm.md, determinism).
//
//   TrackCacheUse use;
//   SequenceTracking tracking = TrackFramesThroughCache(
//       "cache", detector_options, *detector, sequence, options, {}, {}, &use);
//   if (use.from_cache) { ... detection and tracking were skipped }
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "frontend/detector_factory.h"
#include "io/image/image_sequence.h"
#include "sfm/sequence_reconstruction.h"

namespace comic::sfm {

// One line per setting ("tracker.matcher.radius=20\n"); doubles with 17 significant digits, so
// that two settings that differ in any bit differ here. Reads every frame file (or the video)
// once to hash its bytes. Throws comic::Error (kNotFound, kIo) for a frame file it cannot read.
std::string TrackCacheKeyText(const frontend::DetectorOptions& detector,
                              const SequenceReconstructionOptions& options,
                              const io::ImageSequence& sequence);

// FNV-1a 64 of TrackCacheKeyText.
uint64_t TrackCacheKey(const frontend::DetectorOptions& detector,
                       const SequenceReconstructionOptions& options,
                       const io::ImageSequence& sequence);

// `folder`/tracks-<detector>-<16 hex digits of key>.bin.
std::string TrackCacheFile(const std::string& folder, const std::string& detector, uint64_t key);

// What the cache did for one run.
struct TrackCacheUse {
  std::string file;         // the cache file (empty: no cache asked for)
  uint64_t key = 0;         // TrackCacheKey
  bool from_cache = false;  // the tracks were read from `file`: nothing was detected or tracked
  // A cache file of this key that could not be used (corrupt, truncated, another format
  // version, forged sizes or positions, not a regular file): the tracks were computed again and
  // the file replaced. Or a cache folder or file that could not be written (a full disk, a
  // read-only folder): the run went on without keeping the tracks. One line; empty otherwise.
  std::string warning;
};

// TrackFrames through the cache in `folder` (empty: no cache, TrackFrames as it is). When
// `folder`/TrackCacheFile exists and reads back with the same key, its tracks are returned and
// nothing is detected (`tracking_started` and `tracking_progress` are not called). Otherwise the
// frames are tracked (`tracking_started` first) and the file is written atomically, creating
// `folder` if needed; when that fails the folders it created are removed again and `use->warning`
// says why: the cache is optional, and never fails a run. A read-only `folder` holding the file is
// read as any other. `detector` must be MakeDetector(detector_options). Throws comic::Error for
// what TrackFrames throws for.
SequenceTracking TrackFramesThroughCache(
    const std::string& folder, const frontend::DetectorOptions& detector_options,
    const frontend::Detector& detector, const io::ImageSequence& sequence,
    const SequenceReconstructionOptions& options, const std::function<void()>& tracking_started,
    const frontend::TrackingProgress& tracking_progress, TrackCacheUse* use);

}  // namespace comic::sfm
