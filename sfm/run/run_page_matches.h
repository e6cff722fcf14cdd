// The match matrix of report.html (sfm/run/run_page.h): for every two frames, how many tracks the
// mapper was given see both, as a heat map. For an image set (descriptors matched over frame
// pairs) it shows which photos were linked and which stand apart; for a video, a band along the
// diagonal that narrows where tracking broke. Frames are grouped into at most
// RunPageOptions::max_matrix_cells cells of consecutive frames, so the page stays small for long
// clips.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "frontend/matching/track.h"
#include "io/report/page_sections.h"
#include "sfm/run/detector_run.h"
#include "sfm/run/run_page_options.h"

namespace comic::sfm {

struct SharedTrackMatrix {
  int num_frames = 0;
  std::vector<int> cell_first_frames;  // per cell: its first frame, ascending from 0
  // Row-major, cells x cells: off the diagonal, the tracks seen in a frame of both cells; on it,
  // the tracks seen in two frames of the cell (0 for a cell of one frame).
  std::vector<int64_t> counts;
  int64_t At(int row, int column) const {
    return counts[static_cast<size_t>(row) * cell_first_frames.size() + column];
  }
};

// Frame f is in cell f * cells / num_frames, cells = min(num_frames, max_cells). Each track
// counts once per cell pair, however many of its frames lie in them.
SharedTrackMatrix SharedTracksBetweenFrames(const frontend::FeatureTracks& tracks, int max_cells);

// The heat map of the run's tracks; none for fewer than two frames or no tracks.
std::optional<io::PageSection> MatchMatrixSection(const DetectorRun& run,
                                                  const RunPageOptions& options);

}  // namespace comic::sfm
