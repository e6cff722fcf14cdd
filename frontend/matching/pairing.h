// Which frame pairs are matched: consecutive frames of a video, a window of later frames, or every
// pair of an image set (as COLMAP's sequential and exhaustive matchers), and the `auto` choice
// between them from the frames themselves; and how (FeatureMatcher: the patch tracker for video,
// descriptors for image sets).
//
//   Pairing requested = ParsePairing("auto");        // or "sequential", "exhaustive", "window:8"
//   PairingChoice choice = ChoosePairing(ThumbnailsOf(sequence), requested);
//   TrackerOptions tracker = TrackerOptionsForPairing(choice.chosen, sequence.NumFrames(), base);
//
// `auto` tells a video from an image set by how alike the frames look (tiny grey thumbnails,
// normalised cross-correlation): in a video every frame looks much more like the next one than
// like the frames in general. It is a video when every step overlaps strongly (the 10th
// percentile of the consecutive similarities >= min_consecutive_similarity) and the order shows,
// by either of
//   gain = (median similarity of consecutive frames − median of the frames at least 2 apart)
//          / (1 − median of the frames at least 2 apart) >= min_gain
// (1 when consecutive thumbnails are identical, 0 when they are no more alike than any two; long
// videos), or
//   the fraction of consecutive frames that are mutual near neighbours (each among the other's
//   max(2, min(3, (n − 1) / 4)) most similar frames) >= min_neighbour_fraction (short clips, where
//   the frames 2 apart are still alike).
// Measured, 32 px thumbnails (10th percentile / gain / neighbours): KITTI 06 frames 0–50
// 0.70 / 0.73 / 100 %; the bundled 12 KITTI frames 0.77 / 0.57 / 100 %; the dino ring
// 0.85 / 0.83 / 100 %; VOT car1 0.80 / 0.74 / –: videos. The temple sparse ring 0.67 / 0.44 /
// 73 % (its file order jumps across the ring); Herz-Jesu-P8 0.21 / 0.38 (steps of 2–3 m): sets.
// Deterministic: a function of the frames and the options only.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/matching/image_set_matching.h"
#include "frontend/matching/tracker.h"

namespace comic::io {
class ImageSequence;
}

namespace comic::frontend {

enum class PairingMode { kAuto, kSequential, kWindow, kExhaustive };

struct Pairing {
  PairingMode mode = PairingMode::kAuto;
  int window = 0;  // kWindow: each frame is matched to the next `window` frames (>= 1)
};

// "auto", "sequential", "exhaustive", "window:K" (K >= 1). Throws comic::Error(kInvalidArgument)
// naming the value and the valid forms.
Pairing ParsePairing(const std::string& text);
// The inverse of ParsePairing.
std::string PairingName(const Pairing& pairing);

struct PairingChoiceOptions {
  // Height of the thumbnails compared (pixels; the width keeps the aspect ratio).
  int thumbnail_height = 32;
  // The thresholds of the video test (see the top of the file for the measured values).
  double min_gain = 0.6;
  double min_consecutive_similarity = 0.5;
  double min_neighbour_fraction = 0.9;
  // An image set of more frames than this is matched with a window of `image_set_window`
  // frames instead of all pairs (the cost of all pairs grows with the square of the frames; an
  // image set is matched by descriptors, docs/descriptors.md gives the cost of 100 frames).
  int max_exhaustive_frames = 200;
  int image_set_window = 20;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

struct PairingChoice {
  Pairing requested;
  Pairing chosen;         // never kAuto
  bool measured = false;  // the similarities below were computed (requested kAuto, >= 3 frames)
  bool looks_like_video = false;
  double consecutive_similarity_median = 0.0;
  double consecutive_similarity_p10 = 0.0;
  double other_similarity_median = 0.0;  // frames at least 2 apart
  double gain = 0.0;
  double neighbour_fraction = 0.0;  // consecutive frames that are mutual near neighbours
  std::string reason;               // one line: why this pairing
};

// A grey frame's thumbnail for ChoosePairing: `height` pixels high (area averaging), zero mean,
// unit variance, CV_64F. A uniform frame gives zeros.
cv::Mat MakeThumbnail(const cv::Mat& gray, int height);
// Normalised cross-correlation of two thumbnails of one size, in [−1, 1].
double ThumbnailSimilarity(const cv::Mat& a, const cv::Mat& b);
// The thumbnails of every frame of `sequence` (reads each frame once).
std::vector<cv::Mat> ThumbnailsOf(const io::ImageSequence& sequence,
                                  const PairingChoiceOptions& options = {});

// The pairing for frames with these thumbnails: `requested` itself unless it is kAuto; kAuto
// gives kSequential for a video, otherwise kExhaustive (kWindow with image_set_window beyond
// max_exhaustive_frames). Fewer than 3 frames: kSequential (every pair is consecutive).
PairingChoice ChoosePairing(const std::vector<cv::Mat>& thumbnails, const Pairing& requested,
                            const PairingChoiceOptions& options = {});

// `base` (the video defaults) set up for `pairing` (not kAuto) over `num_frames` frames:
//   kSequential  base unchanged (frame i to i + 1 only);
//   kWindow K    match_window K (at most num_frames − 1), the pairs beyond the next frame
//                verified (verify_min_gap 2);
//   kExhaustive  every pair (match_window num_frames − 1), every pair verified, each also
//                matched with the later frame turned by 180° (views stored upside down), and
//                the coarse-to-fine prediction with a 200 px coarse radius and a 40 px search
//                radius (neighbours of an image set are hundreds of pixels apart), and the SSD
//                threshold 800 (wide baselines change the patches; docs/sfm.md, the temple ring
//                and Herz-Jesu).
TrackerOptions TrackerOptionsForPairing(const Pairing& pairing, int num_frames,
                                        TrackerOptions base);

// How the chosen frame pairs are matched (--matcher): the patch tracker (video: frames near each
// other, frontend/matching/tracker.h) or descriptors (image sets: views far apart, turned, in any
// order; frontend/matching/image_set_matching.h).
enum class FeatureMatcher { kAuto, kPatches, kDescriptors };

// "auto", "patches", "descriptors"; Parse throws comic::Error(kInvalidArgument) listing them.
const char* FeatureMatcherName(FeatureMatcher matcher);
FeatureMatcher ParseFeatureMatcher(const std::string& name);

// Whether `choice` is matched by descriptors: kDescriptors always, kPatches never, kAuto for a
// video (IsVideo; an image set keeps the patch tracker's image-set set-up, docs/matching.md).
bool MatchesByDescriptors(FeatureMatcher matcher, const PairingChoice& choice);

// The frames are in time order (a video, or the folder of its frames): the pairing chosen is
// sequential, or a window of frames was asked for (auto picks a window only for a large image
// set).
bool IsVideo(const PairingChoice& choice);

// The frames after each frame that a video matched by descriptors pairs it with (COLMAP's
// sequential matcher's default overlap), besides those 2^k after it.
inline constexpr int kSequentialDescriptorWindow = 10;

// The descriptor matching of `choice` (not kAuto): every pair for kExhaustive, the next K frames
// for kWindow K, the next kSequentialDescriptorWindow frames and those 2^k after each frame for
// kSequential; the features selected as `tracker` selects them
// (min_response, max_features); `num_threads` threads.
ImageSetMatchingOptions ImageSetMatchingOptionsForPairing(const Pairing& pairing,
                                                          const TrackerOptions& tracker,
                                                          int num_threads);

}  // namespace comic::frontend
