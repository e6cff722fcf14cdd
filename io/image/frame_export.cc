#include "io/image/frame_export.h"

#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::io {

void WriteSequenceFrames(const ImageSequence& sequence, const std::string& folder,
                         const FrameExportProgress& progress) {
  COMIC_CHECK(sequence.IsVideo(), kInvalidArgument,
              sequence.path() << ": is a folder of images already; only a video's frames are "
                                 "written as images");
  EnsureWritableDirectory(folder);
  for (size_t i = 0; i < sequence.NumFrames(); ++i) {
    // In order: the sequence decodes a video forwards without seeking.
    const Frame frame = sequence.ReadFrame(i);
    WriteImageAtomically(JoinPaths(folder, frame.name), frame.color);
    if (progress) progress(i + 1, sequence.NumFrames());
  }
}

}  // namespace comic::io
