// The prior focal length a folder of photos states in its EXIF (io/image/exif_focal.h), for the
// run without --intrinsics: a few frames spread over the sequence are read, and their focal
// lengths in pixels (as COLMAP computes them) must agree within 1 %; frames without EXIF are
// skipped. A video, frames without a focal in their EXIF, or frames that disagree give none, and
// the run keeps COLMAP's guess of 1.2 max(w, h).
//
//   ExifFocalPrior exif = FindExifFocalPrior(sequence);
//   if (exif.focal_px) ...  // at sequence.SourceFrameSize(); exif.description says from what
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "io/image/image_sequence.h"

namespace comic::sfm {

struct ExifFocalPrior {
  // The agreed focal length in pixels at the frames' stored size (SourceFrameSize).
  std::optional<double> focal_px;
  // How it was found ("FocalLengthIn35mmFilm 28 mm in 000000.jpg, 8 of 8 frames read agree"),
  // or why there is none when some frame had a focal ("EXIF focal lengths disagree: ...").
  // Empty when no frame read had an EXIF focal.
  std::string description;
  size_t frames_read = 0;
  size_t frames_with_focal = 0;
};

struct ExifFocalPriorOptions {
  size_t max_frames = 8;           // frames read, spread evenly from the first to the last
  double max_disagreement = 0.01;  // relative to the first frame's focal
  double min_focal_factor = 0.01;  // plausible focal lengths, times max(w, h)
  double max_focal_factor = 100.0;
};

// The EXIF focal prior of `sequence`'s frames (none for a video). Never throws for bad EXIF.
ExifFocalPrior FindExifFocalPrior(const io::ImageSequence& sequence,
                                  const ExifFocalPriorOptions& options = {});

}  // namespace comic::sfm
