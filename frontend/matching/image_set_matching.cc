#include "frontend/matching/image_set_matching.h"

#include <time.h>

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "frontend/combined_detector.h"
#include "frontend/matching/combined_tracking.h"
#include "frontend/parallel_for.h"
#include "io/core/error.h"
#include "io/image/image_sequence.h"

namespace comic::frontend {
namespace {

double ThreadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Counts work done from several threads and reports it in increasing order.
class ProgressCounter {
 public:
  ProgressCounter(const ImageSetMatchingProgress& progress, size_t offset, size_t grand_total)
      : progress_(progress), offset_(offset), grand_total_(grand_total) {}
  void Add() {
    if (!progress_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    progress_(offset_ + (++done_), grand_total_);
  }

 private:
  const ImageSetMatchingProgress& progress_;
  size_t offset_;
  size_t grand_total_;
  size_t done_ = 0;
  std::mutex mutex_;
};

// Frames come from a sequence (read one at a time: a video cannot be read in parallel) or from
// memory.
using FrameReader = std::function<cv::Mat(int frame)>;

struct FrameSource {
  int num_frames = 0;
  cv::Size image_size;
  std::vector<std::string> names;
  FrameReader read;
  DetectionFilter filter;  // applied to each frame's detection (empty: none)
};

FeatureSet SelectFeatures(FeatureSet detected, const ImageSetMatchingOptions& options) {
  FeatureSet kept;
  for (Feature& feature : detected) {
    if (feature.response < options.min_response) continue;
    if (options.max_features > 0 && static_cast<int>(kept.size()) >= options.max_features) break;
    kept.push_back(std::move(feature));
  }
  return kept;
}

// Reads the frames in batches (one at a time: a video cannot be read in parallel) and calls
// work(frame, gray) for the frames of a batch in parallel.
void ForEachFrame(const FrameSource& source, int num_threads,
                  const std::function<void(int frame, const cv::Mat& gray)>& work) {
  const int batch = std::max(1, 2 * ResolveNumThreads(num_threads, source.num_frames));
  for (int start = 0; start < source.num_frames; start += batch) {
    const int end = std::min(source.num_frames, start + batch);
    std::vector<cv::Mat> grays;
    for (int frame = start; frame < end; ++frame) {
      grays.push_back(source.read(frame));
      COMIC_CHECK(grays.back().type() == CV_8UC1 && grays.back().size() == source.image_size,
                  kInvalidArgument,
                  "image set matching: frame " << frame << " is not CV_8UC1 of the first's size");
    }
    ParallelFor(end - start, num_threads, [&](int item, int) { work(start + item, grays[item]); });
  }
}

// Stage 1: features and descriptors of every frame.
void DescribeFrames(const FrameSource& source, const Detector& detector,
                    const ImageSetMatchingOptions& options, ProgressCounter* progress,
                    ImageSetMatching* result) {
  FeatureTracks& tracks = result->tracks;
  tracks.features.assign(source.num_frames, {});
  tracks.descriptors.assign(source.num_frames, cv::Mat(0, kDescriptorSize, CV_8UC1));
  const DescriptorOptions describe =
      options.descriptor ? *options.descriptor : DescriptorOptionsFor(detector.Name());
  std::vector<double> detection_s(source.num_frames, 0.0), description_s(source.num_frames, 0.0);
  ForEachFrame(source, options.num_threads, [&](int frame, const cv::Mat& gray) {
    const double t0 = ThreadCpuSeconds();
    FeatureSet detected = detector.Detect(gray);
    if (source.filter) detected = source.filter(frame, std::move(detected));
    tracks.features[frame] = SelectFeatures(std::move(detected), options);
    const double t1 = ThreadCpuSeconds();
    tracks.descriptors[frame] = DescribeFeatures(gray, tracks.features[frame], describe);
    detection_s[frame] = t1 - t0;
    description_s[frame] = ThreadCpuSeconds() - t1;
    progress->Add();
  });
  for (int frame = 0; frame < source.num_frames; ++frame) {
    result->summary.detection_cpu_s += detection_s[frame];
    result->summary.description_cpu_s += description_s[frame];
    result->summary.num_features += static_cast<int64_t>(tracks.features[frame].size());
  }
}

DescriptorMatchOptions GuidedOptions(const ImageSetMatchingOptions& options) {
  DescriptorMatchOptions guided = options.matching;
  guided.max_ratio = options.guided_max_ratio;
  return guided;
}

// Stage 2: every pair matched and verified in parallel, collected in pair order.
void MatchPairs(const ImageSetMatchingOptions& options, ProgressCounter* progress,
                ImageSetMatching* result) {
  const FeatureTracks& tracks = result->tracks;
  const std::vector<std::pair<int, int>> pairs = ImageSetPairs(
      static_cast<int>(tracks.NumFrames()), options.window, options.quadratic_overlap);
  struct PairResult {
    std::vector<PatchMatch> verified;
    int num_raw = 0;
    double matching_s = 0.0;
    double verification_s = 0.0;
  };
  std::vector<PairResult> pair_results(pairs.size());
  ParallelFor(static_cast<int>(pairs.size()), options.num_threads, [&](int p, int) {
    const auto [frame1, frame2] = pairs[p];
    PairResult& out = pair_results[p];
    const double t0 = ThreadCpuSeconds();
    const std::vector<PatchMatch> raw =
        MatchDescriptors(tracks.descriptors[frame1], tracks.descriptors[frame2], options.matching);
    const double t1 = ThreadCpuSeconds();
    out.num_raw = static_cast<int>(raw.size());
    cv::Matx33d fundamental;
    out.verified = VerifyMatches(tracks.features[frame1], tracks.features[frame2], raw,
                                 options.verification, &fundamental);
    const double t2 = ThreadCpuSeconds();
    if (options.guided_matching && !out.verified.empty()) {
      std::vector<PatchMatch> guided = MatchDescriptorsAlongEpipolarLines(
          tracks.descriptors[frame1], tracks.descriptors[frame2], tracks.features[frame1],
          tracks.features[frame2], fundamental, options.guided_max_error_px,
          GuidedOptions(options));
      if (guided.size() > out.verified.size()) out.verified = std::move(guided);
    }
    out.matching_s = (t1 - t0) + (ThreadCpuSeconds() - t2);
    out.verification_s = t2 - t1;
    progress->Add();
  });
  ImageSetMatchingSummary& summary = result->summary;
  summary.num_pairs = static_cast<int>(pairs.size());
  for (size_t p = 0; p < pairs.size(); ++p) {
    PairResult& out = pair_results[p];
    summary.num_raw_matches += out.num_raw;
    summary.matching_cpu_s += out.matching_s;
    summary.verification_cpu_s += out.verification_s;
    if (out.verified.empty()) continue;
    ++summary.num_verified_pairs;
    summary.num_verified_matches += static_cast<int64_t>(out.verified.size());
    result->verified_pairs.push_back({pairs[p].first, pairs[p].second, std::move(out.verified)});
  }
}

ImageSetMatching MatchWithOneDetector(const FrameSource& source, const Detector& detector,
                                      const ImageSetMatchingOptions& options,
                                      const ImageSetMatchingProgress& progress, size_t offset,
                                      size_t grand_total) {
  ImageSetMatching result;
  result.tracks.detector_name = detector.Name();
  result.tracks.image_size = source.image_size;
  result.tracks.frame_names = source.names;
  result.summary.num_frames = source.num_frames;
  ProgressCounter describe_progress(progress, offset, grand_total);
  DescribeFrames(source, detector, options, &describe_progress, &result);
  ProgressCounter match_progress(progress, offset + source.num_frames, grand_total);
  MatchPairs(options, &match_progress, &result);
  const double t0 = ThreadCpuSeconds();
  result.tracks.tracks = BuildTracks(result.tracks.features, result.verified_pairs,
                                     options.conflict_rule, &result.track_building);
  result.summary.track_building_cpu_s = ThreadCpuSeconds() - t0;
  result.tracks.Check();
  return result;
}

// The components' results as one: features, descriptors and tracks concatenated per frame in
// component order (combined_tracking.h's layout), pairs' indices moved, counts summed.
ImageSetMatching MergeParts(std::vector<ImageSetMatching> parts, const std::string& name) {
  std::vector<TrackingResult> tracking(parts.size());
  for (size_t p = 0; p < parts.size(); ++p) {
    tracking[p].tracks = parts[p].tracks;
    tracking[p].track_building = parts[p].track_building;
  }
  TrackingResult merged_tracking = MergeTrackingResults(tracking, name);
  ImageSetMatching merged;
  merged.tracks = std::move(merged_tracking.tracks);
  merged.track_building = merged_tracking.track_building;
  const int num_frames = static_cast<int>(merged.tracks.NumFrames());
  std::vector<std::vector<int>> offsets(num_frames);
  for (int frame = 0; frame < num_frames; ++frame) {
    offsets[frame] = FirstFeatureOfEachPart(tracking, frame);
  }
  std::map<std::pair<int, int>, std::vector<PatchMatch>> pairs;
  ImageSetMatchingSummary& sum = merged.summary;
  for (size_t p = 0; p < parts.size(); ++p) {
    for (const FramePairMatches& pair : parts[p].verified_pairs) {
      std::vector<PatchMatch>& out = pairs[{pair.frame1, pair.frame2}];
      for (PatchMatch m : pair.matches) {
        m.index1 += offsets[pair.frame1][p];
        m.index2 += offsets[pair.frame2][p];
        out.push_back(m);
      }
    }
    const ImageSetMatchingSummary& s = parts[p].summary;
    sum.num_frames = s.num_frames;
    sum.num_features += s.num_features;
    sum.num_pairs = s.num_pairs;
    sum.num_raw_matches += s.num_raw_matches;
    sum.num_verified_matches += s.num_verified_matches;
    sum.detection_cpu_s += s.detection_cpu_s;
    sum.description_cpu_s += s.description_cpu_s;
    sum.matching_cpu_s += s.matching_cpu_s;
    sum.verification_cpu_s += s.verification_cpu_s;
    sum.track_building_cpu_s += s.track_building_cpu_s;
  }
  for (auto& [frames, matches] : pairs) {
    merged.verified_pairs.push_back({frames.first, frames.second, std::move(matches)});
  }
  sum.num_verified_pairs = static_cast<int>(merged.verified_pairs.size());
  return merged;
}

ImageSetMatching MatchSource(const FrameSource& source, const Detector& detector,
                             const ImageSetMatchingOptions& options,
                             const ImageSetMatchingProgress& progress) {
  options.Check();
  const size_t per_detector =
      source.num_frames +
      ImageSetPairs(source.num_frames, options.window, options.quadratic_overlap).size();
  const auto* combined = dynamic_cast<const CombinedDetector*>(&detector);
  if (combined == nullptr) {
    return MatchWithOneDetector(source, detector, options, progress, 0, per_detector);
  }
  const size_t total = per_detector * combined->NumComponents();
  std::vector<ImageSetMatching> parts;
  for (size_t c = 0; c < combined->NumComponents(); ++c) {
    parts.push_back(MatchWithOneDetector(source, combined->Component(c), options, progress,
                                         c * per_detector, total));
  }
  return MergeParts(std::move(parts), combined->Name());
}

}  // namespace

ImageSetMatchingOptions::ImageSetMatchingOptions() {
  verification.max_error_px = 4.0;
  verification.min_num_inliers = 15;
  verification.min_inlier_ratio = 0.25;
  verification.max_num_iterations = 10000;
}

void ImageSetMatchingOptions::Check() const {
  COMIC_CHECK(max_features >= 0, kInvalidArgument,
              "image set matching: max_features must be >= 0, got " << max_features);
  COMIC_CHECK(window >= 0, kInvalidArgument,
              "image set matching: window must be >= 0, got " << window);
  COMIC_CHECK(num_threads >= 0, kInvalidArgument,
              "image set matching: num_threads must be >= 0, got " << num_threads);
  COMIC_CHECK(guided_max_error_px > 0, kInvalidArgument,
              "image set matching: guided_max_error_px must be > 0, got " << guided_max_error_px);
  COMIC_CHECK(guided_max_ratio > 0 && guided_max_ratio <= 1, kInvalidArgument,
              "image set matching: guided_max_ratio must be in (0, 1], got " << guided_max_ratio);
  if (descriptor) descriptor->Check();
  matching.Check();
  verification.Check();
}

ImageSetMatchingProgress ProgressInFrames(std::function<void(size_t, size_t)> progress,
                                          size_t num_frames) {
  if (!progress) return {};
  auto told = std::make_shared<size_t>(0);
  return [progress = std::move(progress), num_frames, told](size_t done, size_t total) {
    const size_t frames = total == 0 ? num_frames : done * num_frames / total;
    while (*told < frames) progress(++*told, num_frames);
  };
}

std::vector<std::pair<int, int>> ImageSetPairs(int num_frames, int window, bool quadratic_overlap) {
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < num_frames; ++i) {
    const int last_in_window = window <= 0 ? num_frames - 1 : std::min(num_frames - 1, i + window);
    for (int j = i + 1; j <= last_in_window; ++j) pairs.emplace_back(i, j);
    if (!quadratic_overlap || window <= 0) continue;
    for (int64_t step = 1; i + step < num_frames; step *= 2) {
      if (i + step > last_in_window) pairs.emplace_back(i, static_cast<int>(i + step));
    }
  }
  return pairs;
}

ImageSetMatching MatchImageSet(const io::ImageSequence& sequence, const Detector& detector,
                               const ImageSetMatchingOptions& options,
                               const ImageSetMatchingProgress& progress,
                               const DetectionFilter& filter) {
  FrameSource source;
  source.num_frames = static_cast<int>(sequence.NumFrames());
  source.image_size = sequence.FrameSize();
  source.names = sequence.FrameNames();
  source.read = [&sequence](int frame) { return sequence.ReadFrame(frame).gray; };
  source.filter = filter;
  return MatchSource(source, detector, options, progress);
}

double DescribeTrackedFeatures(const io::ImageSequence& sequence, FeatureTracks* tracks,
                               int num_threads, const std::optional<DescriptorOptions>& options,
                               const ImageSetMatchingProgress& progress) {
  COMIC_CHECK(tracks != nullptr, kInvalidArgument, "describe tracks: no tracks");
  COMIC_CHECK(
      tracks->NumFrames() == sequence.NumFrames() && tracks->image_size == sequence.FrameSize(),
      kInvalidArgument,
      "describe tracks: the tracks are of "
          << tracks->NumFrames() << " frames of " << tracks->image_size << ", the sequence of "
          << sequence.NumFrames() << " of " << sequence.FrameSize());
  const DescriptorOptions describe =
      options ? *options : DescriptorOptionsFor(tracks->detector_name);
  describe.Check();
  FrameSource source;
  source.num_frames = static_cast<int>(sequence.NumFrames());
  source.image_size = sequence.FrameSize();
  source.read = [&sequence](int frame) { return sequence.ReadFrame(frame).gray; };
  std::vector<cv::Mat> descriptors(source.num_frames);
  std::vector<double> cpu_s(source.num_frames, 0.0);
  ProgressCounter counter(progress, 0, source.num_frames);
  ForEachFrame(source, num_threads, [&](int frame, const cv::Mat& gray) {
    const double t0 = ThreadCpuSeconds();
    descriptors[frame] = DescribeFeatures(gray, tracks->features[frame], describe);
    cpu_s[frame] = ThreadCpuSeconds() - t0;
    counter.Add();
  });
  tracks->descriptors = std::move(descriptors);
  tracks->Check();
  double total = 0.0;
  for (double s : cpu_s) total += s;
  return total;
}

ImageSetMatching MatchImageFrames(const std::vector<cv::Mat>& grays, const Detector& detector,
                                  const ImageSetMatchingOptions& options,
                                  const std::vector<std::string>& frame_names,
                                  const ImageSetMatchingProgress& progress) {
  COMIC_CHECK(
      frame_names.empty() || frame_names.size() == grays.size(), kInvalidArgument,
      "image set matching: " << frame_names.size() << " names for " << grays.size() << " frames");
  FrameSource source;
  source.num_frames = static_cast<int>(grays.size());
  source.image_size = grays.empty() ? cv::Size() : grays.front().size();
  source.names = frame_names;
  source.read = [&grays](int frame) { return grays[frame]; };
  return MatchSource(source, detector, options, progress);
}

}  // namespace comic::frontend
