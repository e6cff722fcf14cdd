// A binary file of one sequence's tracking: the features of every frame (every field of
// frontend::Feature), the tracks, the descriptors when they were computed, and what building the
// tracks met; under a 64-bit key that says what made them (sfm/run/track_cache.h). Exact: floats
// and doubles are stored as their bytes, so that what is read is what was written, bit for bit.
//
//   TrackFile file;
//   file.key = key;
//   file.tracks = tracking.tracks;
//   WriteTrackFile("cache/tracks-harris-0123456789abcdef.bin", file);  // atomic
//   TrackFile read = ReadTrackFile("cache/tracks-harris-0123456789abcdef.bin");
//
// Layout (host byte order, checked by a marker; all counts 64-bit):
//   "COMICTRK", uint32 0x01020304, uint32 format version, uint64 key,
//   payload (detector name, image size, frame names, features, tracks, descriptors, summaries),
//   uint64 FNV-1a 64 of every byte before it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "frontend/matching/image_set_matching.h"
#include "frontend/matching/track.h"
#include "frontend/matching/track_builder.h"

namespace comic::frontend {

// The version ReadTrackFile reads; files of other versions are refused (kInvalidData).
// 2: the count of features removed by masks (masked_features).
inline constexpr uint32_t kTrackFileVersion = 2;

struct TrackFile {
  uint64_t key = 0;  // the writer's; the reader compares it with its own
  FeatureTracks tracks;
  TrackBuildSummary track_building;
  std::optional<ImageSetMatchingSummary> image_set_matching;
  // Detected features that masks of moving objects removed (frontend/feature_masks.h): a cached
  // run reports the same count as the run that made the file.
  int64_t masked_features = 0;
};

// The bytes of the file. Throws comic::Error(kInvalidArgument) if `file.tracks` fails Check().
std::string EncodeTrackFile(const TrackFile& file);

// Reads the bytes of a file; `what` (its path) starts every message. Throws
// comic::Error(kInvalidData) for anything but a complete file of this version written on a machine
// of this byte order (wrong magic, other version, checksum mismatch, a count or a descriptor size
// larger than the bytes left, a position or scale that is not finite, tracks that fail
// FeatureTracks::Check()); never reads past the end, nor allocates more than the bytes hold.
TrackFile DecodeTrackFile(const std::string& bytes, const std::string& what);

// EncodeTrackFile written atomically (io/core/file_utils.h): `path` is the complete new file or
// untouched. Throws comic::Error(kIo) naming `path`.
void WriteTrackFile(const std::string& path, const TrackFile& file);

// DecodeTrackFile of the file at `path`, read by io::ReadRegularFile: a device, FIFO or other
// non-regular file is refused (kInvalidData), and no more than the file's size is read. Throws
// comic::Error (kNotFound, kIo, kInvalidData).
TrackFile ReadTrackFile(const std::string& path);

}  // namespace comic::frontend
