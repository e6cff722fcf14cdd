#include "frontend/matching/tracker.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "io/core/error.h"
#include "io/image/image_sequence.h"

namespace comic::frontend {

const char* MotionPredictionName(MotionPrediction prediction) {
  switch (prediction) {
    case MotionPrediction::kNone:
      return "none";
    case MotionPrediction::kConstantVelocity:
      return "velocity";
    case MotionPrediction::kCoarseToFine:
      return "coarse-to-fine";
  }
  return "?";
}

MotionPrediction ParseMotionPrediction(const std::string& name) {
  for (MotionPrediction p : {MotionPrediction::kNone, MotionPrediction::kConstantVelocity,
                             MotionPrediction::kCoarseToFine}) {
    if (name == MotionPredictionName(p)) return p;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "unknown motion prediction '" + name + "' (valid: none, velocity, coarse-to-fine)");
}

void TrackerOptions::Check() const {
  matcher.Check();
  COMIC_CHECK(matcher.gate == CandidateGate::kRadius, kInvalidArgument,
              "tracker: the matcher must use the radius gate");
  COMIC_CHECK(max_features >= 0, kInvalidArgument,
              "tracker: max_features must be >= 0 (0 = all), got " << max_features);
  COMIC_CHECK(unpredicted_radius >= 0, kInvalidArgument,
              "tracker: unpredicted_radius must be >= 0 px, got " << unpredicted_radius);
  COMIC_CHECK(velocity_neighbours >= 1, kInvalidArgument,
              "tracker: velocity_neighbours must be >= 1, got " << velocity_neighbours);
  COMIC_CHECK(velocity_neighbour_radius > 0, kInvalidArgument,
              "tracker: velocity_neighbour_radius must be > 0 px");
  COMIC_CHECK(coarse_factor >= 2, kInvalidArgument,
              "tracker: coarse_factor must be >= 2, got " << coarse_factor);
  COMIC_CHECK(coarse_radius > 0, kInvalidArgument, "tracker: coarse_radius must be > 0 px");
  COMIC_CHECK(coarse_features >= 1, kInvalidArgument, "tracker: coarse_features must be >= 1");
  COMIC_CHECK(match_window >= 1, kInvalidArgument,
              "tracker: match_window must be >= 1, got " << match_window);
  COMIC_CHECK(verify_min_gap >= 0, kInvalidArgument,
              "tracker: verify_min_gap must be >= 0 (0 = none), got " << verify_min_gap);
  if (verify_min_gap > 0) verification.Check();
  COMIC_CHECK(!match_turned_180 || verify_min_gap > 0, kInvalidArgument,
              "tracker: match_turned_180 needs verify_min_gap > 0 (the verified matches decide "
              "between the hypotheses)");
}

FeatureSet SelectTrackableFeatures(const FeatureSet& detected, const cv::Size& image_size,
                                   const TrackerOptions& options) {
  // Keep the max_features strongest (by response, then the deterministic SortByResponse order)
  // without reordering the input.
  std::vector<size_t> usable;
  for (size_t i = 0; i < detected.size(); ++i) {
    if (detected[i].response >= options.min_response && PatchFits(detected[i], image_size)) {
      usable.push_back(i);
    }
  }
  if (options.max_features > 0 && static_cast<int>(usable.size()) > options.max_features) {
    std::vector<size_t> by_strength = usable;
    std::stable_sort(by_strength.begin(), by_strength.end(), [&](size_t a, size_t b) {
      const Feature& fa = detected[a];
      const Feature& fb = detected[b];
      if (fa.response != fb.response) return fa.response > fb.response;
      if (fa.y != fb.y) return fa.y < fb.y;
      return fa.x < fb.x;
    });
    by_strength.resize(options.max_features);
    std::sort(by_strength.begin(), by_strength.end());
    usable = by_strength;
  }
  FeatureSet kept;
  kept.reserve(usable.size());
  for (size_t i : usable) kept.push_back(detected[i]);
  return kept;
}

namespace {

// A known displacement at a position.
struct MotionSample {
  cv::Point2f position;
  cv::Point2f displacement;
};

// Median displacement of the `k` samples nearest to `p` within `max_distance`, if any. Ties in
// distance are broken by sample order, so the result is deterministic.
bool MedianNeighbourDisplacement(const std::vector<MotionSample>& samples, cv::Point2f p, int k,
                                 double max_distance, cv::Point2f* displacement) {
  std::vector<std::pair<float, int>> near;
  const float max_d2 = static_cast<float>(max_distance * max_distance);
  for (int s = 0; s < static_cast<int>(samples.size()); ++s) {
    const cv::Point2f d = samples[s].position - p;
    const float d2 = d.dot(d);
    if (d2 <= max_d2) near.emplace_back(d2, s);
  }
  if (near.empty()) return false;
  const size_t n = std::min<size_t>(k, near.size());
  std::partial_sort(near.begin(), near.begin() + n, near.end());
  std::vector<float> xs, ys;
  for (size_t i = 0; i < n; ++i) {
    xs.push_back(samples[near[i].second].displacement.x);
    ys.push_back(samples[near[i].second].displacement.y);
  }
  auto median = [](std::vector<float> v) {
    std::sort(v.begin(), v.end());
    const size_t m = v.size() / 2;
    return v.size() % 2 == 1 ? v[m] : 0.5f * (v[m - 1] + v[m]);
  };
  *displacement = {median(xs), median(ys)};
  return true;
}

// The strongest `count` features of a detection whose patch fits.
FeatureSet StrongestFitting(const FeatureSet& detected, const cv::Size& size, int count) {
  FeatureSet sorted = detected;
  SortByResponse(&sorted);
  FeatureSet kept;
  for (const Feature& f : sorted) {
    if (static_cast<int>(kept.size()) >= count) break;
    if (PatchFits(f, size)) kept.push_back(f);
  }
  return kept;
}

// The features of an image of `size` turned by 180° in its plane: positions (x, y) ->
// (w − 1 − x, h − 1 − y), the side masks (row-major, centred) and curves turned with them.
FeatureSet TurnFeatures180(const FeatureSet& features, const cv::Size& size) {
  const float w1 = static_cast<float>(size.width - 1), h1 = static_cast<float>(size.height - 1);
  FeatureSet turned = features;
  for (Feature& f : turned) {
    f.x = w1 - f.x;
    f.y = h1 - f.y;
    std::reverse(f.side_mask.begin(), f.side_mask.end());
    for (cv::Point2f& p : f.curve) p = {w1 - p.x, h1 - p.y};
  }
  return turned;
}

// The consecutive pairs (i, i+1) and the window pairs as one list for BuildTracks.
std::vector<FramePairMatches> AllPairs(const std::vector<std::vector<PatchMatch>>& consecutive,
                                       const std::vector<FramePairMatches>& window) {
  std::vector<FramePairMatches> pairs;
  pairs.reserve(consecutive.size() + window.size());
  for (size_t i = 0; i < consecutive.size(); ++i) {
    pairs.push_back({static_cast<int>(i), static_cast<int>(i) + 1, consecutive[i]});
  }
  pairs.insert(pairs.end(), window.begin(), window.end());
  return pairs;
}

}  // namespace

Tracker::Tracker(const TrackerOptions& options, std::string detector_name, const Detector* detector)
    : options_(options), detector_name_(std::move(detector_name)), detector_(detector) {
  options_.Check();
  COMIC_CHECK(options_.prediction != MotionPrediction::kCoarseToFine || detector_ != nullptr,
              kInvalidArgument, "tracker: coarse-to-fine prediction needs a detector");
}

Tracker::CoarseFrame Tracker::MakeCoarseFrame(const cv::Mat& gray) const {
  CoarseFrame coarse;
  if (options_.prediction != MotionPrediction::kCoarseToFine) return coarse;
  const double f = options_.coarse_factor;
  const cv::Size coarse_size(std::max(1, static_cast<int>(std::lround(gray.cols / f))),
                             std::max(1, static_cast<int>(std::lround(gray.rows / f))));
  cv::resize(gray, coarse.gray, coarse_size, 0, 0, cv::INTER_AREA);
  coarse.features =
      StrongestFitting(detector_->Detect(coarse.gray), coarse_size, options_.coarse_features);
  coarse.patches = PreparePatches(coarse.gray, coarse.features, options_.matcher);
  return coarse;
}

Tracker::TurnedFrame Tracker::TurnFrame180(const cv::Mat& gray, const FeatureSet& features,
                                           const CoarseFrame& coarse) const {
  TurnedFrame turned;
  cv::rotate(gray, turned.gray, cv::ROTATE_180);
  turned.features = TurnFeatures180(features, gray.size());
  turned.patches = PreparePatches(turned.gray, turned.features, options_.matcher);
  if (!coarse.gray.empty()) {
    cv::rotate(coarse.gray, turned.coarse.gray, cv::ROTATE_180);
    turned.coarse.features = TurnFeatures180(coarse.features, coarse.gray.size());
    turned.coarse.patches =
        PreparePatches(turned.coarse.gray, turned.coarse.features, options_.matcher);
  }
  return turned;
}

const std::vector<PatchMatch>& Tracker::AcceptedMatches(int frame1, int frame2) const {
  return accepted_[frame2][frame2 - frame1 - 1];
}

SearchRegions Tracker::PredictSearchRegions(
    int frame1, const cv::Mat& gray2, const FeatureSet& features2, const CoarseFrame& coarse2,
    const std::vector<std::vector<PatchMatch>>& accepted_to_frame2, bool turned) const {
  const FeatureSet& current = features_[frame1];
  const int frame2 = static_cast<int>(features_.size());
  const int gap = frame2 - frame1;
  SearchRegions search;
  if (options_.prediction == MotionPrediction::kNone) return search;
  const float fine_radius = static_cast<float>(options_.matcher.radius);
  const float unpredicted_radius = static_cast<float>(
      options_.unpredicted_radius > 0 ? options_.unpredicted_radius : options_.matcher.radius);
  search.centres.resize(current.size());
  search.radii.assign(current.size(), fine_radius);

  std::vector<MotionSample> samples;
  std::vector<bool> own(current.size(), false);
  // A feature's own velocity says nothing about where it is in a frame turned upside down.
  if (gap == 1 && !turned && options_.prediction == MotionPrediction::kConstantVelocity) {
    if (frame1 >= 1) {
      const FeatureSet& before = features_[frame1 - 1];
      for (const PatchMatch& m : AcceptedMatches(frame1 - 1, frame1)) {
        const cv::Point2f velocity = current[m.index2].Position() - before[m.index1].Position();
        samples.push_back({current[m.index2].Position(), velocity});
        own[m.index2] = true;
        search.centres[m.index2] = current[m.index2].Position() + velocity;
      }
    }
  }
  if (gap > 1) {
    // Two hops through a frame in between, frame1 -> m -> frame2, both matched already (the
    // nearer pairs are matched first): where that puts a feature is its prediction, and these
    // displacements predict its neighbours. Nearest m first, so a feature's own link comes from
    // the pair of the smallest first hop.
    for (int m = frame1 + 1; m < frame2; ++m) {
      std::vector<int> in_frame2(features_[m].size(), -1);
      for (const PatchMatch& hop : accepted_to_frame2[frame2 - m - 1]) {
        in_frame2[hop.index1] = hop.index2;
      }
      for (const PatchMatch& hop : AcceptedMatches(frame1, m)) {
        const int c = in_frame2[hop.index2];
        if (c < 0 || own[hop.index1]) continue;
        const cv::Point2f position = current[hop.index1].Position();
        samples.push_back({position, features2[c].Position() - position});
        own[hop.index1] = true;
        search.centres[hop.index1] = features2[c].Position();
      }
    }
  }
  if (options_.prediction == MotionPrediction::kCoarseToFine) {
    // Coarse pass: match the strongest features of the downscaled frames.
    const CoarseFrame& coarse1 = coarse_[frame1];
    const double f = options_.coarse_factor;
    PatchMatcherOptions coarse_options = options_.matcher;
    coarse_options.radius = options_.coarse_radius / f;
    const double sx = static_cast<double>(gray2.cols) / coarse2.gray.cols;
    const double sy = static_cast<double>(gray2.rows) / coarse2.gray.rows;
    for (const PatchMatch& m : MatchFeatures(coarse1.features, coarse1.patches, coarse2.features,
                                             coarse2.patches, coarse_options)) {
      const Feature& a = coarse1.features[m.index1];
      const Feature& b = coarse2.features[m.index2];
      // Coarse pixel centres map back as areas do: x = (x_c + 0.5)·s − 0.5.
      const cv::Point2f position(static_cast<float>((a.x + 0.5) * sx - 0.5),
                                 static_cast<float>((a.y + 0.5) * sy - 0.5));
      const cv::Point2f displacement(static_cast<float>((b.x - a.x) * sx),
                                     static_cast<float>((b.y - a.y) * sy));
      samples.push_back({position, displacement});
    }
  }
  for (size_t i = 0; i < current.size(); ++i) {
    if (own[i]) continue;
    cv::Point2f displacement;
    if (MedianNeighbourDisplacement(samples, current[i].Position(), options_.velocity_neighbours,
                                    options_.velocity_neighbour_radius, &displacement)) {
      search.centres[i] = current[i].Position() + displacement;
    } else {
      search.centres[i] = current[i].Position();
      search.radii[i] = unpredicted_radius;
    }
  }
  return search;
}

void Tracker::AddFrame(const cv::Mat& gray, FeatureSet features, const std::string& name) {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "tracker: frames must be non-empty 8-bit single-channel images");
  COMIC_CHECK(features_.empty() || gray.size() == image_size_, kInvalidArgument,
              "tracker: frame " << features_.size() << " is " << gray.cols << "x" << gray.rows
                                << ", the first was " << image_size_.width << "x"
                                << image_size_.height);
  const int frame = static_cast<int>(features_.size());
  CoarseFrame coarse = MakeCoarseFrame(gray);
  // This frame's patches, prepared once: it is image 2 of the pairs below and image 1 of the
  // next match_window frames' pairs.
  PatchSet patches = PreparePatches(gray, features, options_.matcher);
  std::optional<TurnedFrame> turned;  // made when first needed
  bool previous_pair_turned = false;  // the pair (frame − 1, frame) kept the turned hypothesis
  // Earlier frames matched to this one, nearest first: the predictions for the farther ones
  // build on the matches to the nearer ones.
  std::vector<std::vector<PatchMatch>> mutual_to_frame, accepted_to_frame;
  for (int gap = 1; gap <= options_.match_window && gap <= frame; ++gap) {
    const int earlier = frame - gap;
    const bool verify = options_.verify_min_gap > 0 && gap >= options_.verify_min_gap;
    // The earlier frame matched to this one as given (gray2, features2, coarse2), or turned by
    // 180°: the mutual best matches, and those accepted (cost threshold, then the epipolar
    // verification on the features as stored, whose indices the turned ones share).
    auto match = [&](const cv::Mat& gray2, const FeatureSet& features2, const PatchSet& patches2,
                     const CoarseFrame& coarse2, bool is_turned, std::vector<PatchMatch>* mutual,
                     std::vector<PatchMatch>* accepted) {
      const SearchRegions search =
          PredictSearchRegions(earlier, gray2, features2, coarse2, accepted_to_frame, is_turned);
      *mutual = SelectMutualBest(ComputeCandidateCosts(
          features_[earlier], patches_[earlier], features2, patches2, options_.matcher, search));
      *accepted = ApplyCostThreshold(*mutual, options_.matcher.max_cost);
      if (verify) {
        *accepted = VerifyMatches(features_[earlier], features, *accepted, options_.verification);
      }
    };
    std::vector<PatchMatch> mutual, accepted;
    match(gray, features, patches, coarse, false, &mutual, &accepted);
    if (verify && options_.match_turned_180) {
      if (!turned) turned = TurnFrame180(gray, features, coarse);
      std::vector<PatchMatch> turned_mutual, turned_accepted;
      match(turned->gray, turned->features, turned->patches, turned->coarse, true, &turned_mutual,
            &turned_accepted);
      if (turned_accepted.size() > accepted.size()) {
        mutual = std::move(turned_mutual);
        accepted = std::move(turned_accepted);
        turned_pairs_.emplace_back(earlier, frame);
        if (gap == 1) previous_pair_turned = true;
      }
    }
    accepted_to_frame.push_back(std::move(accepted));
    mutual_to_frame.push_back(std::move(mutual));
  }
  if (options_.matcher.cost == MatchCost::kTrackSides && frame > 0) {
    // The memory along the track: a feature whose match from the frame before cost its full
    // patch (the side did not win) is compared by its full patch when it is matched on. Done
    // after every pair into this frame, so that it changes only the pairs out of it.
    PatchMatcherOptions full = options_.matcher;
    full.cost = MatchCost::kFullPatch;
    const PatchSet& matched = previous_pair_turned ? turned->patches : patches;
    for (const PatchMatch& m : accepted_to_frame.front()) {
      if (m.cost >= PatchCost(patches_[frame - 1], m.index1, matched, m.index2, full)) {
        patches.DropSides(m.index2);
      }
    }
  }
  features_.push_back(std::move(features));
  names_.push_back(name);
  mutual_.push_back(std::move(mutual_to_frame));
  accepted_.push_back(std::move(accepted_to_frame));
  patches_.push_back(std::move(patches));
  coarse_.push_back(std::move(coarse));
  image_size_ = gray.size();
  // Frames no later frame will be matched to: free their patches.
  const int expired = frame - options_.match_window;
  if (expired >= 0) {
    patches_[expired] = PatchSet();
    coarse_[expired] = CoarseFrame();
  }
}

TrackingResult Tracker::Result() const {
  TrackingResult result;
  result.tracks.detector_name = detector_name_;
  result.tracks.image_size = image_size_;
  const bool any_name =
      std::any_of(names_.begin(), names_.end(), [](const std::string& n) { return !n.empty(); });
  if (any_name) result.tracks.frame_names = names_;
  result.tracks.features = features_;
  for (int frame2 = 1; frame2 < static_cast<int>(features_.size()); ++frame2) {
    for (int gap = 1; gap <= static_cast<int>(mutual_[frame2].size()); ++gap) {
      if (gap == 1) {
        result.mutual_matches.push_back(mutual_[frame2][0]);
        result.accepted_matches.push_back(accepted_[frame2][0]);
      } else {
        result.window_mutual_matches.push_back({frame2 - gap, frame2, mutual_[frame2][gap - 1]});
        result.window_accepted_matches.push_back(
            {frame2 - gap, frame2, accepted_[frame2][gap - 1]});
      }
    }
  }
  result.options = options_;
  result.turned_pairs = turned_pairs_;
  result.tracks.tracks =
      BuildTracks(features_, AllPairs(result.accepted_matches, result.window_accepted_matches),
                  options_.conflict_rule, &result.track_building);
  return result;
}

TrackingResult TrackSequence(const io::ImageSequence& sequence, const Detector& detector,
                             const TrackerOptions& options, const TrackingProgress& progress) {
  Tracker tracker(options, detector.Name(), &detector);
  for (size_t i = 0; i < sequence.NumFrames(); ++i) {
    const io::Frame frame = sequence.ReadFrame(i);
    tracker.AddFrame(
        frame.gray,
        SelectTrackableFeatures(detector.Detect(frame.gray), frame.gray.size(), options),
        frame.name);
    if (progress) progress(i + 1, sequence.NumFrames());
  }
  return tracker.Result();
}

TrackingResult TrackFrames(const std::vector<cv::Mat>& grays, const Detector& detector,
                           const TrackerOptions& options,
                           const std::vector<std::string>& frame_names,
                           const TrackingProgress& progress) {
  COMIC_CHECK(frame_names.empty() || frame_names.size() == grays.size(), kInvalidArgument,
              "tracker: " << frame_names.size() << " names for " << grays.size() << " frames");
  Tracker tracker(options, detector.Name(), &detector);
  for (size_t i = 0; i < grays.size(); ++i) {
    COMIC_CHECK(!grays[i].empty() && grays[i].type() == CV_8UC1, kInvalidArgument,
                "tracker: frame " << i << " is not a non-empty 8-bit single-channel image");
    tracker.AddFrame(grays[i],
                     SelectTrackableFeatures(detector.Detect(grays[i]), grays[i].size(), options),
                     frame_names.empty() ? "" : frame_names[i]);
    if (progress) progress(i + 1, grays.size());
  }
  return tracker.Result();
}

FeatureTracks TracksAtThreshold(const TrackingResult& result, double max_cost) {
  FeatureTracks tracks = result.tracks;
  const TrackerOptions& options = result.options;
  auto accept = [&](int frame1, int frame2, const std::vector<PatchMatch>& mutual) {
    std::vector<PatchMatch> accepted = ApplyCostThreshold(mutual, max_cost);
    if (options.verify_min_gap > 0 && frame2 - frame1 >= options.verify_min_gap) {
      accepted = VerifyMatches(tracks.features[frame1], tracks.features[frame2], accepted,
                               options.verification);
    }
    return accepted;
  };
  std::vector<std::vector<PatchMatch>> accepted;
  for (size_t i = 0; i < result.mutual_matches.size(); ++i) {
    accepted.push_back(
        accept(static_cast<int>(i), static_cast<int>(i) + 1, result.mutual_matches[i]));
  }
  std::vector<FramePairMatches> window;
  for (const FramePairMatches& pair : result.window_mutual_matches) {
    window.push_back({pair.frame1, pair.frame2, accept(pair.frame1, pair.frame2, pair.matches)});
  }
  tracks.tracks = BuildTracks(tracks.features, AllPairs(accepted, window), options.conflict_rule);
  return tracks;
}

}  // namespace comic::frontend
