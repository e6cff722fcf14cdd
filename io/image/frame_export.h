// The frames of a video as image files, so that COLMAP's image tools (image_undistorter, the GUI)
// find the images a model or database made from the video names (issue 17): each selected frame
// is written once, as decoded (and resized, as the model saw it), as a lossless PNG named as
// ImageSequence::FrameNames() names it ("frame_000123.png").
//
//   io::StagedFolder frames(out_dir + "/images");
//   io::WriteSequenceFrames(sequence, frames.path());
//   frames.Commit();
#pragma once

#include <functional>
#include <string>

#include "io/image/image_sequence.h"

namespace comic::io {

// Called after each frame written with (frames written, frames in all).
using FrameExportProgress = std::function<void(size_t frames_done, size_t num_frames)>;

// Writes every selected frame of `sequence` (a video; a folder's frames are image files already)
// as `folder`/FrameNames()[i], a PNG of frame.color, each file atomically. Creates `folder`.
// Throws comic::Error: kInvalidArgument for a sequence that is not a video, kIo naming the file
// that cannot be written, kInvalidData for a frame that does not decode.
void WriteSequenceFrames(const ImageSequence& sequence, const std::string& folder,
                         const FrameExportProgress& progress = {});

}  // namespace comic::io
