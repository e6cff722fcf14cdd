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
  COMIC_CHECK(min_window_eigenvalue >= 0, kInvalidArgument,
              "tracker: min_window_eigenvalue must be >= 0, got " << min_window_eigenvalue);
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
  continuation.Check();
  COMIC_CHECK(align_patches || continuation.max_continued_frames == 0, kInvalidArgument,
              "tracker: continuation.max_continued_frames > 0 needs align_patches");
}

namespace {

FeatureSet SelectFeatures(const FeatureSet& detected, const cv::Size& image_size,
                          const cv::Mat* gray, const TrackerOptions& options) {
  // Keep the max_features strongest (by response, then the deterministic SortByResponse order)
  // without reordering the input.
  std::vector<size_t> usable;
  for (size_t i = 0; i < detected.size(); ++i) {
    if (detected[i].response >= options.min_response && PatchFits(detected[i], image_size) &&
        (options.min_window_eigenvalue <= 0 ||
         WindowMinEigenvalue(*gray, detected[i].Position(), kPatchSize) >=
             options.min_window_eigenvalue)) {
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

}  // namespace

FeatureSet SelectTrackableFeatures(const FeatureSet& detected, const cv::Mat& gray,
                                   const TrackerOptions& options) {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "tracker: frames must be non-empty 8-bit single-channel images");
  return SelectFeatures(detected, gray.size(), &gray, options);
}

FeatureSet SelectTrackableFeatures(const FeatureSet& detected, const cv::Size& image_size,
                                   const TrackerOptions& options) {
  COMIC_CHECK(options.min_window_eigenvalue <= 0, kInvalidArgument,
              "tracker: min_window_eigenvalue needs the image (SelectTrackableFeatures(detected, "
              "gray, options))");
  return SelectFeatures(detected, image_size, nullptr, options);
}

namespace {

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
  SearchRegions search_to_frame;
  ImagePyramid pyramid;
  if (options_.align_patches) pyramid = ImagePyramid(gray, options_.continuation.alignment.levels);
  std::vector<PatchAlignment> aligned;  // of frame − 1's features into this frame
  for (int gap = 1; gap <= options_.match_window && gap <= frame; ++gap) {
    const int earlier = frame - gap;
    const bool verify = options_.verify_min_gap > 0 && gap >= options_.verify_min_gap;
    // The earlier frame matched to this one as given (gray2, features2, coarse2), or turned by
    // 180°: the mutual best matches, and those accepted (cost threshold, then the epipolar
    // verification on the features as stored, whose indices the turned ones share).
    auto match = [&](const cv::Mat& gray2, const FeatureSet& features2, const PatchSet& patches2,
                     const CoarseFrame& coarse2, bool is_turned, std::vector<PatchMatch>* mutual,
                     std::vector<PatchMatch>* accepted) {
      SearchRegions search =
          PredictSearchRegions(earlier, gray2, features2, coarse2, accepted_to_frame, is_turned);
      if (gap == 1 && !is_turned && options_.align_patches) {
        aligned = AlignFeatures(features_[earlier], pyramids_[earlier], pyramid, search, {},
                                options_.continuation.alignment);
        search = GuidedSearchRegions(features_[earlier], search, options_.matcher.radius, aligned,
                                     options_.continuation);
      }
      if (gap == 1 && !is_turned) search_to_frame = search;
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
  std::vector<int> runs(features.size(), 0);
  if (!aligned.empty() && !previous_pair_turned) {
    AddContinuations(gray, aligned, &features, &patches, &mutual_to_frame.front(),
                     &accepted_to_frame.front(), &runs);
  }
  next_link_.emplace_back();  // this frame's, filled below
  RecordLinks(accepted_to_frame);
  std::vector<FramePairMatches> bridges;
  if (options_.align_patches && options_.continuation.bridge_frames >= 2) {
    bridges = AddBridges(gray, pyramid, &features, &patches, &runs);
  }
  next_link_.back().assign(features.size(), {-1, -1});
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
  search_regions_.push_back(std::move(search_to_frame));
  continued_runs_.push_back(std::move(runs));
  alignments_.push_back(std::move(aligned));
  bridges_.push_back(std::move(bridges));
  pyramids_.push_back(std::move(pyramid));
  patches_.push_back(std::move(patches));
  coarse_.push_back(std::move(coarse));
  image_size_ = gray.size();
  // Frames no later frame will be matched to: free their patches.
  const int expired = frame - options_.match_window;
  if (expired >= 0) {
    patches_[expired] = PatchSet();
    coarse_[expired] = CoarseFrame();
  }
  const int unaligned = frame - std::max(1, options_.continuation.bridge_frames);
  if (unaligned >= 0) pyramids_[unaligned] = ImagePyramid();
}

void Tracker::RecordLinks(const std::vector<std::vector<PatchMatch>>& accepted_to_frame) {
  const int frame = static_cast<int>(features_.size());
  // Nearest frames last, so that a feature linked to several frames keeps the nearest.
  for (int gap = static_cast<int>(accepted_to_frame.size()); gap >= 1; --gap) {
    for (const PatchMatch& m : accepted_to_frame[gap - 1]) {
      std::pair<int, int>& next = next_link_[frame - gap][m.index1];
      if (next.first < 0 || next.first > frame) next = {frame, m.index2};
    }
  }
}

std::vector<FramePairMatches> Tracker::AddBridges(const cv::Mat& gray, const ImagePyramid& pyramid,
                                                  FeatureSet* features, PatchSet* patches,
                                                  std::vector<int>* runs) {
  const TrackContinuationOptions& options = options_.continuation;
  const int frame = static_cast<int>(features_.size());
  // The features of this frame some track holds already.
  std::vector<bool> held(features->size(), false);
  for (int earlier = std::max(0, frame - std::max(options_.match_window, options.bridge_frames));
       earlier < frame; ++earlier) {
    for (const std::pair<int, int>& next : next_link_[earlier]) {
      if (next.first == frame) held[next.second] = true;
    }
  }
  std::vector<FramePairMatches> bridges;
  for (int gap = 2; gap <= options.bridge_frames && gap <= frame; ++gap) {
    const int earlier = frame - gap;
    const FeatureSet& from = features_[earlier];
    // Where the tracks that reach this frame moved since `earlier`, and the track ends there.
    std::vector<MotionSample> samples;
    std::vector<int> ends;
    for (int k = 0; k < static_cast<int>(from.size()); ++k) {
      std::pair<int, int> at = next_link_[earlier][k];
      if (at.first < 0) {
        if (continued_runs_[earlier][k] < std::max(1, options.max_continued_frames)) {
          ends.push_back(k);
        }
        continue;
      }
      while (at.first >= 0 && at.first < frame) at = next_link_[at.first][at.second];
      if (at.first == frame) {
        samples.push_back(
            {from[k].Position(), (*features)[at.second].Position() - from[k].Position()});
      }
    }
    if (ends.empty()) continue;
    FeatureSet candidates;
    std::vector<cv::Point2f> points;
    for (int k : ends) {
      candidates.push_back(from[k]);
      points.push_back(from[k].Position());
    }
    SearchRegions start;
    start.centres = PredictFromNeighbours(points, samples, options_.velocity_neighbours,
                                          options_.velocity_neighbour_radius);
    const std::vector<PatchAlignment> aligned =
        AlignFeatures(candidates, pyramids_[earlier], pyramid, start, {}, options.alignment);
    // Best alignments first.
    std::vector<int> order;
    for (int c = 0; c < static_cast<int>(ends.size()); ++c) {
      if (IsTrusted(aligned[c], options)) order.push_back(c);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return aligned[a].residual < aligned[b].residual; });
    FramePairMatches links{earlier, frame, {}};
    FeatureSet added;
    const double radius2 = options.aligned_radius * options.aligned_radius;
    const double separation2 = options.min_separation * options.min_separation;
    for (int c : order) {
      const cv::Point2f p = aligned[c].position;
      int nearest = -1;
      double nearest_d2 = radius2;
      bool crowded = false;
      for (int i = 0; i < static_cast<int>(features->size()); ++i) {
        const cv::Point2f d = (*features)[i].Position() - p;
        const double d2 = d.dot(d);
        if (held[i]) {
          crowded = crowded || d2 <= separation2;
          continue;
        }
        if ((*runs)[i] == 0 && d2 <= nearest_d2) {
          nearest_d2 = d2;
          nearest = i;
        }
      }
      const int k = ends[c];
      if (nearest >= 0) {
        links.matches.push_back({k, nearest, aligned[c].residual});
        held[nearest] = true;
      } else if (!crowded && continued_runs_[earlier][k] + gap <= options.max_continued_frames) {
        Feature moved = from[k];
        const cv::Point2f shift = p - moved.Position();
        moved.x = p.x;
        moved.y = p.y;
        for (cv::Point2f& q : moved.curve) q += shift;
        const int index = static_cast<int>(features->size());
        features->push_back(moved);
        added.push_back(moved);
        runs->push_back(continued_runs_[earlier][k] + gap);
        held.push_back(true);
        links.matches.push_back({k, index, aligned[c].residual});
      }
    }
    patches->Append(gray, added);
    if (links.matches.empty()) continue;
    std::sort(links.matches.begin(), links.matches.end(),
              [](const PatchMatch& a, const PatchMatch& b) { return a.index1 < b.index1; });
    for (const PatchMatch& m : links.matches) next_link_[earlier][m.index1] = {frame, m.index2};
    bridges.push_back(std::move(links));
  }
  return bridges;
}

void Tracker::AddContinuations(const cv::Mat& gray, const std::vector<PatchAlignment>& aligned,
                               FeatureSet* features, PatchSet* patches,
                               std::vector<PatchMatch>* mutual, std::vector<PatchMatch>* accepted,
                               std::vector<int>* runs) const {
  const int previous = static_cast<int>(features_.size()) - 1;
  const std::vector<Continuation> continued =
      ContinueUnmatched(features_[previous], continued_runs_[previous], *features, *accepted,
                        aligned, options_.continuation);
  // A continued feature's match replaces its mutual-best match above the threshold, if any.
  std::vector<bool> is_continued(features_[previous].size(), false);
  for (const Continuation& c : continued) is_continued[c.index1] = true;
  mutual->erase(std::remove_if(mutual->begin(), mutual->end(),
                               [&](const PatchMatch& m) { return is_continued[m.index1]; }),
                mutual->end());
  FeatureSet added;
  for (const Continuation& c : continued) {
    const PatchMatch match{c.index1, static_cast<int>(features->size() + added.size()), c.residual};
    mutual->push_back(match);
    accepted->push_back(match);
    runs->push_back(continued_runs_[previous][c.index1] + 1);
    added.push_back(c.feature);
  }
  patches->Append(gray, added);
  features->insert(features->end(), added.begin(), added.end());
  const auto by_index1 = [](const PatchMatch& a, const PatchMatch& b) {
    return a.index1 < b.index1;
  };
  std::sort(mutual->begin(), mutual->end(), by_index1);
  std::sort(accepted->begin(), accepted->end(), by_index1);
}

TrackingResult Tracker::Result() const {
  TrackingResult result;
  result.tracks.detector_name = detector_name_;
  result.tracks.image_size = image_size_;
  const bool any_name =
      std::any_of(names_.begin(), names_.end(), [](const std::string& n) { return !n.empty(); });
  if (any_name) result.tracks.frame_names = names_;
  result.tracks.features = features_;
  for (const std::vector<int>& runs : continued_runs_) {
    std::vector<uint8_t> flags(runs.size());
    for (size_t k = 0; k < runs.size(); ++k) flags[k] = runs[k] > 0 ? 1 : 0;
    result.continued.push_back(std::move(flags));
  }
  for (int frame2 = 1; frame2 < static_cast<int>(features_.size()); ++frame2) {
    for (int gap = 1; gap <= static_cast<int>(mutual_[frame2].size()); ++gap) {
      if (gap == 1) {
        result.mutual_matches.push_back(mutual_[frame2][0]);
        result.accepted_matches.push_back(accepted_[frame2][0]);
        result.search_regions.push_back(search_regions_[frame2]);
        if (options_.align_patches) result.alignments.push_back(alignments_[frame2]);
      } else {
        result.window_mutual_matches.push_back({frame2 - gap, frame2, mutual_[frame2][gap - 1]});
        result.window_accepted_matches.push_back(
            {frame2 - gap, frame2, accepted_[frame2][gap - 1]});
      }
    }
  }
  for (const std::vector<FramePairMatches>& bridges : bridges_) {
    for (const FramePairMatches& pair : bridges) {
      result.window_mutual_matches.push_back(pair);
      result.window_accepted_matches.push_back(pair);
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
                             const TrackerOptions& options, const TrackingProgress& progress,
                             const DetectionFilter& filter) {
  Tracker tracker(options, detector.Name(), &detector);
  for (size_t i = 0; i < sequence.NumFrames(); ++i) {
    const io::Frame frame = sequence.ReadFrame(i);
    FeatureSet detected = detector.Detect(frame.gray);
    if (filter) detected = filter(static_cast<int>(i), std::move(detected));
    tracker.AddFrame(frame.gray, SelectTrackableFeatures(detected, frame.gray, options),
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
                     SelectTrackableFeatures(detector.Detect(grays[i]), grays[i], options),
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
