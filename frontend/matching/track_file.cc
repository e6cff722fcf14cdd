#include "frontend/matching/track_file.h"

#include <cmath>
#include <cstring>
#include <type_traits>

#include "io/core/content_hash.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::frontend {

namespace {

constexpr char kMagic[8] = {'C', 'O', 'M', 'I', 'C', 'T', 'R', 'K'};
// Written in host order: read back as another number on a machine of the other byte order.
constexpr uint32_t kByteOrderMarker = 0x01020304u;
constexpr size_t kHeaderSize = sizeof(kMagic) + 4 + 4 + 8;
constexpr size_t kChecksumSize = 8;

class Writer {
 public:
  template <typename T>
  void Put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void PutBytes(const void* data, size_t size) {
    bytes_.append(static_cast<const char*>(data), size);
  }
  void PutCount(size_t count) { Put<uint64_t>(count); }
  void PutString(const std::string& text) {
    PutCount(text.size());
    PutBytes(text.data(), text.size());
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

// Every read is checked against the bytes left: a truncated or forged count throws before
// anything is allocated for it.
class Reader {
 public:
  Reader(const std::string& bytes, size_t begin, size_t end, const std::string& what)
      : bytes_(bytes), pos_(begin), end_(end), what_(what) {}

  template <typename T>
  T Get(const char* field) {
    static_assert(std::is_trivially_copyable_v<T>);
    Need(sizeof(T), 1, field);
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  void GetBytes(void* data, size_t size, const char* field) {
    Need(size, 1, field);
    std::memcpy(data, bytes_.data() + pos_, size);
    pos_ += size;
  }
  // A count of items of at least `item_size` bytes each, all of which must still be there.
  size_t GetCount(size_t item_size, const char* field) {
    const uint64_t count = Get<uint64_t>(field);
    Need(count, item_size, field);
    return static_cast<size_t>(count);
  }
  std::string GetString(const char* field) {
    std::string text(GetCount(1, field), '\0');
    GetBytes(text.data(), text.size(), field);
    return text;
  }
  size_t left() const { return end_ - pos_; }
  // Throws unless `count` items of `item_size` bytes are still there: called before allocating
  // for them, so a forged count costs nothing.
  void Need(uint64_t count, size_t item_size, const char* field) const {
    COMIC_CHECK(item_size == 0 || count <= left() / item_size, kInvalidData,
                what_ << ": track file is truncated or corrupt (" << field << ": " << count << " x "
                      << item_size << " bytes, " << left() << " left)");
  }

 private:
  const std::string& bytes_;
  size_t pos_;
  size_t end_;
  const std::string& what_;
};

// x, y, scale, response, cornerness, level, polarity, two counts.
constexpr size_t kMinFeatureSize = 5 * 4 + 4 + 1 + 8 + 8;

void PutFeature(const Feature& feature, Writer* out) {
  out->Put(feature.x);
  out->Put(feature.y);
  out->Put(feature.scale);
  out->Put(feature.response);
  out->Put(feature.cornerness);
  out->Put<int32_t>(feature.level);
  out->Put(static_cast<int8_t>(feature.polarity));
  out->PutCount(feature.side_mask.size());
  for (PatchSide side : feature.side_mask) out->Put(static_cast<uint8_t>(side));
  out->PutCount(feature.curve.size());
  for (const cv::Point2f& point : feature.curve) {
    out->Put(point.x);
    out->Put(point.y);
  }
}

// The checksum vouches for the bytes, not for their meaning: a file made to pass it may hold NaN or
// infinite positions, which no detector writes and the mapper cannot use.
void CheckFinite(float a, float b, const char* field, const std::string& what) {
  COMIC_CHECK(std::isfinite(a) && std::isfinite(b), kInvalidData,
              what << ": track file is corrupt (" << field << " " << a << ", " << b << ")");
}

Feature GetFeature(Reader* in, const std::string& what) {
  Feature feature;
  feature.x = in->Get<float>("feature x");
  feature.y = in->Get<float>("feature y");
  feature.scale = in->Get<float>("feature scale");
  feature.response = in->Get<float>("feature response");
  feature.cornerness = in->Get<float>("feature cornerness");
  feature.level = in->Get<int32_t>("feature level");
  const int8_t polarity = in->Get<int8_t>("feature polarity");
  COMIC_CHECK(polarity >= -1 && polarity <= 1, kInvalidData,
              what << ": track file is corrupt (polarity " << int{polarity} << ")");
  feature.polarity = static_cast<Polarity>(polarity);
  feature.side_mask.resize(in->GetCount(1, "side mask"));
  for (PatchSide& side : feature.side_mask) {
    const uint8_t value = in->Get<uint8_t>("side mask");
    COMIC_CHECK(value <= 2, kInvalidData,
                what << ": track file is corrupt (patch side " << int{value} << ")");
    side = static_cast<PatchSide>(value);
  }
  feature.curve.resize(in->GetCount(8, "curve"));
  for (cv::Point2f& point : feature.curve) {
    point.x = in->Get<float>("curve");
    point.y = in->Get<float>("curve");
    CheckFinite(point.x, point.y, "curve point", what);
  }
  CheckFinite(feature.x, feature.y, "feature position", what);
  CheckFinite(feature.scale, 0.0f, "feature scale", what);
  return feature;
}

void PutDescriptors(const std::vector<cv::Mat>& descriptors, Writer* out) {
  out->PutCount(descriptors.size());
  for (const cv::Mat& d : descriptors) {
    // FeatureTracks::Check: CV_8UC1 with 128 columns, or no rows (then stored as none at all).
    const bool empty = d.rows == 0;
    out->Put<int32_t>(d.rows);
    out->Put<int32_t>(empty ? 0 : d.cols);
    for (int r = 0; r < d.rows; ++r) out->PutBytes(d.ptr(r), d.cols);
  }
}

std::vector<cv::Mat> GetDescriptors(Reader* in, const std::string& what) {
  std::vector<cv::Mat> descriptors(in->GetCount(8, "descriptor frames"));
  for (cv::Mat& d : descriptors) {
    const int32_t rows = in->Get<int32_t>("descriptor rows");
    const int32_t cols = in->Get<int32_t>("descriptor columns");
    if (rows == 0 && cols == 0) continue;
    COMIC_CHECK(rows > 0 && cols == 128, kInvalidData,
                what << ": track file is corrupt (descriptors " << rows << "x" << cols << ")");
    in->Need(static_cast<uint64_t>(rows), static_cast<size_t>(cols), "descriptors");
    d.create(rows, cols, CV_8UC1);
    in->GetBytes(d.data, d.total(), "descriptors");
  }
  return descriptors;
}

void PutSummaries(const TrackFile& file, Writer* out) {
  const TrackBuildSummary& building = file.track_building;
  out->Put<int32_t>(building.num_matches);
  out->Put<int32_t>(building.num_conflicting_components);
  out->Put<int32_t>(building.num_dropped_features);
  out->Put<int32_t>(building.num_refused_matches);
  out->Put<int64_t>(file.masked_features);
  out->Put<uint8_t>(file.image_set_matching.has_value());
  if (!file.image_set_matching) return;
  const ImageSetMatchingSummary& s = *file.image_set_matching;
  out->Put<int32_t>(s.num_frames);
  out->Put<int64_t>(s.num_features);
  out->Put<int32_t>(s.num_pairs);
  out->Put<int32_t>(s.num_verified_pairs);
  out->Put<int64_t>(s.num_raw_matches);
  out->Put<int64_t>(s.num_verified_matches);
  for (double seconds : {s.detection_cpu_s, s.description_cpu_s, s.matching_cpu_s,
                         s.verification_cpu_s, s.track_building_cpu_s}) {
    out->Put(seconds);
  }
}

void GetSummaries(Reader* in, TrackFile* file) {
  TrackBuildSummary& building = file->track_building;
  building.num_matches = in->Get<int32_t>("summary");
  building.num_conflicting_components = in->Get<int32_t>("summary");
  building.num_dropped_features = in->Get<int32_t>("summary");
  building.num_refused_matches = in->Get<int32_t>("summary");
  file->masked_features = in->Get<int64_t>("summary");
  if (in->Get<uint8_t>("summary") == 0) return;
  ImageSetMatchingSummary& s = file->image_set_matching.emplace();
  s.num_frames = in->Get<int32_t>("summary");
  s.num_features = in->Get<int64_t>("summary");
  s.num_pairs = in->Get<int32_t>("summary");
  s.num_verified_pairs = in->Get<int32_t>("summary");
  s.num_raw_matches = in->Get<int64_t>("summary");
  s.num_verified_matches = in->Get<int64_t>("summary");
  for (double* seconds : {&s.detection_cpu_s, &s.description_cpu_s, &s.matching_cpu_s,
                          &s.verification_cpu_s, &s.track_building_cpu_s}) {
    *seconds = in->Get<double>("summary");
  }
}

void PutTracks(const FeatureTracks& tracks, Writer* out) {
  out->PutString(tracks.detector_name);
  out->Put<int32_t>(tracks.image_size.width);
  out->Put<int32_t>(tracks.image_size.height);
  out->PutCount(tracks.frame_names.size());
  for (const std::string& name : tracks.frame_names) out->PutString(name);
  out->PutCount(tracks.features.size());
  for (const FeatureSet& frame : tracks.features) {
    out->PutCount(frame.size());
    for (const Feature& feature : frame) PutFeature(feature, out);
  }
  out->PutCount(tracks.tracks.size());
  for (const Track& track : tracks.tracks) {
    out->PutCount(track.observations.size());
    for (const TrackObservation& obs : track.observations) {
      out->Put<int32_t>(obs.frame);
      out->Put<int32_t>(obs.feature);
    }
  }
  PutDescriptors(tracks.descriptors, out);
}

FeatureTracks GetTracks(Reader* in, const std::string& what) {
  FeatureTracks tracks;
  tracks.detector_name = in->GetString("detector name");
  tracks.image_size.width = in->Get<int32_t>("image size");
  tracks.image_size.height = in->Get<int32_t>("image size");
  tracks.frame_names.resize(in->GetCount(8, "frame names"));
  for (std::string& name : tracks.frame_names) name = in->GetString("frame name");
  tracks.features.resize(in->GetCount(8, "frames"));
  for (FeatureSet& frame : tracks.features) {
    const size_t count = in->GetCount(kMinFeatureSize, "features");
    frame.reserve(count);
    for (size_t i = 0; i < count; ++i) frame.push_back(GetFeature(in, what));
  }
  tracks.tracks.resize(in->GetCount(8, "tracks"));
  for (Track& track : tracks.tracks) {
    track.observations.resize(in->GetCount(8, "observations"));
    for (TrackObservation& obs : track.observations) {
      obs.frame = in->Get<int32_t>("observation");
      obs.feature = in->Get<int32_t>("observation");
    }
  }
  tracks.descriptors = GetDescriptors(in, what);
  return tracks;
}

}  // namespace

std::string EncodeTrackFile(const TrackFile& file) {
  try {
    file.tracks.Check();
  } catch (const Error& e) {
    throw Error(ErrorKind::kInvalidArgument, std::string("track file: ") + e.what());
  }
  Writer out;
  out.PutBytes(kMagic, sizeof(kMagic));
  out.Put(kByteOrderMarker);
  out.Put(kTrackFileVersion);
  out.Put(file.key);
  PutTracks(file.tracks, &out);
  PutSummaries(file, &out);
  out.Put(io::HashBytes(out.bytes()));
  return std::move(out.bytes());
}

TrackFile DecodeTrackFile(const std::string& bytes, const std::string& what) {
  COMIC_CHECK(bytes.size() >= kHeaderSize + kChecksumSize &&
                  std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) == 0,
              kInvalidData, what << ": not a comic track file");
  Reader header(bytes, sizeof(kMagic), kHeaderSize, what);
  const uint32_t marker = header.Get<uint32_t>("byte order");
  COMIC_CHECK(marker == kByteOrderMarker, kInvalidData,
              what << ": track file written on a machine of another byte order");
  const uint32_t version = header.Get<uint32_t>("version");
  COMIC_CHECK(version == kTrackFileVersion, kInvalidData,
              what << ": track file of format version " << version << ", this build reads version "
                   << kTrackFileVersion);
  TrackFile file;
  file.key = header.Get<uint64_t>("key");
  // The checksum before the content: a flipped byte anywhere is refused, not read as a feature.
  const size_t end = bytes.size() - kChecksumSize;
  uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + end, kChecksumSize);
  io::ContentHash content;
  content.Add(bytes.data(), end);
  COMIC_CHECK(checksum == content.value(), kInvalidData,
              what << ": track file is truncated or corrupt (checksum mismatch)");
  Reader in(bytes, kHeaderSize, end, what);
  file.tracks = GetTracks(&in, what);
  GetSummaries(&in, &file);
  COMIC_CHECK(in.left() == 0, kInvalidData,
              what << ": track file is corrupt (" << in.left() << " bytes after the content)");
  try {
    file.tracks.Check();
  } catch (const Error& e) {
    throw Error(ErrorKind::kInvalidData, what + ": track file is corrupt: " + e.what());
  }
  return file;
}

void WriteTrackFile(const std::string& path, const TrackFile& file) {
  io::WriteFileAtomically(path, EncodeTrackFile(file));
}

TrackFile ReadTrackFile(const std::string& path) {
  return DecodeTrackFile(io::ReadRegularFile(path), path);
}

}  // namespace comic::frontend
