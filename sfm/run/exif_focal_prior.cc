#include "sfm/run/exif_focal_prior.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/image/exif_focal.h"
#include "io/report/number_text.h"

namespace comic::sfm {
namespace {

// Up to `count` frame indices from the first to the last, evenly spread.
std::vector<size_t> SpreadFrames(size_t num_frames, size_t count) {
  std::vector<size_t> frames;
  if (num_frames == 0 || count == 0) return frames;
  const size_t taken = std::min(num_frames, count);
  for (size_t k = 0; k < taken; ++k) {
    const size_t frame = taken == 1 ? 0 : k * (num_frames - 1) / (taken - 1);
    if (frames.empty() || frames.back() != frame) frames.push_back(frame);
  }
  return frames;
}

struct FrameFocal {
  std::string name;
  io::ExifFocalPixels focal;
};

std::string Pixels(double focal_px) { return io::NumberText("%.1f", focal_px) + " px"; }

}  // namespace

ExifFocalPrior FindExifFocalPrior(const io::ImageSequence& sequence,
                                  const ExifFocalPriorOptions& options) {
  ExifFocalPrior prior;
  if (sequence.IsVideo()) return prior;
  const cv::Size size = sequence.SourceFrameSize();
  const double max_size = std::max(size.width, size.height);
  std::vector<FrameFocal> focals;
  for (const size_t i : SpreadFrames(sequence.NumFrames(), options.max_frames)) {
    ++prior.frames_read;
    const std::optional<io::ExifFocal> exif = io::ReadJpegExifFocal(sequence.FramePath(i));
    if (!exif) continue;
    const std::optional<io::ExifFocalPixels> focal =
        io::ExifFocalInPixels(*exif, size.width, size.height);
    if (focal) focals.push_back({sequence.FrameNames()[i], *focal});
  }
  prior.frames_with_focal = focals.size();
  if (focals.empty()) return prior;
  const FrameFocal& first = focals.front();
  const double f = first.focal.focal_px;
  if (!(f >= options.min_focal_factor * max_size && f <= options.max_focal_factor * max_size)) {
    prior.description = "EXIF " + first.focal.from + " in " + first.name + " gives " + Pixels(f) +
                        ", not a plausible focal length for " + std::to_string(size.width) + "x" +
                        std::to_string(size.height) + " frames";
    return prior;
  }
  for (const FrameFocal& other : focals) {
    if (std::abs(other.focal.focal_px - f) > options.max_disagreement * f) {
      prior.description = "EXIF focal lengths disagree: " + Pixels(f) + " (" + first.name +
                          ") and " + Pixels(other.focal.focal_px) + " (" + other.name + ")";
      return prior;
    }
  }
  prior.focal_px = f;
  prior.description = "EXIF " + first.focal.from + " in " + first.name + ", " +
                      std::to_string(focals.size()) + " of " + std::to_string(prior.frames_read) +
                      " frames read agree";
  return prior;
}

}  // namespace comic::sfm
