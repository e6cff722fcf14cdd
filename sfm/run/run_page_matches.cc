#include "sfm/run/run_page_matches.h"

#include <algorithm>
#include <string>
#include <utility>

#include "io/report/page_distributions.h"

namespace comic::sfm {

namespace {

// The cells a track passes through (ascending, as its frames are), each with how many of the
// track's frames lie in it.
std::vector<std::pair<int, int>> CellsOfTrack(const frontend::Track& track,
                                              const std::vector<int>& cell_of_frame) {
  std::vector<std::pair<int, int>> cells;
  for (const frontend::TrackObservation& obs : track.observations) {
    if (obs.frame < 0 || obs.frame >= static_cast<int>(cell_of_frame.size())) continue;
    const int cell = cell_of_frame[obs.frame];
    if (!cells.empty() && cells.back().first == cell) {
      ++cells.back().second;
    } else {
      cells.emplace_back(cell, 1);
    }
  }
  return cells;
}

}  // namespace

SharedTrackMatrix SharedTracksBetweenFrames(const frontend::FeatureTracks& tracks, int max_cells) {
  SharedTrackMatrix matrix;
  matrix.num_frames = static_cast<int>(tracks.NumFrames());
  const int cells = std::min(matrix.num_frames, std::max(1, max_cells));
  if (cells <= 0) return matrix;
  std::vector<int> cell_of_frame(matrix.num_frames);
  for (int f = 0; f < matrix.num_frames; ++f) {
    cell_of_frame[f] = static_cast<int>(static_cast<int64_t>(f) * cells / matrix.num_frames);
    if (f == 0 || cell_of_frame[f] != cell_of_frame[f - 1]) matrix.cell_first_frames.push_back(f);
  }
  const size_t n = matrix.cell_first_frames.size();
  matrix.counts.assign(n * n, 0);
  for (const frontend::Track& track : tracks.tracks) {
    const std::vector<std::pair<int, int>> passed = CellsOfTrack(track, cell_of_frame);
    for (size_t a = 0; a < passed.size(); ++a) {
      const size_t row = passed[a].first;
      if (passed[a].second >= 2) ++matrix.counts[row * n + row];
      for (size_t b = a + 1; b < passed.size(); ++b) {
        const size_t column = passed[b].first;
        ++matrix.counts[row * n + column];
        ++matrix.counts[column * n + row];
      }
    }
  }
  return matrix;
}

std::optional<io::PageSection> MatchMatrixSection(const DetectorRun& run,
                                                  const RunPageOptions& options) {
  const frontend::FeatureTracks& tracks = run.run.tracks;
  if (tracks.NumFrames() < 2 || tracks.tracks.empty()) return std::nullopt;
  const SharedTrackMatrix matrix = SharedTracksBetweenFrames(tracks, options.max_matrix_cells);
  io::HeatMap map;
  map.title = "Tracks shared between frames";
  map.value_label = "shared tracks";
  map.num_frames = matrix.num_frames;
  map.cell_first_frames = matrix.cell_first_frames;
  map.values = matrix.counts;
  const bool grouped = static_cast<int>(matrix.cell_first_frames.size()) < matrix.num_frames;
  map.note =
      std::string(run.run.image_set_matching
                      ? "The tracks built from the verified matches of every frame pair matched: "
                      : "The tracks the tracker built: ") +
      "a cell counts the tracks seen in both its frames (the mapper's input, before any was "
      "triangulated). " +
      (grouped ? "The " + std::to_string(matrix.num_frames) + " frames are grouped into " +
                     std::to_string(matrix.cell_first_frames.size()) +
                     " cells of consecutive frames; a track counts once per cell pair, and on "
                     "the diagonal when it links two frames of one cell."
               : std::string("The diagonal is empty: a frame shares nothing with itself."));
  return io::HeatMapSection(map);
}

}  // namespace comic::sfm
