// The pictures of the clip in report.html (sfm/run/run_page.h): a few frames with their features
// and tracks drawn (boundary / interior colours with --masks or --regions), among them the first
// frame no model holds, and a strip of thumbnails spread over the clip. Each frame is read once,
// in order (a video is decoded forward, never seeked).
#pragma once

#include <string>
#include <vector>

#include "io/report/page_sections.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/run_inputs.h"
#include "sfm/run/run_page_options.h"

namespace comic::sfm {

struct RunFramePictures {
  std::vector<io::PageImage> tracks;        // frames with their tracks
  std::vector<io::PageLegendEntry> legend;  // what the colours on them mean
  std::vector<io::PageImage> thumbnails;    // unregistered frames framed in red
  std::string thumbnails_note;
};

// The frames drawn with tracks: spread over the clip (late enough to show some history), one of
// them the first unregistered frame when there is one; ascending, at most `count`.
std::vector<int> TrackFramesToDraw(int num_frames, int count, const std::vector<int>& unregistered);

// The frames of the thumbnail strip: all when there are at most `count`, else `count` spread
// evenly from the first to the last.
std::vector<int> ThumbnailFrames(int num_frames, int count);

RunFramePictures RunFramePicturesOf(const DetectorRun& run, const RunInputs& inputs,
                                    const RunPageOptions& options);

}  // namespace comic::sfm
