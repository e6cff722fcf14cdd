#include "frontend/matching/pairing.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "io/core/error.h"
#include "io/image/image_sequence.h"

namespace comic::frontend {
namespace {

constexpr const char* kValidForms = "auto, sequential, exhaustive or window:K with K >= 1";

// The value at fraction q of the sorted values (nearest rank); 0 for none.
double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(q * (values.size() - 1) + 0.5));
  return values[k];
}

}  // namespace

Pairing ParsePairing(const std::string& text) {
  if (text == "auto") return {PairingMode::kAuto, 0};
  if (text == "sequential") return {PairingMode::kSequential, 0};
  if (text == "exhaustive") return {PairingMode::kExhaustive, 0};
  const std::string prefix = "window:";
  if (text.compare(0, prefix.size(), prefix) == 0) {
    const std::string number = text.substr(prefix.size());
    size_t used = 0;
    long window = 0;
    try {
      window = std::stol(number, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    COMIC_CHECK(!number.empty() && used == number.size() && window >= 1 && window <= 100000,
                kInvalidArgument,
                "--matching: bad window in '" << text << "' (expected " << kValidForms << ")");
    return {PairingMode::kWindow, static_cast<int>(window)};
  }
  throw Error(ErrorKind::kInvalidArgument,
              "--matching: unknown pairing '" + text + "' (expected " + kValidForms + ")");
}

std::string PairingName(const Pairing& pairing) {
  switch (pairing.mode) {
    case PairingMode::kAuto:
      return "auto";
    case PairingMode::kSequential:
      return "sequential";
    case PairingMode::kExhaustive:
      return "exhaustive";
    case PairingMode::kWindow:
      return "window:" + std::to_string(pairing.window);
  }
  return "auto";
}

void PairingChoiceOptions::Check() const {
  COMIC_CHECK(thumbnail_height >= 4 && thumbnail_height <= 1024, kInvalidArgument,
              "pairing: thumbnail_height must be in [4, 1024], got " << thumbnail_height);
  COMIC_CHECK(min_gain > 0.0 && min_gain < 1.0, kInvalidArgument,
              "pairing: min_gain must be in (0, 1), got " << min_gain);
  COMIC_CHECK(
      min_consecutive_similarity > -1.0 && min_consecutive_similarity < 1.0, kInvalidArgument,
      "pairing: min_consecutive_similarity must be in (-1, 1), got " << min_consecutive_similarity);
  COMIC_CHECK(min_neighbour_fraction > 0.0 && min_neighbour_fraction <= 1.0, kInvalidArgument,
              "pairing: min_neighbour_fraction must be in (0, 1], got " << min_neighbour_fraction);
  COMIC_CHECK(max_exhaustive_frames >= 2, kInvalidArgument,
              "pairing: max_exhaustive_frames must be >= 2, got " << max_exhaustive_frames);
  COMIC_CHECK(image_set_window >= 1, kInvalidArgument,
              "pairing: image_set_window must be >= 1, got " << image_set_window);
}

cv::Mat MakeThumbnail(const cv::Mat& gray, int height) {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "thumbnail: expected a non-empty 8-bit single-channel image");
  COMIC_CHECK(height >= 1, kInvalidArgument, "thumbnail: height must be >= 1");
  const int width = std::max(
      1, static_cast<int>(std::lround(gray.cols * static_cast<double>(height) / gray.rows)));
  cv::Mat small;
  cv::resize(gray, small, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  cv::Mat thumbnail;
  small.convertTo(thumbnail, CV_64F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(thumbnail, mean, stddev);
  thumbnail -= mean[0];
  if (stddev[0] > 1e-9) thumbnail /= stddev[0];
  return thumbnail;
}

double ThumbnailSimilarity(const cv::Mat& a, const cv::Mat& b) {
  COMIC_CHECK(a.size() == b.size() && a.type() == CV_64F && b.type() == CV_64F, kInvalidArgument,
              "thumbnail similarity: thumbnails differ in size or type");
  return a.dot(b) / static_cast<double>(a.total());
}

std::vector<cv::Mat> ThumbnailsOf(const io::ImageSequence& sequence,
                                  const PairingChoiceOptions& options) {
  options.Check();
  std::vector<cv::Mat> thumbnails;
  thumbnails.reserve(sequence.NumFrames());
  for (size_t i = 0; i < sequence.NumFrames(); ++i) {
    thumbnails.push_back(MakeThumbnail(sequence.ReadFrame(i).gray, options.thumbnail_height));
  }
  return thumbnails;
}

PairingChoice ChoosePairing(const std::vector<cv::Mat>& thumbnails, const Pairing& requested,
                            const PairingChoiceOptions& options) {
  options.Check();
  COMIC_CHECK(requested.mode != PairingMode::kWindow || requested.window >= 1, kInvalidArgument,
              "pairing: window must be >= 1, got " << requested.window);
  PairingChoice choice;
  choice.requested = requested;
  if (requested.mode != PairingMode::kAuto) {
    choice.chosen = requested;
    choice.reason = "requested";
    return choice;
  }
  const int n = static_cast<int>(thumbnails.size());
  if (n < 3) {
    choice.chosen = {PairingMode::kSequential, 0};
    choice.reason = "fewer than 3 frames: every pair is consecutive";
    return choice;
  }
  std::vector<double> consecutive, other;
  for (int i = 0; i + 1 < n; ++i) {
    consecutive.push_back(ThumbnailSimilarity(thumbnails[i], thumbnails[i + 1]));
  }
  // The frames in general: all pairs at least 2 apart, rows sampled evenly for long videos so
  // that the cost stays about 100 rows × n comparisons.
  const int row_step = std::max(1, (n + 99) / 100);
  for (int i = 0; i < n; i += row_step) {
    for (int j = 0; j < n; ++j) {
      if (std::abs(i - j) >= 2) other.push_back(ThumbnailSimilarity(thumbnails[i], thumbnails[j]));
    }
  }
  // Consecutive frames that are each other's near neighbours: frame i + 1 among the `rank` most
  // similar frames to frame i and frame i among those to frame i + 1 (rows sampled as above).
  // (a frame of a video has two neighbours, each may be the nearer)
  const int rank = std::max(2, std::min(3, (n - 1) / 4));
  int neighbour_pairs = 0, pairs_checked = 0;
  auto rank_of = [&](int i, int k) {
    const double s = ThumbnailSimilarity(thumbnails[i], thumbnails[k]);
    int better = 0;
    for (int j = 0; j < n; ++j) {
      if (j != i && j != k && ThumbnailSimilarity(thumbnails[i], thumbnails[j]) > s) ++better;
    }
    return better + 1;
  };
  for (int i = 0; i + 1 < n; i += row_step) {
    ++pairs_checked;
    if (rank_of(i, i + 1) <= rank && rank_of(i + 1, i) <= rank) ++neighbour_pairs;
  }
  choice.measured = true;
  choice.neighbour_fraction = static_cast<double>(neighbour_pairs) / pairs_checked;
  choice.consecutive_similarity_median = Quantile(consecutive, 0.5);
  choice.consecutive_similarity_p10 = Quantile(consecutive, 0.1);
  choice.other_similarity_median = Quantile(other, 0.5);
  const double headroom = std::max(1e-9, 1.0 - choice.other_similarity_median);
  choice.gain = (choice.consecutive_similarity_median - choice.other_similarity_median) / headroom;
  choice.looks_like_video =
      choice.consecutive_similarity_p10 >= options.min_consecutive_similarity &&
      (choice.gain >= options.min_gain ||
       choice.neighbour_fraction >= options.min_neighbour_fraction);
  std::ostringstream reason;
  reason.precision(2);
  reason << std::fixed << "consecutive frames' thumbnails: median similarity "
         << choice.consecutive_similarity_median << " (10th percentile "
         << choice.consecutive_similarity_p10 << ") against " << choice.other_similarity_median
         << " for frames 2 or more apart, gain " << choice.gain << "; "
         << std::lround(100.0 * choice.neighbour_fraction)
         << " % of consecutive frames are near neighbours";
  if (choice.looks_like_video) {
    choice.chosen = {PairingMode::kSequential, 0};
    reason << ": a video";
  } else if (n <= options.max_exhaustive_frames) {
    choice.chosen = {PairingMode::kExhaustive, 0};
    reason << ": an image set";
  } else {
    choice.chosen = {PairingMode::kWindow, options.image_set_window};
    reason << ": an image set of more than " << options.max_exhaustive_frames
           << " frames, matched within a window";
  }
  choice.reason = reason.str();
  return choice;
}

TrackerOptions TrackerOptionsForPairing(const Pairing& pairing, int num_frames,
                                        TrackerOptions base) {
  COMIC_CHECK(pairing.mode != PairingMode::kAuto, kInvalidArgument,
              "pairing: choose a pairing (ChoosePairing) before setting up the tracker");
  const int most = std::max(1, num_frames - 1);
  switch (pairing.mode) {
    case PairingMode::kAuto:
    case PairingMode::kSequential:
      break;
    case PairingMode::kWindow:
      COMIC_CHECK(pairing.window >= 1, kInvalidArgument,
                  "pairing: window must be >= 1, got " << pairing.window);
      base.match_window = std::min(pairing.window, most);
      // The next frame's matches are the video's; farther pairs can be chance matches across a
      // wide step, so they are checked with a fundamental matrix (docs/sfm.md, temple ring).
      if (base.match_window > 1 && base.verify_min_gap == 0) base.verify_min_gap = 2;
      break;
    case PairingMode::kExhaustive:
      base.match_window = most;
      base.verify_min_gap = 1;
      base.match_turned_180 = true;
      base.prediction = MotionPrediction::kCoarseToFine;
      base.coarse_radius = 200.0;
      base.matcher.radius = 40.0;
      // Views 10–40° apart change a 23×23 patch more than video frames do; every pair is
      // verified with a fundamental matrix, which removes the chance matches a looser threshold
      // lets in (temple ring at 640×480, harris: 5/16 views at T = 400, 16/16 at 800).
      base.matcher.max_cost = 800.0;
      break;
  }
  return base;
}

const char* FeatureMatcherName(FeatureMatcher matcher) {
  switch (matcher) {
    case FeatureMatcher::kAuto:
      return "auto";
    case FeatureMatcher::kPatches:
      return "patches";
    case FeatureMatcher::kDescriptors:
      return "descriptors";
  }
  return "auto";
}

FeatureMatcher ParseFeatureMatcher(const std::string& name) {
  for (FeatureMatcher matcher :
       {FeatureMatcher::kAuto, FeatureMatcher::kPatches, FeatureMatcher::kDescriptors}) {
    if (name == FeatureMatcherName(matcher)) return matcher;
  }
  throw Error(ErrorKind::kInvalidArgument,
              "--matcher: unknown matcher '" + name + "' (expected auto, patches or descriptors)");
}

bool MatchesByDescriptors(FeatureMatcher matcher, const PairingChoice& choice) {
  switch (matcher) {
    case FeatureMatcher::kPatches:
      return false;
    case FeatureMatcher::kDescriptors:
      return true;
    case FeatureMatcher::kAuto:
      break;
  }
  // A video by descriptors over a window of frames: every link verified, tracks that continue
  // across blurred frames (VOT car1: 238 of 252 frames against 11 by the patch tracker). An image
  // set keeps the patch tracker's image-set set-up: descriptors alone build a wrong model of the
  // Middlebury temple ring (33 degrees off; docs/matching.md).
  return IsVideo(choice);
}

bool IsVideo(const PairingChoice& choice) {
  return choice.chosen.mode == PairingMode::kSequential ||
         (choice.chosen.mode == PairingMode::kWindow &&
          choice.requested.mode == PairingMode::kWindow);
}

ImageSetMatchingOptions ImageSetMatchingOptionsForPairing(const Pairing& pairing,
                                                          const TrackerOptions& tracker,
                                                          int num_threads) {
  COMIC_CHECK(pairing.mode != PairingMode::kAuto, kInvalidArgument,
              "pairing: choose a pairing (ChoosePairing) before setting up the matching");
  ImageSetMatchingOptions options;
  switch (pairing.mode) {
    case PairingMode::kAuto:
    case PairingMode::kExhaustive:
      options.window = 0;
      break;
    case PairingMode::kWindow:
      options.window = pairing.window;
      break;
    case PairingMode::kSequential:
      // A video by descriptors is matched as COLMAP's sequential matcher does by default: each
      // frame with the next 10 and with those 2^k after it, so that tracks continue across a
      // few bad frames and the far pairs tie the trajectory together.
      options.window = kSequentialDescriptorWindow;
      options.quadratic_overlap = true;
      break;
  }
  options.min_response = tracker.min_response;
  options.max_features = tracker.max_features;
  options.num_threads = num_threads;
  options.Check();
  return options;
}

}  // namespace comic::frontend
