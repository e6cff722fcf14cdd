// The track file: every field read back bit for bit (features with side masks and curves, NaN and
// negative zero, descriptors present and absent, the summaries), and a truncated, flipped,
// foreign or other-version file refused with kInvalidData, never read past its end.
#include "frontend/matching/track_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/core/content_hash.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

Feature MakeFeature(float seed, bool with_sides) {
  Feature feature;
  feature.x = 10.25f + seed;
  feature.y = 20.5f - seed;
  feature.scale = 8.4f;
  feature.response = seed * 1e-3f;
  feature.cornerness = 0.0312f;
  feature.level = static_cast<int>(seed) % 255;
  feature.polarity = with_sides ? Polarity::kDark : Polarity::kNone;
  if (with_sides) {
    feature.side_mask.resize(kPatchSize * kPatchSize, PatchSide::kPlus);
    feature.side_mask[3] = PatchSide::kMinus;
    feature.side_mask[7] = PatchSide::kNone;
    feature.curve = {{1.5f, 2.25f}, {3.0f, -4.125f}};
  }
  return feature;
}

TrackFile MakeFile(bool with_descriptors) {
  TrackFile file;
  file.key = 0x0123456789abcdefull;
  FeatureTracks& tracks = file.tracks;
  tracks.detector_name = "comic+hessian";
  tracks.image_size = {640, 480};
  tracks.frame_names = {"a.png", "b.png", "c.png"};
  tracks.features = {{MakeFeature(1, true), MakeFeature(2, false)},
                     {MakeFeature(3, true), MakeFeature(4, true), MakeFeature(5, false)},
                     {}};
  // Values text formats lose: NaN, negative zero, the float next to 1.
  tracks.features[1][1].response = std::numeric_limits<float>::quiet_NaN();
  tracks.features[1][2].x = -0.0f;
  tracks.features[1][2].y = std::nextafter(1.0f, 2.0f);
  tracks.tracks = {{{{0, 0}, {1, 1}}}, {{{0, 1}, {1, 0}}}};
  if (with_descriptors) {
    for (const FeatureSet& frame : tracks.features) {
      cv::Mat d(static_cast<int>(frame.size()), 128, CV_8UC1);
      for (int r = 0; r < d.rows; ++r) {
        for (int c = 0; c < d.cols; ++c) d.at<uint8_t>(r, c) = static_cast<uint8_t>(r * 131 + c);
      }
      tracks.descriptors.push_back(d);
    }
  }
  file.track_building = {41, 2, 5, 3};
  file.masked_features = 7;
  if (with_descriptors) {
    ImageSetMatchingSummary summary;
    summary.num_frames = 3;
    summary.num_features = 5;
    summary.num_pairs = 3;
    summary.num_verified_pairs = 1;
    summary.num_raw_matches = 12;
    summary.num_verified_matches = 2;
    summary.detection_cpu_s = 0.1;
    summary.track_building_cpu_s = 1e-9;
    file.image_set_matching = summary;
  }
  return file;
}

bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

void ExpectSame(const TrackFile& a, const TrackFile& b) {
  EXPECT_EQ(a.key, b.key);
  EXPECT_EQ(a.masked_features, b.masked_features);
  EXPECT_EQ(a.tracks.detector_name, b.tracks.detector_name);
  EXPECT_EQ(a.tracks.image_size, b.tracks.image_size);
  EXPECT_EQ(a.tracks.frame_names, b.tracks.frame_names);
  ASSERT_EQ(a.tracks.features.size(), b.tracks.features.size());
  for (size_t f = 0; f < a.tracks.features.size(); ++f) {
    ASSERT_EQ(a.tracks.features[f].size(), b.tracks.features[f].size());
    for (size_t i = 0; i < a.tracks.features[f].size(); ++i) {
      const Feature& p = a.tracks.features[f][i];
      const Feature& q = b.tracks.features[f][i];
      EXPECT_TRUE(SameBits(p.x, q.x) && SameBits(p.y, q.y) && SameBits(p.scale, q.scale) &&
                  SameBits(p.response, q.response) && SameBits(p.cornerness, q.cornerness))
          << f << " " << i;
      EXPECT_EQ(p.level, q.level);
      EXPECT_EQ(p.polarity, q.polarity);
      EXPECT_EQ(p.side_mask, q.side_mask);
      EXPECT_EQ(p.curve, q.curve);
    }
  }
  ASSERT_EQ(a.tracks.tracks.size(), b.tracks.tracks.size());
  for (size_t t = 0; t < a.tracks.tracks.size(); ++t) {
    ASSERT_EQ(a.tracks.tracks[t].Length(), b.tracks.tracks[t].Length());
    for (size_t o = 0; o < a.tracks.tracks[t].Length(); ++o) {
      EXPECT_EQ(a.tracks.tracks[t].observations[o].frame, b.tracks.tracks[t].observations[o].frame);
      EXPECT_EQ(a.tracks.tracks[t].observations[o].feature,
                b.tracks.tracks[t].observations[o].feature);
    }
  }
  ASSERT_EQ(a.tracks.descriptors.size(), b.tracks.descriptors.size());
  for (size_t f = 0; f < a.tracks.descriptors.size(); ++f) {
    EXPECT_EQ(a.tracks.descriptors[f].rows, b.tracks.descriptors[f].rows);
    if (a.tracks.descriptors[f].rows > 0) {
      EXPECT_EQ(cv::norm(a.tracks.descriptors[f], b.tracks.descriptors[f], cv::NORM_INF), 0.0);
    }
  }
  EXPECT_EQ(a.track_building.num_matches, b.track_building.num_matches);
  EXPECT_EQ(a.track_building.num_conflicting_components,
            b.track_building.num_conflicting_components);
  EXPECT_EQ(a.track_building.num_dropped_features, b.track_building.num_dropped_features);
  EXPECT_EQ(a.track_building.num_refused_matches, b.track_building.num_refused_matches);
  ASSERT_EQ(a.image_set_matching.has_value(), b.image_set_matching.has_value());
  if (a.image_set_matching) {
    EXPECT_EQ(a.image_set_matching->num_raw_matches, b.image_set_matching->num_raw_matches);
    EXPECT_EQ(a.image_set_matching->track_building_cpu_s,
              b.image_set_matching->track_building_cpu_s);
  }
}

// The message of the comic::Error(kInvalidData) that decoding `bytes` throws ("" if none).
std::string DecodeError(const std::string& bytes) {
  try {
    DecodeTrackFile(bytes, "t.bin");
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData) << e.what();
    return e.what();
  }
  return "";
}

TEST(TrackFile, RoundTripIsExact) {
  for (bool with_descriptors : {false, true}) {
    SCOPED_TRACE(with_descriptors);
    const TrackFile file = MakeFile(with_descriptors);
    const std::string bytes = EncodeTrackFile(file);
    ExpectSame(file, DecodeTrackFile(bytes, "t.bin"));
    // The same bytes again: a re-written cache is the same file.
    EXPECT_EQ(EncodeTrackFile(DecodeTrackFile(bytes, "t.bin")), bytes);
  }
}

TEST(TrackFile, WritesAtomicallyAndReadsBack) {
  test::ScopedTempDir dir;
  const std::string path = dir.File("tracks.bin");
  WriteTrackFile(path, MakeFile(true));
  WriteTrackFile(path, MakeFile(false));  // replaced
  ExpectSame(MakeFile(false), ReadTrackFile(path));
  EXPECT_EQ(io::ListFiles(dir.path()), std::vector<std::string>{"tracks.bin"});
}

TEST(TrackFile, EveryTruncationIsRefused) {
  const std::string bytes = EncodeTrackFile(MakeFile(true));
  for (size_t size = 0; size < bytes.size(); ++size) {
    EXPECT_NE(DecodeError(bytes.substr(0, size)), "") << size;
  }
}

TEST(TrackFile, EveryFlippedByteIsRefused) {
  const std::string bytes = EncodeTrackFile(MakeFile(false));
  for (size_t i = 0; i < bytes.size(); ++i) {
    std::string flipped = bytes;
    flipped[i] = static_cast<char>(flipped[i] ^ 0x10);
    EXPECT_NE(DecodeError(flipped), "") << i;
  }
}

TEST(TrackFile, SaysWhatIsWrong) {
  std::string bytes = EncodeTrackFile(MakeFile(false));
  EXPECT_NE(DecodeError("P6\n640 480\n255\n").find("t.bin: not a comic track file"),
            std::string::npos);
  std::string other_version = bytes;
  other_version[12] = 3;  // the version follows the magic and the byte-order marker
  EXPECT_NE(DecodeError(other_version).find("format version 3, this build reads version 2"),
            std::string::npos);
  std::string swapped = bytes;
  std::swap(swapped[8], swapped[11]);
  EXPECT_NE(DecodeError(swapped).find("another byte order"), std::string::npos);
  EXPECT_NE(DecodeError(bytes.substr(0, bytes.size() - 1)).find("checksum"), std::string::npos);
}

// A file whose checksum is right but whose counts lie (made by hand, not by the writer): refused
// before anything is allocated for the count.
TEST(TrackFile, AForgedCountIsRefusedBeforeAllocating) {
  std::string bytes = EncodeTrackFile(MakeFile(false));
  // The detector name's length is the first field after the 24-byte header.
  const uint64_t huge = uint64_t{1} << 60;
  std::memcpy(bytes.data() + 24, &huge, sizeof(huge));
  io::ContentHash hash;
  hash.Add(bytes.data(), bytes.size() - 8);
  const uint64_t checksum = hash.value();
  std::memcpy(bytes.data() + bytes.size() - 8, &checksum, sizeof(checksum));
  EXPECT_NE(DecodeError(bytes).find("detector name"), std::string::npos);
}

TEST(TrackFile, TracksThatFailCheckAreNotWritten) {
  TrackFile file = MakeFile(false);
  file.tracks.tracks.push_back({{{0, 7}, {1, 0}}});  // feature 7 of frame 0 does not exist
  try {
    EncodeTrackFile(file);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
  }
}

TEST(TrackFile, AMissingFileIsNotFound) {
  try {
    ReadTrackFile("/nonexistent/tracks.bin");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kNotFound);
  }
}

// `bytes` with `replacement` written over the first place `original` occurs, and the checksum
// made right again: a forged file, as a hand-edited cache would be.
std::string Forge(std::string bytes, const std::string& original, const std::string& replacement) {
  const size_t at = bytes.find(original);
  EXPECT_NE(at, std::string::npos);
  if (at == std::string::npos) return bytes;
  bytes.replace(at, replacement.size(), replacement);
  const uint64_t checksum = io::HashBytes(bytes.substr(0, bytes.size() - 8));
  std::memcpy(bytes.data() + bytes.size() - 8, &checksum, sizeof(checksum));
  return bytes;
}

template <typename T>
std::string BytesOf(T value) {
  return std::string(reinterpret_cast<const char*>(&value), sizeof(T));
}

// Descriptor rows of 2^31 - 1 (a 256 GB matrix) behind a valid checksum: refused from the bytes
// left, before the matrix is allocated, as kInvalidData (a cache miss), not std::bad_alloc.
TEST(TrackFile, AForgedDescriptorSizeIsRefusedBeforeAllocating) {
  const std::string bytes = EncodeTrackFile(MakeFile(true));
  // Frame 1's descriptors: 3 rows of 128, their first bytes 0, 1, 2.
  const std::string rows = BytesOf<int32_t>(3) + BytesOf<int32_t>(128) + std::string("\0\1\2", 3);
  const std::string forged =
      Forge(bytes, rows, BytesOf<int32_t>(std::numeric_limits<int32_t>::max()));
  ASSERT_NE(forged, bytes);
  const std::string error = DecodeError(forged);
  EXPECT_NE(error.find("t.bin: track file is truncated or corrupt (descriptors: 2147483647 x 128"),
            std::string::npos)
      << error;
}

// NaN or infinite positions and scales behind a valid checksum: refused (a cache miss), not handed
// to the mapper. A NaN response stays valid: detectors may leave it undefined.
TEST(TrackFile, NonFinitePositionsAreRefused) {
  const std::string bytes = EncodeTrackFile(MakeFile(false));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // Feature 0 of frame 0 is at (11.25, 19.5), scale 8.4; its curve holds (3, -4.125).
  const std::vector<std::pair<std::string, std::string>> forgeries = {
      {BytesOf(11.25f) + BytesOf(19.5f), BytesOf(nan)},
      {BytesOf(11.25f) + BytesOf(19.5f), BytesOf(11.25f) + BytesOf(-inf)},
      {BytesOf(19.5f) + BytesOf(8.4f), BytesOf(19.5f) + BytesOf(inf)},
      {BytesOf(3.0f) + BytesOf(-4.125f), BytesOf(nan)}};
  for (const auto& [original, replacement] : forgeries) {
    const std::string error = DecodeError(Forge(bytes, original, replacement));
    EXPECT_NE(error.find("t.bin: track file is corrupt ("), std::string::npos) << error;
    EXPECT_NE(error.find("inf"), error.find("nan")) << error;  // one of them is named
  }
  const std::string curve = DecodeError(Forge(bytes, forgeries[3].first, BytesOf(nan)));
  EXPECT_NE(curve.find("(curve point nan, -4.125)"), std::string::npos) << curve;
  const std::string position = DecodeError(Forge(bytes, forgeries[0].first, BytesOf(nan)));
  EXPECT_NE(position.find("(feature position nan, 19.5)"), std::string::npos) << position;
}

// A link to /dev/zero or a FIFO in the cache file's place: refused at once, nothing read (the
// read is bounded by the file's size, and only regular files have one).
TEST(TrackFile, ANonRegularFileIsNotRead) {
  test::ScopedTempDir dir;
  const std::string link = dir.File("zero.bin");
  ASSERT_EQ(::symlink("/dev/zero", link.c_str()), 0);
  const std::string fifo = dir.File("fifo.bin");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  for (const std::string& path : {link, fifo}) {
    try {
      ReadTrackFile(path);
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
      EXPECT_NE(std::string(e.what()).find(path + ": not a regular file"), std::string::npos)
          << e.what();
    }
  }
  // A link to a regular file is read as the file.
  WriteTrackFile(dir.File("tracks.bin"), MakeFile(false));
  ASSERT_EQ(::symlink(dir.File("tracks.bin").c_str(), dir.File("link.bin").c_str()), 0);
  ExpectSame(MakeFile(false), ReadTrackFile(dir.File("link.bin")));
}

}  // namespace
}  // namespace comic::frontend
